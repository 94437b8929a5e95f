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
  use ccix_tensor, only: is_finite
  use ccix_host, only: host_warning
  use ccix_frame, only: flag_floor, flag_tension, flag_fallback
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
    end do
  end function state_flags

  !> PNEWDT asks at most ratio of the increment. Hosts differ in what PNEWDT holds on entry: Abaqus sets
  !> it large and takes the smallest request; CalculiX passes -1 ("no request") and redoes the increment
  !> for ANY positive value, above 1 too (docs/calculix.md). So with PNEWDT <= 0 on entry only a cutback
  !> (< 1) is written.
  pure recursive subroutine suggest_step(pnewdt, ratio)
    real(real64), intent(inout) :: pnewdt
    real(real64), intent(in) :: ratio
    if (pnewdt > 0) then
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
  !> expected, when DTIME is negative or not finite, or the stored state is not usable: a slot 1-32 not
  !> finite (unless slot 13 <= 0 marks the state as uninitialised), or pc of a frame in use (slot 26)
  !> not positive.
  recursive logical function arguments_rejected(dtime, statev, phi, noel, npt) result(bad)
    real(real64), intent(in) :: dtime, statev(:), phi
    integer, intent(in) :: noel, npt
    character(len=*), parameter :: rejected = '; increment rejected (PNEWDT < 1) at element '
    character(len=message_len) :: line
    integer :: slot
    bad = .true.
    if (.not. (dtime >= 0 .and. dtime <= huge(dtime))) then
      write (line, '(a,es14.6e3,a,a,i0,a,i0)') 'Cam-Clay IX UMAT: DTIME = ', dtime, &
        ': expected a finite time increment >= 0', rejected, noel, ', integration point ', npt
      call host_warning(trim(line))
      return
    end if
    if (is_finite(statev(is_pc_hard)) .and. statev(is_pc_hard) <= 0) then
      bad = .false.   ! uninitialised: every stored slot is set from PROPS and STRESS
      return
    end if
    if (all(abs(statev(1:nstatv_min)) <= huge(dtime))) then   ! all finite (NaN compares false)
      slot = nstatv_min + 1
    else
      slot = 1
    end if
    do slot = slot, nstatv_min
      if (.not. is_finite(statev(slot))) then
        write (line, '(a,i0,a,es14.6e3,a,a,i0,a,i0)') 'Cam-Clay IX UMAT: STATEV(', slot, ') = ', &
          statev(slot), ': expected a finite number', rejected, noel, ', integration point ', npt
        call host_warning(trim(line))
        return
      end if
    end do
    if (phi < 1 .and. .not. (statev(is_pc_soft) > 0)) then
      write (line, '(a,i0,a,es14.6e3,a,a,i0,a,i0)') 'Cam-Clay IX UMAT: STATEV(', is_pc_soft, ') = ', &
        statev(is_pc_soft), ': expected the soft-frame pc > 0 ' // &
        '(slot 13 > 0: the state is initialised)', &
        rejected, noel, ', integration point ', npt
      call host_warning(trim(line))
      return
    end if
    bad = .false.
  end function arguments_rejected

end module ccix_state
