!> The two-frame mixture of Cam-Clay IX (theory.md §2): both frames see the same strain increment,
!> sigma = phi sigma_hard + (1 - phi) sigma_soft and D = phi D_hard + (1 - phi) D_soft. A frame with
!> zero volume fraction is not integrated and keeps its state.
module ccix_mixture
  use, intrinsic :: iso_fortran_env, only: real64
  use ccix_tensor, only: lu_factor, lu_solve
  use ccix_frame, only: frame_t, frame_integrate, frame_failed, frame_elastic
  implicit none
  private

  integer, parameter, public :: hard = 1, soft = 2

  !> State of the mixture at one point, Mandel components.
  type, public :: mixture_state_t
    real(real64) :: sig(6, 2) = 0     !< frame stresses (hard, soft)
    real(real64) :: evp(6, 2) = 0     !< frame viscoplastic strains
    real(real64) :: pc(2) = 0         !< frame preconsolidation pressures
    real(real64) :: evp_total(6) = 0  !< overall viscoplastic strain, Y21 eq. 3
  end type mixture_state_t

  !> What one step did: local iterations (max over frames), flags per frame, whether any frame
  !> yielded, and the worst local error estimate.
  type, public :: step_info_t
    integer :: iterations = 0
    integer :: flags(2) = 0
    logical :: viscoplastic = .false.
    logical :: failed = .false.
    real(real64) :: err_est = 0
  end type step_info_t

  public :: mixture_integrate

contains

  !> Integrate both frames over one step. phi is the hard-frame fraction. On failure the state is
  !> returned unchanged and info%failed is set.
  pure subroutine mixture_integrate(frames, phi, state_n, deps, dt, want_error, state, sig, d, info)
    type(frame_t), intent(in) :: frames(2)
    real(real64), intent(in) :: phi, deps(6), dt
    type(mixture_state_t), intent(in) :: state_n
    logical, intent(in) :: want_error
    type(mixture_state_t), intent(out) :: state
    real(real64), intent(out) :: sig(6), d(6, 6)
    type(step_info_t), intent(out) :: info
    real(real64) :: frac(2), devp(6, 2), d_frame(6, 6), err(2), rhs(6), cbar(6, 6)
    integer :: k, it, status, piv(6)
    logical :: ok

    frac = [phi, 1 - phi]
    state = state_n
    sig = 0
    d = 0
    devp = 0
    err = 0
    do k = 1, 2
      if (frac(k) <= 0) cycle
      call frame_integrate(frames(k), state_n%sig(:, k), state_n%pc(k), deps, dt, want_error, &
                           state%sig(:, k), state%pc(k), devp(:, k), d_frame, it, status, &
                           info%flags(k), err(k))
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
      if (phi >= 1) then
        state%evp_total = state%evp(:, hard)
      else if (phi <= 0) then
        state%evp_total = state%evp(:, soft)
      else
        cbar = phi * frames(hard)%c + (1 - phi) * frames(soft)%c
        rhs = phi * matmul(frames(hard)%c, devp(:, hard)) &
            + (1 - phi) * matmul(frames(soft)%c, devp(:, soft))
        call lu_factor(6, cbar, piv, ok)
        call lu_solve(6, cbar, piv, rhs)
        state%evp_total = state_n%evp_total + rhs
      end if
    end if
  end subroutine mixture_integrate

end module ccix_mixture
