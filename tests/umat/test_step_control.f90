!> Step control through PNEWDT with PROPS(20) = tol > 0 (theory.md §3.6, docs/umat.md): a host that
!> cuts back on PNEWDT < 1 and grows the step by PNEWDT > 1 integrates constant-stress creep with an
!> error that falls with tol; a rejected step leaves STRESS and STATEV exactly as they came in.
!> Reference: the Radau integration of python/camclay9/reference.py (creep_mixture, Woodford,
!> theta = 30 deg, -35 MPa, jump to diag(-35, -35, -75) MPa): creep strain -1.5808987616e-04 at 3600 s.
program test_step_control
  use, intrinsic :: iso_fortran_env, only: real64, output_unit
  use test_support
  implicit none
  real(real64), parameter :: creep_radau = -1.5808987616e-04_real64, t_end = 3600
  real(real64), parameter :: tols(3) = [1e-5_real64, 1e-6_real64, 1e-7_real64]
  real(real64) :: err(3)
  integer :: steps(3), rejected(3), k

  do k = 1, 3
    call adaptive_creep(tols(k), err(k), steps(k), rejected(k))
    write (output_unit, '(a,es8.1,a,i6,a,i5,a,es10.3)') 'tol ', tols(k), ': steps ', steps(k), &
      ', rejected ', rejected(k), ', relative error of the creep strain ', err(k)
  end do
  call check_true('error falls with tol', err(2) < 0.5_real64 * err(1) .and. err(3) < 0.5_real64 * err(2))
  call check_true('steps grow with 1/tol', steps(1) < steps(2) .and. steps(2) < steps(3))
  call check_true('tol = 1e-7 within 1e-3 of Radau', err(3) < 1e-3_real64)
  call rejected_step_leaves_state()
  call calculix_convention()
  call finish('test_step_control')

contains

  subroutine adaptive_creep(tol, rel_err, nsteps, nrejected)
    real(real64), intent(in) :: tol
    real(real64), intent(out) :: rel_err
    integer, intent(out) :: nsteps, nrejected
    real(real64) :: props(23), stress(6), statev(nstatv_test), stran(6), dstran(6), d(6, 6), target(6)
    real(real64) :: t, dt, pnewdt, eps0, th
    logical :: ok
    integer :: i
    th = 30 * pi / 180
    props = props_with(0.5_real64, [sin(th), 0.0_real64, cos(th)], tol=tol)
    stress = [-35.0_real64, -35.0_real64, -35.0_real64, 0.0_real64, 0.0_real64, 0.0_real64]
    statev = 0; stran = 0; dstran = 0
    target = [-35.0_real64, -35.0_real64, -75.0_real64, 0.0_real64, 0.0_real64, 0.0_real64]
    call mixed_step(props, 6, stress, statev, stran, dstran, [(.true., i = 1, 6)], target, 0.0_real64, d, ok)
    stran = stran + dstran
    eps0 = stran(3)
    t = 0; dt = 1e-3_real64; nsteps = 0; nrejected = 0
    do while (t < t_end * (1 - 1e-14_real64))
      dt = min(dt, t_end - t)
      dstran = 0
      call mixed_step(props, 6, stress, statev, stran, dstran, [(.true., i = 1, 6)], target, dt, d, ok, pnewdt)
      if (.not. ok) then
        nrejected = nrejected + 1
        dt = dt * pnewdt
        if (nrejected > 100000) exit
        cycle
      end if
      stran = stran + dstran
      t = t + dt
      nsteps = nsteps + 1
      dt = dt * pnewdt
    end do
    rel_err = abs((stran(3) - eps0) - creep_radau) / abs(creep_radau)
  end subroutine adaptive_creep

  !> A 100 s step from the paper's start is far too coarse for tol = 1e-8: PNEWDT < 1, state untouched.
  subroutine rejected_step_leaves_state()
    real(real64) :: props(23), stress(6), statev(nstatv_test), s0(6), v0(nstatv_test), d(6, 6), pnewdt
    props = props_with(0.5_real64, [0.0_real64, 0.0_real64, 1.0_real64], tol=1e-8_real64)
    stress = [-35.0_real64, -35.0_real64, -35.0_real64, 0.0_real64, 0.0_real64, 0.0_real64]
    statev = 0; pnewdt = 1
    call call_umat(props, 6, stress, statev, [0d0, 0d0, 0d0, 0d0, 0d0, 0d0], [0d0, 0d0, -1d-4, 0d0, 0d0, 0d0], &
                   1.0_real64, d, pnewdt)
    s0 = stress; v0 = statev; pnewdt = 1
    call call_umat(props, 6, stress, statev, [0d0, 0d0, -1d-4, 0d0, 0d0, 0d0], [0d0, 0d0, -1d-4, 0d0, 0d0, 0d0], &
                   1.0e4_real64, d, pnewdt)
    write (output_unit, '(a,f6.3)') 'coarse step: PNEWDT = ', pnewdt
    call check_true('coarse step rejected', pnewdt < 1 .and. pnewdt >= 0.25_real64)
    call check_true('rejected step: STRESS unchanged', all(stress == s0))
    call check_true('rejected step: STATEV unchanged', all(statev == v0))
    call check_true('rejected step: DDSDDE finite', all(abs(d) < huge(1.0_real64)))
  end subroutine rejected_step_leaves_state

  !> CalculiX passes PNEWDT = -1 ("no request") and redoes the increment for any positive value: a
  !> rejected step must come back below 1, an accepted one must leave -1 alone (no growth advice).
  subroutine calculix_convention()
    real(real64) :: props(23), stress(6), statev(nstatv_test), d(6, 6), pnewdt, s0(6), v0(nstatv_test)
    props = props_with(0.5_real64, [0.0_real64, 0.0_real64, 1.0_real64], tol=1e-8_real64)
    stress = [-35.0_real64, -35.0_real64, -35.0_real64, 0.0_real64, 0.0_real64, 0.0_real64]
    statev = 0; pnewdt = -1
    call call_umat(props, 6, stress, statev, [0d0, 0d0, 0d0, 0d0, 0d0, 0d0], [0d0, 0d0, -1d-9, 0d0, 0d0, 0d0], &
                   1.0e-6_real64, d, pnewdt)
    call check_close('PNEWDT = -1 in, tiny accepted step: left at -1', pnewdt, -1.0_real64, 0.0_real64)
    s0 = stress; v0 = statev; pnewdt = -1
    call call_umat(props, 6, stress, statev, [0d0, 0d0, 0d0, 0d0, 0d0, 0d0], [0d0, 0d0, -1d-4, 0d0, 0d0, 0d0], &
                   1.0e4_real64, d, pnewdt)
    call check_true('PNEWDT = -1 in, rejected step: a cutback in (0, 1)', pnewdt > 0 .and. pnewdt < 1)
    call check_true('rejected step (CalculiX convention): state unchanged', all(stress == s0) .and. all(statev == v0))
  end subroutine calculix_convention

end program test_step_control
