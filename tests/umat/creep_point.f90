!> One material point under constant stress (the Perzyna creep check of issue #2): both frames start
!> at -35 MPa (isotropic) with zero strain; the overall stress jumps elastically (DTIME = 0 call) to
!> diag(-35, -35, -75) MPa and is held for T seconds in N backward-Euler steps (uniform, or geometric
!> with ratio r), optionally after a hold of HOLD seconds at -35 MPa in NHOLD geometric steps (ratio
!> 1 + 20/NHOLD; default 400). Prints N, T, the creep strain eps33(T) - eps33(0+), pc_hard, pc_soft.
!> Usage: creep_point THETA_DEG T N [RATIO [HOLD [NHOLD]]]
program creep_point
  use, intrinsic :: iso_fortran_env, only: real64, output_unit, error_unit
  use test_support
  implicit none
  real(real64) :: props(23), theta, t_end, ratio, stress(6), statev(nstatv_test), stran(6), dstran(6)
  real(real64) :: target(6), d(6, 6), dt, t, eps0_33, hold, hold_ratio
  integer :: nsteps, k, hold_steps
  logical :: ok
  character(len=64) :: arg

  call get_command_argument(1, arg); read (arg, *) theta
  call get_command_argument(2, arg); read (arg, *) t_end
  call get_command_argument(3, arg); read (arg, *) nsteps
  ratio = 1
  if (command_argument_count() >= 4) then
    call get_command_argument(4, arg); read (arg, *) ratio
  end if
  hold = 0
  if (command_argument_count() >= 5) then
    call get_command_argument(5, arg); read (arg, *) hold
  end if
  hold_steps = 400
  if (command_argument_count() >= 6) then
    call get_command_argument(6, arg); read (arg, *) hold_steps
  end if
  theta = theta * pi / 180
  props = props_with(0.5_real64, [sin(theta), 0.0_real64, cos(theta)])

  stress = [-35.0_real64, -35.0_real64, -35.0_real64, 0.0_real64, 0.0_real64, 0.0_real64]
  statev = 0
  stran = 0
  target = stress
  if (hold > 0) then
    ! Hold the confinement; steps grow geometrically from 1e-3 s.
    hold_ratio = 1 + 20.0_real64 / hold_steps
    dt = hold * (hold_ratio - 1) / (hold_ratio**hold_steps - 1)
    t = 0
    do k = 1, hold_steps
      if (k == hold_steps) dt = hold - t
      dstran = 0
      call mixed_step(props, 6, stress, statev, stran, dstran, [(.true., k = 1, 6)], target, dt, d, ok)
      if (.not. ok) stop 'creep_point: hold failed'
      stran = stran + dstran
      t = t + dt
      dt = dt * hold_ratio
    end do
  end if
  target = [-35.0_real64, -35.0_real64, -75.0_real64, 0.0_real64, 0.0_real64, 0.0_real64]
  ! Elastic jump at t = 0+ (DTIME = 0), all six components under stress control.
  dstran = 0
  call mixed_step(props, 6, stress, statev, stran, dstran, [(.true., k = 1, 6)], target, 0.0_real64, d, ok)
  if (.not. ok) stop 'creep_point: elastic jump failed'
  stran = stran + dstran
  eps0_33 = stran(3)
  ! Hold: first step dt1 such that the steps sum to t_end.
  if (ratio == 1) then
    dt = t_end / nsteps
  else
    dt = t_end * (ratio - 1) / (ratio**nsteps - 1)
  end if
  t = 0
  do k = 1, nsteps
    if (k == nsteps) dt = t_end - t
    dstran = 0
    call mixed_step(props, 6, stress, statev, stran, dstran, [(.true., k = 1, 6)], target, dt, d, ok)
    if (.not. ok) then
      write (error_unit, '(a,i0,a,es12.5)') 'creep_point: step ', k, ' failed at t = ', t
      stop 1
    end if
    stran = stran + dstran
    t = t + dt
    dt = dt * ratio
  end do
  write (output_unit, '(i10,4es24.16)') nsteps, t_end, stran(3) - eps0_33, statev(13), statev(26)
end program creep_point
