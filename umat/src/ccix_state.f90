!> The UMAT's state and step policy in the Abaqus conventions (docs/umat.md "STATEV", "Time step
!> control"; umat-interface.md): the frames' stored state unpacked to Mandel vectors and packed back,
!> the rigid rotation of the stored tensors, the diagnostic flag bits, and the PNEWDT policy. The entry
!> point (umat.f90) only calls these; the layout itself (the slots) is ccix_props'.
!>
!> Re-entrant: RECURSIVE procedures (pure but for the warning of a rejected call), no module variables.
module ccix_state
  use, intrinsic :: iso_fortran_env, only: real64
  use ccix_tensor, only: stress_to_mandel, mandel_to_stress, strain_to_mandel, mandel_to_strain, &
                         rotate_mandel, mandel_w
  use ccix_props, only: is_sig_hard, is_evp_hard, is_pc_hard, is_sig_soft, is_evp_soft, is_pc_soft, &
                        is_evp_total, nstatv_min, message_len
  use ccix_tensor, only: is_finite, is_nan, first_not_finite
  use ccix_host, only: host_warning
  use ccix_frame, only: flag_floor, flag_tension, flag_fallback, flag_outrun
  use ccix_mixture, only: step_info_t, hard, soft
  implicit none
  private

  !> PNEWDT after a failed or rejected step (at most), and the largest growth asked for.
  real(real64), parameter, public :: step_cutback = 0.25_real64, step_max_growth = 1.5_real64
  integer, parameter :: sig_slot(2) = [is_sig_hard, is_sig_soft], evp_slot(2) = [is_evp_hard, is_evp_soft]

  public :: state_rotate, state_unpack, state_pack, state_flags, suggest_step, step_ratio, arguments_rejected

