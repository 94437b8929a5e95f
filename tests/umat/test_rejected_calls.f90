!> Rejected calls leave the state as it came in (umat-interface.md: PNEWDT < 1 with STRESS and STATEV
!> unchanged), issue 11:
!> 1. A rejected call with DROT /= I (step control, and a non-finite DSTRAN) returns STATEV
!>    bit-identical; an accepted call with the same DROT and no strain returns the stored tensors
!>    rotated, R s R^T computed here with 3 x 3 matrices (independent of the UMAT's Mandel rotation).
!> 2. DTIME < 0 and DTIME = NaN are rejected, STRESS and STATEV bit-identical; DTIME = 0 is accepted.
!> 3. NaN, +Inf and -Inf in each of STATEV 1-32 are rejected with the state bit-identical; a
!>    non-positive soft-frame pc is rejected while the soft frame is in use (phi < 1), not with phi = 1.
!> 4. An uninitialised state (STATEV(13) = 0) is started from PROPS: NaN elsewhere is not kept.
program test_rejected_calls
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan, ieee_positive_inf, &
                                           ieee_negative_inf, ieee_is_finite
  use test_support, only: props_with, call_umat, check_true, check_close, finish, nstatv_test
  implicit none
  real(real64), parameter :: zero6(6) = 0, e3(3) = [0.0_real64, 0.0_real64, 1.0_real64]
  real(real64) :: props(23), stress0(6), statev0(nstatv_test), stress(6), statev(nstatv_test)
  real(real64) :: ddsdde(6, 6), pnewdt, rot(3, 3), bad(3), expected(3, 3)
  integer :: slot, kind
  character(len=16) :: label

  ! A state with viscoplastic strain in both frames: a deviatoric start outside both surfaces
  ! (p = 26.7 MPa, q = 50 MPa; soft pc0 = 35 MPa), one compressive step of 10 s.
  props = props_with(0.5_real64, [0.6_real64, 0.0_real64, 0.8_real64])
  stress0 = [-10.0_real64, -10.0_real64, -60.0_real64, 0.0_real64, 0.0_real64, 0.0_real64]
  statev0 = 0
  pnewdt = 1
  call call_umat(props, 6, stress0, statev0, zero6, &
                 [-1.0e-4_real64, 2.0e-5_real64, -3.0e-4_real64, 4.0e-5_real64, 1.0e-5_real64, -2.0e-5_real64], &
                 10.0_real64, ddsdde, pnewdt)
  call check_true('setup: viscoplastic strain in both frames', &
                  any(statev0(7:12) /= 0) .and. any(statev0(20:25) /= 0) .and. pnewdt >= 1)

  ! A rotation of 0.3 rad about (1, 2, 2)/3 (Rodrigues), not the identity.
  rot = rotation([1.0_real64, 2.0_real64, 2.0_real64] / 3, 0.3_real64)

  ! 1a. Rejected by step control: tol = 1e-9 and a large viscoplastic step.
  props(20) = 1.0e-9_real64
  call expect_rejected('step control, DROT /= I', props, 100.0_real64, &
                       [-1.0e-3_real64, 0.0_real64, -2.0e-3_real64, 0.0_real64, 0.0_real64, 0.0_real64], rot)
  props(20) = 0
  ! 1b. Rejected as an unusable argument (issue 34; before: as a failed local solve): a NaN in DSTRAN.
  call expect_rejected('NaN DSTRAN, DROT /= I', props, 10.0_real64, &
                       [ieee_value(1.0_real64, ieee_quiet_nan), 0.0_real64, 0.0_real64, 0.0_real64, &
                        0.0_real64, 0.0_real64], rot)
  ! 1c. Accepted with the same DROT, no strain, DTIME = 0 (elastic): stored tensors rotated.
  stress = stress0; statev = statev0; pnewdt = 1
  call call_umat(props, 6, stress, statev, zero6, zero6, 0.0_real64, ddsdde, pnewdt, rot)
  expected = matmul(rot, matmul(voigt_to_matrix(statev0(1:6), 1.0_real64), transpose(rot)))
  call check_true('accepted call: hard-frame stress rotated, R s R^T', &
                  maxval(abs(voigt_to_matrix(statev(1:6), 1.0_real64) - expected)) <= 1.0e-12_real64 * 60)
  expected = matmul(rot, matmul(voigt_to_matrix(statev0(27:32), 0.5_real64), transpose(rot)))
  call check_true('accepted call: overall viscoplastic strain rotated, R e R^T', &
                  maxval(abs(voigt_to_matrix(statev(27:32), 0.5_real64) - expected)) <= &
                  1.0e-12_real64 * maxval(abs(statev0(27:32))))
  call check_close('accepted call: pc unchanged by the rotation', statev(13), statev0(13), 1.0e-15_real64)

  ! 2. DTIME.
  call expect_rejected('DTIME = -1', props, -1.0_real64, zero6)
  call expect_rejected('DTIME = -1e-300', props, -1.0e-300_real64, zero6)
  call expect_rejected('DTIME = NaN', props, ieee_value(1.0_real64, ieee_quiet_nan), zero6)
  stress = stress0; statev = statev0; pnewdt = 1
  call call_umat(props, 6, stress, statev, zero6, zero6, 0.0_real64, ddsdde, pnewdt)
  call check_true('DTIME = 0 accepted: PNEWDT untouched, state unchanged without strain', &
                  pnewdt == 1 .and. maxval(abs(stress - stress0)) <= 1.0e-12_real64 * 60)

  ! 3. Non-finite stored state, slot by slot.
  bad = [ieee_value(1.0_real64, ieee_quiet_nan), ieee_value(1.0_real64, ieee_positive_inf), &
         ieee_value(1.0_real64, ieee_negative_inf)]
  do slot = 1, 32
    do kind = 1, 3
      write (label, '(a,i0,a,i0)') 'STATEV(', slot, ') #', kind
      call expect_rejected(trim(label) // ' non-finite', props, 10.0_real64, &
                           [-1.0e-5_real64, 0.0_real64, 0.0_real64, 0.0_real64, 0.0_real64, 0.0_real64], &
                           slot=slot, value=bad(kind))
    end do
  end do
  call expect_rejected('soft-frame pc = 0 with phi = 0.5', props, 10.0_real64, zero6, slot=26, &
                       value=0.0_real64)
  call expect_rejected('soft-frame pc = -1 with phi = 0.5', props, 10.0_real64, zero6, slot=26, &
                       value=-1.0_real64)
  props(1) = 1
  stress = stress0; statev = statev0; statev(26) = 0; pnewdt = 1
  call call_umat(props, 6, stress, statev, zero6, zero6, 10.0_real64, ddsdde, pnewdt)
  call check_true('soft-frame pc = 0 accepted with phi = 1 (soft frame unused)', pnewdt == 1)
  props(1) = 0.5_real64

  ! 4. Uninitialised state with NaN in the other slots: started from PROPS, nothing non-finite kept
  !    (DTIME = 0, no strain: an elastic call, so pc stays pc0).
  stress = stress0; statev = bad(1); statev(13) = 0; pnewdt = 1
  call call_umat(props, 6, stress, statev, zero6, zero6, 0.0_real64, ddsdde, pnewdt)
  call check_true('uninitialised state: accepted, STATEV 1-32 finite', &
                  pnewdt == 1 .and. all(ieee_is_finite(statev(1:32))))
  call check_close('uninitialised state: hard pc = pc0', statev(13), props(12), 1.0e-15_real64)
  call check_true('uninitialised state: viscoplastic strains zero', &
                  all(statev(7:12) == 0) .and. all(statev(20:25) == 0) .and. all(statev(27:32) == 0))
  call finish('test_rejected_calls')

contains

  !> One call from (stress0, statev0), optionally with STATEV(slot) = value and a DROT; asserts
  !> PNEWDT < 1, STRESS and STATEV bit-identical to what was passed in, DDSDDE finite.
  subroutine expect_rejected(name, props, dtime, dstran, drot, slot, value)
    character(len=*), intent(in) :: name
    real(real64), intent(in) :: props(23), dtime, dstran(6)
    real(real64), intent(in), optional :: drot(3, 3), value
    integer, intent(in), optional :: slot
    real(real64) :: st(6), sv(nstatv_test), sv_in(nstatv_test), dd(6, 6), pn
    st = stress0
    sv = statev0
    if (present(slot)) sv(slot) = value
    sv_in = sv
    pn = 1
    call call_umat(props, 6, st, sv, zero6, dstran, dtime, dd, pn, drot)
    call check_true(name // ': rejected (PNEWDT < 1)', pn < 1)
    call check_true(name // ': STATEV bit-identical', all(transfer(sv, 1_int64, nstatv_test) == &
                                                           transfer(sv_in, 1_int64, nstatv_test)))
    call check_true(name // ': STRESS bit-identical', all(transfer(st, 1_int64, 6) == &
                                                           transfer(stress0, 1_int64, 6)))
    call check_true(name // ': DDSDDE finite', all(ieee_is_finite(dd)))
  end subroutine expect_rejected

  !> Rotation by angle about the unit axis (Rodrigues' formula).
  pure function rotation(axis, angle) result(r)
    real(real64), intent(in) :: axis(3), angle
    real(real64) :: r(3, 3), k(3, 3)
    integer :: i
    k = reshape([0.0_real64, axis(3), -axis(2), -axis(3), 0.0_real64, axis(1), &
                 axis(2), -axis(1), 0.0_real64], [3, 3])
    r = sin(angle) * k + (1 - cos(angle)) * matmul(k, k)
    do i = 1, 3
      r(i, i) = r(i, i) + 1
    end do
  end function rotation

  !> Symmetric 3 x 3 matrix of Voigt components 11, 22, 33, 12, 13, 23; shear scaled by w
  !> (1 for stresses, 1/2 for engineering shear strains).
  pure function voigt_to_matrix(v, w) result(m)
    real(real64), intent(in) :: v(6), w
    real(real64) :: m(3, 3)
    m = reshape([v(1), w * v(4), w * v(5), w * v(4), v(2), w * v(6), w * v(5), w * v(6), v(3)], [3, 3])
  end function voigt_to_matrix

end program test_rejected_calls
