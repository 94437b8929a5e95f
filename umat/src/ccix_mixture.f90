!> The two-frame mixture of Cam-Clay IX (theory.md sec. 2): both frames see the same strain increment,
!> sigma = phi sigma_hard + (1 - phi) sigma_soft and D = phi D_hard + (1 - phi) D_soft. A frame with
!> zero volume fraction is not integrated and keeps its state.
module ccix_mixture
  use, intrinsic :: iso_fortran_env, only: real64
  use ccix_tensor, only: invert6, tangent_to_abaqus
  use ccix_frame, only: frame_t, frame_integrate, frame_failed, frame_elastic
  implicit none
  private

  integer, parameter, public :: hard = 1, soft = 2

  !> The material of one point: both frames, the hard-frame fraction phi and the inverse of the
  !> mixture stiffness Cbar = phi C_hard + (1 - phi) C_soft (for the overall viscoplastic strain).
  !> No default initialisation (frames_from_props and material_set_phi set every component): a local
  !> material_t, which the single-file UMAT derives in every call, costs no initialisation.
  type, public :: material_t
    type(frame_t) :: frames(2)
    real(real64) :: phi
    real(real64) :: cbar(6, 6)          !< Cbar (Mandel): the tangent when no frame flows
    real(real64) :: cbar_inv(6, 6)
    real(real64) :: cbar_abaqus(6, 6)   !< Cbar as an Abaqus DDSDDE (engineering shear)
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

  public :: material_set_phi, mixture_integrate

contains

  !> Complete mat, whose frames are set, for the hard-frame fraction phi: Cbar, its inverse and its
  !> Abaqus form.
  pure recursive subroutine material_set_phi(mat, phi)
    type(material_t), intent(inout) :: mat
    real(real64), intent(in) :: phi
    logical :: ok
    mat%phi = phi
    mat%cbar = phi * mat%frames(hard)%c + (1 - phi) * mat%frames(soft)%c
    call invert6(mat%cbar, mat%cbar_inv, ok)
    call tangent_to_abaqus(mat%cbar, 6, mat%cbar_abaqus)
  end subroutine material_set_phi

  !> Integrate both frames over one step (Mandel components). In: the frame stresses and pc at the
  !> start. Out: frame stresses and pc at the end, the frame viscoplastic strain increments and that of
  !> the mixture (Y21 eq. 3), the mixture stress and tangent. If info%failed, nothing is meaningful.
  pure recursive subroutine mixture_integrate(mat, sig_n, pc_n, deps, dt, want_error, sig_frames, pc, &
                                    devp, devp_total, sig, d, info)
    type(material_t), intent(in) :: mat
    real(real64), intent(in) :: sig_n(6, 2), pc_n(2), deps(6), dt
    logical, intent(in) :: want_error
    real(real64), intent(out) :: sig_frames(6, 2), pc(2), devp(6, 2), devp_total(6), sig(6), d(6, 6)
    type(step_info_t), intent(out) :: info
    real(real64) :: frac(2), d_frames(6, 6, 2), err(2)
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
      call frame_integrate(mat%frames(k), sig_n(:, k), pc_n(k), deps, dt, want_error, &
                           sig_frames(:, k), pc(k), devp(:, k), d_frames(:, :, k), it, status(k), &
                           info%flags(k), err(k), info%f(k))
      info%iterations = max(info%iterations, it)
      if (status(k) == frame_failed) then
        info%failed = .true.
        return
      end if
      sig = sig + frac(k) * sig_frames(:, k)
    end do
    ! Tangent: Cbar while both frames are elastic, else the fraction-weighted frame tangents.
    info%viscoplastic = any(status /= frame_elastic)
    if (.not. info%viscoplastic) then
      d = mat%cbar
    else
      d = 0
      do k = 1, 2
        if (frac(k) <= 0) cycle
        if (status(k) == frame_elastic) then
          d = d + frac(k) * mat%frames(k)%c
        else
          d = d + frac(k) * d_frames(:, :, k)
        end if
      end do
    end if
    info%err_est = maxval(err)

    ! Overall viscoplastic strain (Y21 eq. 3): evp = Cbar^-1 (phi C_h evp_h + (1-phi) C_s evp_s);
    ! the moduli are constant, so it is updated with the increments. Output only.
    if (info%viscoplastic) then
      if (mat%phi >= 1) then
        devp_total = devp(:, hard)
      else if (mat%phi <= 0) then
        devp_total = devp(:, soft)
      else
        devp_total = matmul(mat%cbar_inv, mat%phi * matmul(mat%frames(hard)%c, devp(:, hard)) &
                                          + (1 - mat%phi) * matmul(mat%frames(soft)%c, devp(:, soft)))
      end if
    end if
  end subroutine mixture_integrate

end module ccix_mixture
