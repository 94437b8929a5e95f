!> Abaqus UMAT entry point of the Cam-Clay IX model (Yin, Liu & Borja 2021; Borja, Yin & Zhao 2020).
!>
!> This routine only adapts the Abaqus conventions (Voigt order 11, 22, 33, 12, 13, 23, engineering
!> shear strains, NTENS = 4 or 6, DROT, PNEWDT, STATEV layout) to the Mandel-notation mixture in
!> ccix_mixture. The contract is docs/umat-interface.md and docs/umat.md.
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
  real(real64) :: deps(6), sig(6), d(6, 6), sig_full(6), phi, tol
  real(real64) :: sig_n(6, 2), pc_n(2), sig_frames(6, 2), pc(2), devp(6, 2), devp_total(6)
  real(real64) :: sv(nstatv_min)   ! STATEV 1-32 at the start, rotated: STATEV itself changes only on success
  integer :: code
  logical :: rejected, rotated
  character(len=message_len) :: message

  rpl = 0
  ddsddt = 0
  drplde = 0
  drpldt = 0

  ! Sizes and PROPS, checked (theory.md sec. 6; umat-interface.md "Bad properties"): invalid ones end
  ! the analysis the host's way (ccix_host), with a message naming the slot, its value and the range.
  call material_for(props, nprops, nstatv, ntens, ndi, own, mat, code, message)
  if (code /= 0) call stop_here(message, noel, npt, cmname)
  phi = props(ip_phi)
  tol = 0
  if (nprops >= ip_tol) tol = props(ip_tol)

  ! DROT is read (and checked) only when it is not the identity; /= compares quietly, NaN included.
  rotated = drot(1, 1) /= 1 .or. drot(2, 2) /= 1 .or. drot(3, 3) /= 1 .or. drot(1, 2) /= 0 .or. &
            drot(2, 1) /= 0 .or. drot(1, 3) /= 0 .or. drot(3, 1) /= 0 .or. drot(2, 3) /= 0 .or. &
            drot(3, 2) /= 0

  ! Arguments no smaller step can repair are rejected like a failed step (PNEWDT < 1, STRESS and
  ! STATEV unchanged, a message naming the argument): a negative or non-finite DTIME, a non-finite
  ! DSTRAN or DROT, a non-finite stored state, or a non-finite STRESS to start an uninitialised state
  ! from (docs/umat.md "Rejected calls"). Before any arithmetic on them: with floating-point traps on,
  ! a NaN or an Inf must give the message, not SIGFPE.
  if (arguments_rejected(dtime, ntens, dstran, rotated, drot, stress, statev, props(ip_phi), noel, npt)) then
    call suggest_step(pnewdt, step_cutback)
    call material_ddsdde(mat, ntens, ddsdde)
    return
  end if

  ! State at the start of the increment: rotated by DROT, or started from STRESS and PROPS.
  call start_state(statev, stress, ntens, rotated, drot, mat, sv, sig_n, pc_n)

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
  call step_control(info, tol, dtime, pnewdt, rejected)
  if (rejected) then   ! STRESS and STATEV stay as they came in
    call tangent(mat, info, d, ntens, ddsdde)
    return
  end if

  call add_energies(phi, sig_n, sig_frames, deps, devp, info%viscoplastic, sse, spd)
  sig_full = mandel_to_stress(sig)
  stress = sig_full(1:ntens)
  call tangent(mat, info, d, ntens, ddsdde)
  call state_pack(sig_frames, pc, devp, devp_total, info%viscoplastic, sv)
  statev(1:nstatv_min) = sv
  if (nstatv >= nstatv_diag) call write_diagnostics(info, statev)

