!> Abaqus UMAT entry point of the Cam-Clay IX model (Yin, Liu & Borja 2021; Borja, Yin & Zhao 2020).
!>
!> This routine only adapts the Abaqus conventions (Voigt order 11, 22, 33, 12, 13, 23, engineering
!> shear strains, NTENS = 4 or 6, DROT, PNEWDT, STATEV layout) to the Mandel-notation mixture in
!> ccix_mixture. The contract is ../shared/docs/umat-interface.md and docs/umat.md.
!>
!> Re-entrant: every procedure is RECURSIVE, so that its locals are automatic whatever the compiler
!> flags (gfortran -fno-automatic, ifort's default static local arrays and -save spare RECURSIVE
!> procedures), and the single-file UMAT keeps no module state (ccix_material_cache).
!> (The name has a line of its own, so that a host with a UMAT of its own can rename this one, e.g.
!> with the C preprocessor: -Dumat=umat_camclay9; docs/umat.md, "Other user subroutines".)
recursive subroutine umat( &
    stress, statev, ddsdde, sse, spd, scd, rpl, ddsddt, drplde, drpldt, &
    stran, dstran, time, dtime, temp, dtemp, predef, dpred, cmname, &
    ndi, nshr, ntens, nstatv, props, nprops, coords, drot, pnewdt, &
    celent, dfgrd0, dfgrd1, noel, npt, layer, kspt, jstep, kinc)
  use, intrinsic :: iso_fortran_env, only: real64
  use ccix_tensor, only: stress_to_mandel, mandel_to_stress, strain_to_mandel, mandel_to_strain, &
                         tangent_to_abaqus, rotate_mandel, mandel_w, is_finite
  use ccix_props, only: ip_phi, ip_tol, is_sig_hard, is_evp_hard, is_pc_hard, is_sig_soft, &
                        is_evp_soft, is_pc_soft, is_evp_total, is_iterations, is_flags, &
                        is_f_hard, is_f_soft, nstatv_diag, nstatv_min, message_len
  use ccix_frame, only: flag_floor, flag_tension, flag_fallback
  use ccix_mixture, only: material_t, step_info_t, mixture_integrate, hard, soft
  use ccix_material_cache, only: material_for
  use ccix_host, only: host_warning, host_stop
  implicit none
  character(len=80), intent(in) :: cmname
  integer, intent(in) :: ndi, nshr, ntens, nstatv, nprops, noel, npt, layer, kspt, jstep(*), kinc
  real(real64), intent(inout) :: stress(ntens), statev(nstatv), sse, spd, scd, pnewdt
  real(real64), intent(out) :: ddsdde(ntens, ntens), rpl, ddsddt(ntens), drplde(ntens), drpldt
  real(real64), intent(in) :: stran(ntens), dstran(ntens), time(2), dtime, temp, dtemp, &
                              predef(*), dpred(*), props(nprops), coords(3), drot(3, 3), &
                              celent, dfgrd0(3, 3), dfgrd1(3, 3)

  type(material_t), target :: own          ! the material, where no per-thread cache holds it
  type(material_t), pointer :: mat
  type(step_info_t) :: info
  real(real64) :: deps(6), sig(6), d(6, 6), sig_full(6), phi, tol, ratio, frac(2)
  real(real64) :: sig_n(6, 2), pc_n(2), sig_frames(6, 2), pc(2), devp(6, 2), devp_total(6)
  real(real64) :: sv(nstatv_min)   ! STATEV 1-32 at the start, rotated: STATEV itself changes only on success
  real(real64), parameter :: cutback = 0.25_real64, max_growth = 1.5_real64
  integer, parameter :: sig_slot(2) = [is_sig_hard, is_sig_soft], evp_slot(2) = [is_evp_hard, is_evp_soft]
  integer :: code, k, flags
  logical :: initialise
  character(len=message_len) :: message
  character(len=160) :: where

  rpl = 0
  ddsddt = 0
  drplde = 0
  drpldt = 0

  ! Sizes and PROPS, checked (theory.md sec. 6; umat-interface.md "Bad properties"): invalid ones end
  ! the analysis the host's way (ccix_host), with a message naming the slot, its value and the range.
  call material_for(props, nprops, nstatv, ntens, ndi, own, mat, code, message)
  if (code /= 0) then
    write (where, '(a,i0,a,i0,a,a)') '; stopping at element ', noel, ', integration point ', npt, &
      ', material ', cmname
    call host_stop(trim(message) // trim(where))
  end if
  phi = props(ip_phi)
  tol = 0
  if (nprops >= ip_tol) tol = props(ip_tol)

  ! Arguments no smaller step can repair are rejected like a failed step (PNEWDT < 1, STRESS and
  ! STATEV unchanged, a message naming the argument): a negative or non-finite DTIME, a non-finite
  ! stored state (docs/umat.md "Rejected calls").
  if (bad_arguments()) then
    call suggest_step(pnewdt, cutback)
    ddsdde = mat%cbar_abaqus(1:ntens, 1:ntens)
    return
  end if

  ! State at the start of the increment. pc_hard <= 0 marks an uninitialised state: both frames
  ! start at the stress passed in, with pc = pc0 and no viscoplastic strain (theory.md sec. 2).
  initialise = statev(is_pc_hard) <= 0
  if (initialise) then
    sig_full = 0
    sig_full(1:ntens) = stress
    do k = hard, soft
      sig_n(:, k) = stress_to_mandel(sig_full)
      pc_n(k) = mat%frames(k)%pc0
    end do
    sv = 0
  else
    ! Rigid rotation of the increment (umat-interface.md): rotate the stored tensors, not the normal.
    ! A copy is rotated, so that a rejected call returns STATEV exactly as it came in.
    sv = statev(1:nstatv_min)
    if (drot(1, 1) /= 1 .or. drot(2, 2) /= 1 .or. drot(3, 3) /= 1 .or. drot(1, 2) /= 0 .or. &
        drot(2, 1) /= 0 .or. drot(1, 3) /= 0 .or. drot(3, 1) /= 0 .or. drot(2, 3) /= 0 .or. &
        drot(3, 2) /= 0) call rotate_state(sv)
    do k = hard, soft
      sig_n(:, k) = sv(sig_slot(k):sig_slot(k) + 5) * mandel_w   ! Voigt stress -> Mandel
    end do
    pc_n(hard) = sv(is_pc_hard)
    pc_n(soft) = sv(is_pc_soft)
  end if

  ! Strain increment: NTENS = 4 is 11, 22, 33, 12 with 13 = 23 = 0 (plane strain, axisymmetric).
  deps = 0
  deps(1:ntens) = dstran
  deps = strain_to_mandel(deps)

  call mixture_integrate(mat, sig_n, pc_n, deps, dtime, tol > 0 .and. dtime > 0, &
                         sig_frames, pc, devp, devp_total, sig, d, info)
  if (info%failed) then
    ! Ask for a smaller step; STRESS and STATEV stay as they came in; DDSDDE elastic and finite.
    call suggest_step(pnewdt, cutback)
    ddsdde = mat%cbar_abaqus(1:ntens, 1:ntens)
    return
  end if
  ! Step control on the viscoplastic strain increment (PROPS(20) = tol > 0, theory.md sec. 3.6).
  if (tol > 0 .and. dtime > 0) then
    ratio = info%err_est / tol
    if (ratio > 1) then
      call suggest_step(pnewdt, max(cutback, 0.8_real64 / sqrt(ratio)))
      call tangent_to_abaqus(d, ntens, ddsdde)
      return
    end if
    if (ratio > 0) then
      call suggest_step(pnewdt, min(max_growth, max(1.0_real64, 0.8_real64 / sqrt(ratio))))
    else
      call suggest_step(pnewdt, max_growth)
    end if
  end if

  ! Energies per unit volume: elastic (SSE) and viscoplastic dissipation (SPD), midpoint rule.
  frac(hard) = phi
  frac(soft) = 1 - phi
  do k = hard, soft
    if (frac(k) <= 0) cycle
    sse = sse + frac(k) * 0.5_real64 * dot_product(sig_n(:, k) + sig_frames(:, k), deps - devp(:, k))
    if (info%viscoplastic) spd = spd + frac(k) * 0.5_real64 * dot_product(sig_n(:, k) + sig_frames(:, k), &
                                                                          devp(:, k))
  end do

  sig_full = mandel_to_stress(sig)
  stress = sig_full(1:ntens)
  if (info%viscoplastic) then
    call tangent_to_abaqus(d, ntens, ddsdde)
  else
    ddsdde = mat%cbar_abaqus(1:ntens, 1:ntens)
  end if
  do k = hard, soft
    sv(sig_slot(k):sig_slot(k) + 5) = sig_frames(:, k) / mandel_w
  end do
  sv(is_pc_hard) = pc(hard)
  sv(is_pc_soft) = pc(soft)
  if (info%viscoplastic) then
    do k = hard, soft
      sv(evp_slot(k):evp_slot(k) + 5) = sv(evp_slot(k):evp_slot(k) + 5) + devp(:, k) * mandel_w
    end do
    sv(is_evp_total:is_evp_total + 5) = sv(is_evp_total:is_evp_total + 5) + devp_total * mandel_w
  end if
  statev(1:nstatv_min) = sv
  if (nstatv >= nstatv_diag) then
    ! Diagnostics (docs/umat.md): iterations, flags, yield function values at the end of the step.
    flags = 0
    do k = hard, soft
      if (iand(info%flags(k), flag_floor) /= 0) flags = ior(flags, 2**(k - 1))
      if (iand(info%flags(k), flag_tension) /= 0) flags = ior(flags, 4 * 2**(k - 1))
      if (iand(info%flags(k), flag_fallback) /= 0) flags = ior(flags, 16)
    end do
    statev(is_iterations) = info%iterations
    statev(is_flags) = flags
    statev(is_f_hard) = info%f(hard)
    statev(is_f_soft) = info%f(soft)
  end if

contains

  !> True, with one line to the host (host_warning) naming the argument, its value and what was
  !> expected, when DTIME is negative or not finite, or the stored state is not usable: a slot 1-32 not
  !> finite (unless slot 13 <= 0 marks the state as uninitialised), or pc of a frame in use (slot 26)
  !> not positive.
  recursive logical function bad_arguments() result(bad)
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
    if (props(ip_phi) < 1 .and. .not. (statev(is_pc_soft) > 0)) then
      write (line, '(a,i0,a,es14.6e3,a,a,i0,a,i0)') 'Cam-Clay IX UMAT: STATEV(', is_pc_soft, ') = ', &
        statev(is_pc_soft), ': expected the soft-frame pc > 0 ' // &
        '(slot 13 > 0: the state is initialised)', &
        rejected, noel, ', integration point ', npt
      call host_warning(trim(line))
      return
    end if
    bad = .false.
  end function bad_arguments

  !> Hosts differ in what PNEWDT holds on entry: Abaqus sets it large and takes the smallest request;
  !> CalculiX passes -1 ("no request") and redoes the increment for ANY positive value, above 1 too
  !> (docs/calculix.md). So with PNEWDT <= 0 on entry only a cutback (< 1) is written.
  pure recursive subroutine suggest_step(pnewdt, ratio)
    real(real64), intent(inout) :: pnewdt
    real(real64), intent(in) :: ratio
    if (pnewdt > 0) then
      pnewdt = min(pnewdt, ratio)
    else if (ratio < 1) then
      pnewdt = ratio
    end if
  end subroutine suggest_step

  !> R A R^T for every stored tensor: frame stresses, frame and overall viscoplastic strains.
  pure recursive subroutine rotate_state(sv)
    real(real64), intent(inout) :: sv(:)
    integer :: kk
    do kk = hard, soft
      sv(sig_slot(kk):sig_slot(kk) + 5) = mandel_to_stress(rotate_mandel(drot, &
                                            stress_to_mandel(sv(sig_slot(kk):sig_slot(kk) + 5))))
      sv(evp_slot(kk):evp_slot(kk) + 5) = mandel_to_strain(rotate_mandel(drot, &
                                            strain_to_mandel(sv(evp_slot(kk):evp_slot(kk) + 5))))
    end do
    sv(is_evp_total:is_evp_total + 5) = mandel_to_strain(rotate_mandel(drot, &
                                          strain_to_mandel(sv(is_evp_total:is_evp_total + 5))))
  end subroutine rotate_state

end subroutine umat