contains

  !> Rigid rotation of the increment (umat-interface.md): the stored stresses and viscoplastic
  !> strains rotated by DROT (the bedding normal is a material property and is not).
  pure recursive subroutine state_rotate(drot, sv)
    real(real64), intent(in) :: drot(3, 3)
    real(real64), intent(inout) :: sv(:)
    integer :: k
    do k = hard, soft
      sv(sig_slot(k):sig_slot(k) + 5) = mandel_to_stress(rotate_mandel(drot, &
                                          stress_to_mandel(sv(sig_slot(k):sig_slot(k) + 5))))
      sv(evp_slot(k):evp_slot(k) + 5) = mandel_to_strain(rotate_mandel(drot, &
                                          strain_to_mandel(sv(evp_slot(k):evp_slot(k) + 5))))
    end do
    sv(is_evp_total:is_evp_total + 5) = mandel_to_strain(rotate_mandel(drot, &
                                          strain_to_mandel(sv(is_evp_total:is_evp_total + 5))))
  end subroutine state_rotate

  !> The frames' stresses (Voigt in STATEV -> Mandel) and preconsolidation pressures.
  pure recursive subroutine state_unpack(sv, sig_n, pc_n)
    real(real64), intent(in) :: sv(:)
    real(real64), intent(out) :: sig_n(6, 2), pc_n(2)
    integer :: k
    do k = hard, soft
      sig_n(:, k) = sv(sig_slot(k):sig_slot(k) + 5) * mandel_w
    end do
    pc_n(hard) = sv(is_pc_hard)
    pc_n(soft) = sv(is_pc_soft)
  end subroutine state_unpack

  !> The end of a converged step into the stored state: the frames' stresses and pc, and, where a
  !> frame flowed, the viscoplastic strain increments added (Mandel -> engineering shear).
  pure recursive subroutine state_pack(sig_frames, pc, devp, devp_total, viscoplastic, sv)
    real(real64), intent(in) :: sig_frames(6, 2), pc(2), devp(6, 2), devp_total(6)
    logical, intent(in) :: viscoplastic
    real(real64), intent(inout) :: sv(:)
    integer :: k
    do k = hard, soft
      sv(sig_slot(k):sig_slot(k) + 5) = sig_frames(:, k) / mandel_w
    end do
    sv(is_pc_hard) = pc(hard)
    sv(is_pc_soft) = pc(soft)
    if (.not. viscoplastic) return
    do k = hard, soft
      sv(evp_slot(k):evp_slot(k) + 5) = sv(evp_slot(k):evp_slot(k) + 5) + devp(:, k) * mandel_w
    end do
    sv(is_evp_total:is_evp_total + 5) = sv(is_evp_total:is_evp_total + 5) + devp_total * mandel_w
  end subroutine state_pack

  !> The diagnostic flag bits of STATEV(34) (docs/umat.md "STATEV"): 1, 2 the hard, soft frame's pc at
  !> the floor; 4, 8 the hard, soft frame in tension (p' < 0); 16 the fallback solver was used.
  pure recursive integer function state_flags(info) result(flags)
    type(step_info_t), intent(in) :: info
    integer :: k
    flags = 0
    do k = hard, soft
      if (iand(info%flags(k), flag_floor) /= 0) flags = ior(flags, 2**(k - 1))
      if (iand(info%flags(k), flag_tension) /= 0) flags = ior(flags, 4 * 2**(k - 1))
      if (iand(info%flags(k), flag_fallback) /= 0) flags = ior(flags, 16)
      if (iand(info%flags(k), flag_outrun) /= 0) flags = ior(flags, 32 * 2**(k - 1))
    end do
  end function state_flags

  !> PNEWDT asks at most ratio of the increment. Hosts differ in what PNEWDT holds on entry: Abaqus sets
  !> it large and takes the smallest request; CalculiX passes -1 ("no request") and redoes the increment
  !> for ANY positive value, above 1 too (docs/calculix.md). So with PNEWDT <= 0 (or NaN) on entry only
  !> a cutback (< 1) is written.
  pure recursive subroutine suggest_step(pnewdt, ratio)
    real(real64), intent(inout) :: pnewdt
    real(real64), intent(in) :: ratio
    if (is_nan(pnewdt)) then   ! no request (a quiet test: a NaN must not meet an ordered comparison)
      if (ratio < 1) pnewdt = ratio
    else if (pnewdt > 0) then
      pnewdt = min(pnewdt, ratio)
    else if (ratio < 1) then
      pnewdt = ratio
    end if
  end subroutine suggest_step

  !> The step policy on the local error estimate (theory.md sec. 3.6): err_ratio = err_est / tol. A
  !> step with err_ratio > 1 is rejected with 0.8 / sqrt(err_ratio) (at least step_cutback); an
  !> accepted one grows by the same rule within [1, step_max_growth].
  pure recursive real(real64) function step_ratio(err_ratio) result(ratio)
    real(real64), intent(in) :: err_ratio
    if (err_ratio > 1) then
      ratio = max(step_cutback, 0.8_real64 / sqrt(err_ratio))
    else if (err_ratio > 0) then
      ratio = min(step_max_growth, max(1.0_real64, 0.8_real64 / sqrt(err_ratio)))
    else
      ratio = step_max_growth
    end if
  end function step_ratio


  !> True, with one line to the host (host_warning) naming the argument, its value and what was
  !> expected, when an argument of the increment cannot be used (docs/umat.md "Rejected calls"): DTIME
  !> negative or not finite; DSTRAN not finite; DROT, when read (not the identity), not finite; the
  !> stored state not usable, a slot 1-32 not finite or pc of a frame in use (slot 26) not positive;
  !> or, for an uninitialised state (slot 13 finite and <= 0, started from STRESS), STRESS not finite.
  !> No test here signals on a NaN or an Inf (is_finite, first_not_finite: bit tests; the ordered
  !> comparisons only of finite numbers), so that a host with floating-point traps on gets the line,
  !> not SIGFPE.
  recursive logical function arguments_rejected(dtime, ntens, dstran, rotated, drot, stress, statev, phi, &
                                                noel, npt) result(bad)
    integer, intent(in) :: ntens, noel, npt
    real(real64), intent(in) :: dtime, dstran(ntens), drot(3, 3), stress(ntens), statev(nstatv_min), phi
    logical, intent(in) :: rotated   ! DROT is not the identity (compared quietly: /=), so it is read
    character(len=*), parameter :: a_finite_number = 'a finite number'
    integer :: k
    logical :: usable

    bad = .true.
    usable = is_finite(dtime)
    if (usable) usable = dtime >= 0   ! compared only when finite (no short-circuit in Fortran)
    if (.not. usable) then
      call reject('DTIME', [integer ::], dtime, 'a finite time increment >= 0', noel, npt)
      return
    end if
    k = first_not_finite(ntens, dstran)
    if (k > 0) then
      call reject('DSTRAN', [k], dstran(k), 'a finite strain increment', noel, npt)
      return
    end if
    if (rotated) then
      k = first_not_finite(9, drot)
      if (k > 0) then
        call reject('DROT', [mod(k - 1, 3) + 1, (k - 1) / 3 + 1], drot(mod(k - 1, 3) + 1, (k - 1) / 3 + 1), &
                    'a finite rotation increment', noel, npt)
        return
      end if
    end if
    if (is_finite(statev(is_pc_hard))) then
      if (statev(is_pc_hard) <= 0) then   ! uninitialised: started from STRESS (and PROPS)
        k = first_not_finite(ntens, stress)
        if (k > 0) call reject('STRESS', [k], stress(k), a_finite_number // &
                               ' (STATEV(13) <= 0: the state is started from STRESS)', noel, npt)
        bad = k > 0
        return
      end if
    end if
    k = first_not_finite(nstatv_min, statev)
    if (k > 0) then
      call reject('STATEV', [k], statev(k), a_finite_number, noel, npt)
      return
    end if
    if (phi < 1 .and. .not. (statev(is_pc_soft) > 0)) then
      call reject('STATEV', [is_pc_soft], statev(is_pc_soft), 'the soft-frame pc > 0 ' // &
                  '(slot 13 > 0: the state is initialised)', noel, npt)
      return
    end if
    bad = .false.
  end function arguments_rejected

  !> The line of a rejected call: the argument, with its indices if any (name(i) or name(i,j)), its
  !> value, what was expected, where.
  recursive subroutine reject(name, index, value, expected, noel, npt)
    character(len=*), intent(in) :: name, expected
    integer, intent(in) :: index(:), noel, npt
    real(real64), intent(in) :: value
    character(len=message_len) :: line
    character(len=32) :: argument, number
    select case (size(index))
    case (0)
      argument = name
    case (1)
      write (argument, '(a,a,i0,a)') name, '(', index(1), ')'
    case default
      write (argument, '(a,a,i0,a,i0,a)') name, '(', index(1), ',', index(2), ')'
    end select
    write (number, '(es14.6e3)') value   ! NaN, Infinity, -Infinity: written, never compared
    write (line, '(a,a,a,a,a,a,a,i0,a,i0)') 'Cam-Clay IX UMAT: ', trim(argument), ' = ', &
      trim(adjustl(number)), ': expected ', expected, '; increment rejected (PNEWDT < 1) at element ', &
      noel, ', integration point ', npt
    call host_warning(trim(line))
  end subroutine reject

end module ccix_state
