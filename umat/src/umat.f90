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
  use ccix_tensor, only: stress_to_mandel, mandel_to_stress, strain_to_mandel, tangent_to_abaqus
  use ccix_props, only: ip_phi, ip_tol, is_pc_hard, is_iterations, is_flags, &
                        is_f_hard, is_f_soft, nstatv_diag, nstatv_min, message_len
  use ccix_mixture, only: material_t, step_info_t, mixture_integrate, material_ddsdde, hard, soft
  use ccix_state, only: state_rotate, state_unpack, state_pack, state_flags, suggest_step, step_ratio, &
                        step_cutback, arguments_rejected
  use ccix_material_cache, only: material_for
  use ccix_host, only: host_stop
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
  integer :: code, k
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
  if (arguments_rejected(dtime, statev, props(ip_phi), noel, npt)) then
    call suggest_step(pnewdt, step_cutback)
    call material_ddsdde(mat, ntens, ddsdde)
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
        drot(3, 2) /= 0) call state_rotate(drot, sv)
    call state_unpack(sv, sig_n, pc_n)
  end if

  ! Strain increment: NTENS = 4 is 11, 22, 33, 12 with 13 = 23 = 0 (plane strain, axisymmetric).
  deps = 0
  deps(1:ntens) = dstran
  deps = strain_to_mandel(deps)

  call mixture_integrate(mat, sig_n, pc_n, deps, dtime, tol > 0 .and. dtime > 0, &
                         sig_frames, pc, devp, devp_total, sig, d, info)
  if (info%failed) then
    ! Ask for a smaller step; STRESS and STATEV stay as they came in; DDSDDE elastic and finite.
    call suggest_step(pnewdt, step_cutback)
    call material_ddsdde(mat, ntens, ddsdde)
    return
  end if
  ! Step control on the viscoplastic strain increment (PROPS(20) = tol > 0, theory.md sec. 3.6).
  if (tol > 0 .and. dtime > 0) then
    ratio = info%err_est / tol
    call suggest_step(pnewdt, step_ratio(ratio))
    if (ratio > 1) then   ! rejected: STRESS and STATEV stay as they came in
      call tangent()
      return
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
  call tangent()
  call state_pack(sig_frames, pc, devp, devp_total, info%viscoplastic, sv)
  statev(1:nstatv_min) = sv
  if (nstatv >= nstatv_diag) then
    ! Diagnostics (docs/umat.md): iterations, flags, yield function values at the end of the step.
    statev(is_iterations) = info%iterations
    statev(is_flags) = state_flags(info)
    statev(is_f_hard) = info%f(hard)
    statev(is_f_soft) = info%f(soft)
  end if

contains

  !> DDSDDE: the consistent tangent if a frame flowed, else Cbar.
  recursive subroutine tangent()
    if (info%viscoplastic) then
      call tangent_to_abaqus(d, ntens, ddsdde)
    else
      call material_ddsdde(mat, ntens, ddsdde)
    end if
  end subroutine tangent

end subroutine umat