contains
  ! The phases of the call: contained, so that they are inlined (a call to a module procedure is not,
  ! under -fPIC: 4 % more instructions per elastic call of the library, measured), and given all they
  ! use as arguments (a contained procedure that reads the host's variables keeps them in memory: 5 %
  ! more, measured).

  !> End the analysis the host's way (ccix_host) with message and where it happened.
  recursive subroutine stop_here(message, noel, npt, cmname)
    character(len=*), intent(in) :: message, cmname
    integer, intent(in) :: noel, npt
    character(len=160) :: where
    write (where, '(a,i0,a,i0,a,a)') '; stopping at element ', noel, ', integration point ', npt, &
      ', material ', cmname
    call host_stop(trim(message) // trim(where))
  end subroutine stop_here

  !> The state at the start of the increment: sv, STATEV 1-32 rotated by DROT (a copy, so that a
  !> rejected call returns STATEV exactly as it came in), and the frames' stresses and pc from it. A
  !> state whose pc_hard is not positive is uninitialised: both frames start at the stress passed in,
  !> with pc = pc0 and no viscoplastic strain (theory.md sec. 2).
  pure recursive subroutine start_state(statev, stress, ntens, rotated, drot, mat, sv, sig_n, pc_n)
    integer, intent(in) :: ntens
    logical, intent(in) :: rotated
    real(real64), intent(in) :: statev(nstatv_min), stress(ntens), drot(3, 3)
    type(material_t), intent(in) :: mat
    real(real64), intent(out) :: sv(nstatv_min), sig_n(6, 2), pc_n(2)
    real(real64) :: sig_full(6)
    integer :: k
    if (statev(is_pc_hard) <= 0) then
      sig_full = 0
      sig_full(1:ntens) = stress
      do k = hard, soft
        sig_n(:, k) = stress_to_mandel(sig_full)
        pc_n(k) = mat%frames(k)%pc0
      end do
      sv = 0
      return
    end if
    ! Rigid rotation of the increment (umat-interface.md): the stored tensors, not the normal.
    sv = statev
    if (rotated) call state_rotate(drot, sv)
    call state_unpack(sv, sig_n, pc_n)
  end subroutine start_state

  !> Step control on the viscoplastic strain increment (PROPS(20) = tol > 0, theory.md sec. 3.6): PNEWDT
  !> advised from the step's error estimate; rejected when the step is too inaccurate for tol.
  pure recursive subroutine step_control(info, tol, dtime, pnewdt, rejected)
    type(step_info_t), intent(in) :: info
    real(real64), intent(in) :: tol, dtime
    real(real64), intent(inout) :: pnewdt
    logical, intent(out) :: rejected
    real(real64) :: ratio
    rejected = .false.
    if (.not. (tol > 0 .and. dtime > 0)) return
    ratio = info%err_est / tol
    call suggest_step(pnewdt, step_ratio(ratio))
    rejected = ratio > 1
  end subroutine step_control

  !> SSE and SPD, the elastic energy and the viscoplastic dissipation per unit volume, increased by the
  !> step's in each frame in use (hard fraction phi), midpoint rule: sig_n and sig the frames' stresses
  !> at the start and the end, deps the strain increment, devp the frames' viscoplastic increments.
  pure recursive subroutine add_energies(phi, sig_n, sig, deps, devp, viscoplastic, sse, spd)
    real(real64), intent(in) :: phi, sig_n(6, 2), sig(6, 2), deps(6), devp(6, 2)
    logical, intent(in) :: viscoplastic
    real(real64), intent(inout) :: sse, spd
    real(real64) :: frac(2)
    integer :: k
    frac(hard) = phi
    frac(soft) = 1 - phi
    do k = hard, soft
      if (frac(k) <= 0) cycle
      sse = sse + frac(k) * 0.5_real64 * dot_product(sig_n(:, k) + sig(:, k), deps - devp(:, k))
      if (viscoplastic) spd = spd + frac(k) * 0.5_real64 * dot_product(sig_n(:, k) + sig(:, k), devp(:, k))
    end do
  end subroutine add_energies

  !> The diagnostic slots 33-36 (docs/umat.md "STATEV"): iterations, flags, and the frames' yield
  !> functions at the end of the step.
  pure recursive subroutine write_diagnostics(info, statev)
    type(step_info_t), intent(in) :: info
    real(real64), intent(inout) :: statev(nstatv_diag)
    statev(is_iterations) = info%iterations
    statev(is_flags) = state_flags(info)
    statev(is_f_hard) = info%f(hard)
    statev(is_f_soft) = info%f(soft)
  end subroutine write_diagnostics

  !> DDSDDE: the consistent tangent d if a frame flowed, else Cbar.
  pure recursive subroutine tangent(mat, info, d, ntens, ddsdde)
    type(material_t), intent(in) :: mat
    type(step_info_t), intent(in) :: info
    integer, intent(in) :: ntens
    real(real64), intent(in) :: d(6, 6)
    real(real64), intent(out) :: ddsdde(ntens, ntens)
    if (info%viscoplastic) then
      call tangent_to_abaqus(d, ntens, ddsdde)
    else
      call material_ddsdde(mat, ntens, ddsdde)
    end if
  end subroutine tangent

end subroutine umat
