!> The two-frame mixture of Cam-Clay IX (theory.md sec. 2): both frames see the same strain increment,
!> sigma = phi sigma_hard + (1 - phi) sigma_soft and D = phi D_hard + (1 - phi) D_soft. A frame with
!> zero volume fraction is not integrated and keeps its state.
module ccix_mixture
  use, intrinsic :: iso_fortran_env, only: real64
  use ccix_walpole, only: ti_mix, ti_inverse, ti_apply, ti_abaqus
  use ccix_frame, only: frame_t, frame_integrate, frame_prepare, frame_add_stiffness, frame_failed, &
                        frame_elastic
  implicit none
  private

  integer, parameter, public :: hard = 1, soft = 2

  !> The material of one point: both frames, the hard-frame fraction phi and Walpole's basis of the
  !> bedding normal, which serves both (the soft frame is isotropic). No default initialisation
  !> (ccix_material_cache sets every component): a local material_t, which the single-file UMAT derives
  !> in every call, costs no initialisation.
  type, public :: material_t
    type(frame_t) :: frames(2)
    real(real64) :: phi
    real(real64) :: q(6, 6)   !< walpole_basis of the bedding normal (ccix_props' frames_from_props)
    logical :: have_ddsdde    !< ddsdde is set (material_prepare); else material_ddsdde derives it
    real(real64) :: ddsdde(6, 6)   !< Cbar as an Abaqus DDSDDE, where have_ddsdde
  end type material_t

  !> What one step did (no default initialisation: this is in the hot path of every call).
  type, public :: step_info_t
    integer :: iterations          !< local Newton iterations, the larger of the two frames
    integer :: flags(2)            !< ccix_frame flag bits per frame
    logical :: viscoplastic        !< some frame flowed
    logical :: failed              !< some frame failed: nothing was updated
    real(real64) :: err_est        !< worst local error estimate (theory.md sec. 3.6)
    real(real64) :: f(2)           !< yield function of each frame at the end of the step
  end type step_info_t

  public :: material_ddsdde, material_prepare, mixture_integrate

contains

  !> The mixture stiffness Cbar = phi C_hard + (1 - phi) C_soft (theory.md sec. 2), the tangent when no
  !> frame flows, as an Abaqus DDSDDE (ntens x ntens). Cbar is transversely isotropic about the bedding
  !> normal like C_hard (C_soft is isotropic): the same combination of its Walpole coefficients.
  pure recursive subroutine material_ddsdde(mat, ntens, ddsdde)
    type(material_t), intent(in) :: mat
    integer, intent(in) :: ntens
    real(real64), intent(out) :: ddsdde(ntens, ntens)
    if (mat%have_ddsdde) then
      ddsdde = mat%ddsdde(1:ntens, 1:ntens)   ! the same numbers (ti_abaqus: entry by entry)
    else
      call ti_abaqus(ti_mix(mat%phi, mat%frames(hard)%cw, 1 - mat%phi, mat%frames(soft)%cw), mat%q, &
                     ntens, ddsdde)
    end if
  end subroutine material_ddsdde

  !> Derive now what a material kept for many calls would otherwise derive in each (the same numbers):
  !> the pencils and stiffness matrices of both frames (frame_prepare) and Cbar's DDSDDE. mat%phi must
  !> be set.
  pure recursive subroutine material_prepare(mat)
    type(material_t), intent(inout) :: mat
    if (.not. (mat%frames(hard)%prepared .and. mat%frames(soft)%prepared)) then
      call frame_prepare(mat%frames(hard), mat%q)
      call frame_prepare(mat%frames(soft), mat%q)
    end if
    mat%have_ddsdde = .false.
    call material_ddsdde(mat, 6, mat%ddsdde)
    mat%have_ddsdde = .true.
  end subroutine material_prepare

  !> Integrate both frames over one step (Mandel components). In: the frame stresses and pc at the
  !> start. Out: frame stresses and pc at the end, the frame viscoplastic strain increments and that of
  !> the mixture (Y21 eq. 3), the mixture stress and, if info%viscoplastic, the tangent (else it is Cbar,
  !> material_ddsdde). If info%failed, nothing is meaningful.
  pure recursive subroutine mixture_integrate(mat, sig_n, pc_n, deps, dt, want_error, sig_frames, pc, &
                                    devp, devp_total, sig, d, info)
    type(material_t), intent(in) :: mat
    real(real64), intent(in) :: sig_n(6, 2), pc_n(2), deps(6), dt
    logical, intent(in) :: want_error
    real(real64), intent(out) :: sig_frames(6, 2), pc(2), devp(6, 2), devp_total(6), sig(6), d(6, 6)
    type(step_info_t), intent(out) :: info
    real(real64) :: frac(2), d_frames(6, 6, 2), err(2), y(6)
    integer :: k, it, status(2)

    frac(hard) = mat%phi
    frac(soft) = 1 - mat%phi
    info%iterations = 0
    info%flags = 0
    info%viscoplastic = .false.
    info%failed = .false.
    info%f = 0
    sig_frames = sig_n
    pc = pc_n
    sig = 0
    devp = 0
    devp_total = 0
    err = 0
    status = frame_elastic
    do k = 1, 2
      if (frac(k) <= 0) cycle
      call frame_integrate(mat%frames(k), mat%q, sig_n(:, k), pc_n(k), deps, dt, want_error, &
                           sig_frames(:, k), pc(k), devp(:, k), d_frames(:, :, k), it, status(k), &
                           info%flags(k), err(k), info%f(k))
      info%iterations = max(info%iterations, it)
      if (status(k) == frame_failed) then
        info%failed = .true.
        return
      end if
      sig = sig + frac(k) * sig_frames(:, k)
    end do
    ! Tangent: the fraction-weighted frame tangents when a frame flowed (else Cbar: not set here).
    info%viscoplastic = any(status /= frame_elastic)
    if (info%viscoplastic) then
      d = 0
      do k = 1, 2
        if (frac(k) <= 0) cycle
        if (status(k) == frame_elastic) then
          call frame_add_stiffness(mat%frames(k), mat%q, frac(k), d)
        else
          d = d + frac(k) * d_frames(:, :, k)
        end if
      end do
    end if
    info%err_est = maxval(err)

    ! Overall viscoplastic strain (Y21 eq. 3): evp = Cbar^-1 (phi C_h evp_h + (1-phi) C_s evp_s);
    ! the moduli are constant, so it is updated with the increments. Output only. Cbar^-1 is the
    ! inverse of Cbar's Walpole coefficients (ccix_walpole).
    if (info%viscoplastic) then
      if (mat%phi >= 1) then
        devp_total = devp(:, hard)
      else if (mat%phi <= 0) then
        devp_total = devp(:, soft)
      else
        ! With phi C_h + (1 - phi) C_s = Cbar: Cbar^-1 (1 - phi) C_s x = x - phi Cbar^-1 C_h x, so
        ! devp_total = devp_s + phi Cbar^-1 C_h (devp_h - devp_s).
        associate (fh => mat%frames(hard), fs => mat%frames(soft))
          call ti_apply(fh%cw, fh%n, fh%mh, devp(:, hard) - devp(:, soft), y)
          call ti_apply(ti_inverse(ti_mix(mat%phi, fh%cw, 1 - mat%phi, fs%cw)), fh%n, fh%mh, y, devp_total)
          devp_total = devp(:, soft) + mat%phi * devp_total
        end associate
      end if
    end if
  end subroutine mixture_integrate

end module ccix_mixture
