!> Two rules of theory.md §3.6 checked from outside the UMAT:
!> 1. PNEWDT = clamp(0.8 sqrt(tol/err), 0.25, 1.5) with PROPS(20) = tol > 0, where err (the UMAT's error
!>    estimate of the step) does not depend on tol. err is inferred from one rejected call; then every
!>    other tol, from 1e-3 tol to 1e6 tol in steps of 10^0.1, must give the formula's value to round-off (the rejected range,
!>    the 0.25 and 1.5 clamps, and accepted steps, which the code never asks to shrink: >= 1).
!> 2. The pc floor p_floor = max(1e-6 pc0, 1e-4 MPa): a rate-independent dilatant step from tension that
!>    wants pc below the floor ends with pc exactly at the floor, with the floor flag set; a following
!>    compressive step lifts pc above the floor and clears the flag (the bound is released).
program test_pnewdt_floor
  use, intrinsic :: iso_fortran_env, only: real64, output_unit
  use test_support
  implicit none

  call pnewdt_formula()
  call pc_floor(2.0_real64, 1.0e-4_real64)           ! Woodford hard frame: 1e-6 * 2 < 1e-4
  call pc_floor(1.0e3_real64, 1.0e-3_real64)         ! pc0 = 1000 MPa: 1e-6 * pc0 = 1e-3 > 1e-4
  call finish('test_pnewdt_floor')

contains

  !> PNEWDT returned for the creep step of test_step_control (Woodford, theta = 0, -35 MPa, 100 s with
  !> a -1e-4 axial strain) with PROPS(20) = tol; STRESS/STATEV of a rejected call must be unchanged.
  real(real64) function pnewdt_for(tol) result(pnewdt)
    real(real64), intent(in) :: tol
    real(real64) :: props(23), stress(6), statev(nstatv_test), d(6, 6), s0(6), v0(nstatv_test)
    props = props_with(0.5_real64, [0.0_real64, 0.0_real64, 1.0_real64], tol=tol)
    stress = [-35.0_real64, -35.0_real64, -35.0_real64, 0.0_real64, 0.0_real64, 0.0_real64]
    statev = 0; pnewdt = 1
    call call_umat(props, 6, stress, statev, [0d0, 0d0, 0d0, 0d0, 0d0, 0d0], [0d0, 0d0, -1d-4, 0d0, 0d0, 0d0], &
                   1.0_real64, d, pnewdt)
    s0 = stress; v0 = statev; pnewdt = huge(1.0_real64)   ! as Abaqus: large on entry
    call call_umat(props, 6, stress, statev, [0d0, 0d0, -1d-4, 0d0, 0d0, 0d0], [0d0, 0d0, -1d-4, 0d0, 0d0, 0d0], &
                   100.0_real64, d, pnewdt)
    if (pnewdt < 1) call check_true('rejected step leaves the state', all(stress == s0) .and. all(statev == v0))
  end function pnewdt_for

  subroutine pnewdt_formula()
    real(real64), parameter :: tol0 = 1.0e-6_real64
    real(real64) :: p0, err, tol, got, expect
    integer :: k
    p0 = pnewdt_for(tol0)
    call check_true('PNEWDT: reference call rejected inside the clamps', p0 > 0.25_real64 .and. p0 < 0.8_real64)
    err = tol0 * (0.8_real64 / p0)**2                    ! from PNEWDT = 0.8 sqrt(tol/err)
    write (output_unit, '(a,es10.3,a,f8.5,a,es12.5)') 'tol ', tol0, ': PNEWDT ', p0, ' => err ', err
    do k = -30, 60
      tol = tol0 * 10.0_real64**(0.1_real64 * k)
      got = pnewdt_for(tol)
      expect = min(max(0.8_real64 * sqrt(tol / err), 0.25_real64), 1.5_real64)
      if (tol >= err) expect = max(expect, 1.0_real64)   ! an accepted step is never asked to shrink
      if (mod(k, 5) == 0) write (output_unit, '(a,es10.3,a,f8.5,a,f8.5)') 'tol ', tol, ': PNEWDT ', got, &
        ', formula ', expect
      call check_close('PNEWDT formula', got, expect, 1e-9_real64)
    end do
    call check_true('PNEWDT: cutback clamp 0.25 reached', pnewdt_for(tol0 * 1e-3_real64) == 0.25_real64)
    call check_true('PNEWDT: growth clamp 1.5 reached', pnewdt_for(tol0 * 1e6_real64) == 1.5_real64)
  end subroutine pnewdt_formula

  subroutine pc_floor(pc0, floor_expected)
    real(real64), intent(in) :: pc0, floor_expected
    real(real64) :: props(23), stress(6), statev(nstatv_test), d(6, 6), pnewdt
    character(len=40) :: tag
    write (tag, '(a,es8.1)') 'pc floor, pc0 = ', pc0
    ! Hard frame only (phi = 1), rate independent, from +5 MPa isotropic tension with pc = 30 MPa.
    props = props_with(1.0_real64, [0.0_real64, 0.0_real64, 1.0_real64], 0.0_real64, 0.0_real64)
    props(12) = pc0
    stress = [5.0_real64, 5.0_real64, 5.0_real64, 0.0_real64, 0.0_real64, 0.0_real64]
    statev = 0
    statev(1:3) = 5; statev(14:16) = 5; statev(13) = 30; statev(26) = 30
    pnewdt = 1
    call call_umat(props, 6, stress, statev, [0d0, 0d0, 0d0, 0d0, 0d0, 0d0], [1d-2, 1d-2, 1d-2, 0d0, 0d0, 0d0], &
                   1.0_real64, d, pnewdt)
    write (output_unit, '(a,a,es12.5,a,i0)') trim(tag), ': pc after the dilatant step ', statev(13), ', flags ', &
      int(statev(34))
    call check_true(trim(tag) // ': step accepted', pnewdt >= 1)
    call check_close(trim(tag) // ': pc at the floor', statev(13), floor_expected, 1e-12_real64 * floor_expected)
    call check_true(trim(tag) // ': floor flag set', iand(int(statev(34)), 1) == 1)
    ! Compress: the converged hardening lies above the floor, so pc leaves it and the flag clears.
    pnewdt = 1
    call call_umat(props, 6, stress, statev, [1d-2, 1d-2, 1d-2, 0d0, 0d0, 0d0], [-2d-2, -2d-2, -2d-2, 0d0, 0d0, 0d0], &
                   1.0_real64, d, pnewdt)
    write (output_unit, '(a,a,es12.5,a,i0)') trim(tag), ': pc after compression ', statev(13), ', flags ', &
      int(statev(34))
    call check_true(trim(tag) // ': released above the floor', statev(13) > 10 * floor_expected .and. &
                    iand(int(statev(34)), 1) == 0)
  end subroutine pc_floor

end program test_pnewdt_floor
