!> The two-frame mixture of Cam-Clay IX (theory.md §2): both frames see the same strain increment,
!> sigma = phi sigma_hard + (1 - phi) sigma_soft and D = phi D_hard + (1 - phi) D_soft. A frame with
!> zero volume fraction is not integrated and keeps its state.
module ccix_mixture
  use, intrinsic :: iso_fortran_env, only: real64
  use ccix_tensor, only: invert6
  use ccix_frame, only: frame_t, frame_integrate, frame_failed, frame_elastic
  implicit none
  private

  integer, parameter, public :: hard = 1, soft = 2

  !> The material of one point: both frames, the hard-frame fraction phi and the inverse of the
  !> mixture stiffness Cbar = phi C_hard + (1 - phi) C_soft (for the overall viscoplastic strain).
  type, public :: material_t
    type(frame_t) :: frames(2)
    real(real64) :: phi = 0
    real(real64) :: cbar_inv(6, 6) = 0
  end type material_t

  !> State of the mixture at one point, Mandel components.
  type, public :: mixture_state_t
    ! No default initialisation: these live in the hot path of every UMAT call.
    real(real64) :: sig(6, 2)     !< frame stresses (hard, soft)
    real(real64) :: evp(6, 2)     !< frame viscoplastic strains
    real(real64) :: pc(2)         !< frame preconsolidation pressures
    real(real64) :: evp_total(6)  !< overall viscoplastic strain, Y21 eq. 3
  end type mixture_state_t

  !> What one step did: local iterations (max over frames), flags per frame, whether any frame
  !> yielded, the worst local error estimate and each frame's yield function at the end of the step.
  type, public :: step_info_t
    integer :: iterations
    integer :: flags(2)
    logical :: viscoplastic
    logical :: failed
    real(real64) :: err_est
    real(real64) :: f(2)
  end type step_info_t

  public :: material_new, mixture_integrate

contains

  !> The material of hard and soft frames with hard-frame fraction phi.
  pure function material_new(hard_frame, soft_frame, phi) result(mat)
    type(frame_t), intent(in) :: hard_frame, soft_frame
    real(real64), intent(in) :: phi
    type(material_t) :: mat
    logical :: ok
    mat%frames(hard) = hard_frame
    mat%frames(soft) = soft_frame
    mat%phi = phi
    call invert6(phi * hard_frame%c + (1 - phi) * soft_frame%c, mat%cbar_inv, ok)
  end function material_new

  !> Integrate both frames over one step. On failure the state is returned unchanged and
  !> info%failed is set.
  pure subroutine mixture_integrate(mat, state_n, deps, dt, want_error, state, sig, d, info)
    type(material_t), intent(in) :: mat
    real(real64), intent(in) :: deps(6), dt
    type(mixture_state_t), intent(in) :: state_n
    logical, intent(in) :: want_error
    type(mixture_state_t), intent(out) :: state
    real(real64), intent(out) :: sig(6), d(6, 6)
    type(step_info_t), intent(out) :: info
    real(real64) :: frac(2), devp(6, 2), d_frame(6, 6), err(2)
    integer :: k, it, status

    frac = [mat%phi, 1 - mat%phi]
    info%iterations = 0
    info%flags = 0
    info%viscoplastic = .false.
    info%failed = .false.
    info%f = 0
    state = state_n
    sig = 0
    d = 0
    devp = 0
    err = 0
    do k = 1, 2
      if (frac(k) <= 0) cycle
      call frame_integrate(mat%frames(k), state_n%sig(:, k), state_n%pc(k), deps, dt, want_error, &
                           state%sig(:, k), state%pc(k), devp(:, k), d_frame, it, status, &
                           info%flags(k), err(k), info%f(k))
      info%iterations = max(info%iterations, it)
      if (status == frame_failed) then
        info%failed = .true.
        state = state_n
        return
      end if
      if (status /= frame_elastic) info%viscoplastic = .true.
      state%evp(:, k) = state_n%evp(:, k) + devp(:, k)
      sig = sig + frac(k) * state%sig(:, k)
      d = d + frac(k) * d_frame
    end do
    info%err_est = maxval(err)

    ! Overall viscoplastic strain (Y21 eq. 3): evp = Cbar^-1 (phi C_h evp_h + (1-phi) C_s evp_s);
    ! the moduli are constant, so it is updated with the increments. Output only.
    if (info%viscoplastic) then
      if (mat%phi >= 1) then
        state%evp_total = state%evp(:, hard)
      else if (mat%phi <= 0) then
        state%evp_total = state%evp(:, soft)
      else
        state%evp_total = state_n%evp_total + matmul(mat%cbar_inv, &
          mat%phi * matmul(mat%frames(hard)%c, devp(:, hard)) &
          + (1 - mat%phi) * matmul(mat%frames(soft)%c, devp(:, soft)))
      end if
    end if
  end subroutine mixture_integrate

end module ccix_mixture
