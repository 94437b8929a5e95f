!> The frames built from the last PROPS seen, so that a host calling the UMAT point after point with
!> the same material does not rebuild stiffness, compliance and projection tensors at every call.
!> The key is the whole PROPS vector and the sizes; PROPS(1) (phi, which a host may vary per element)
!> does not enter the frames, so a change of phi only re-runs the checks.
!> Under OpenMP each thread has its own cache (threadprivate).
module ccix_material_cache
  use, intrinsic :: iso_fortran_env, only: real64
  use ccix_frame, only: frame_t
  use ccix_props, only: check_props, frames_from_props, message_len, nprops_normal, ip_phi
  use ccix_mixture, only: material_t, material_new
  implicit none
  private

  type :: cache_t
    logical :: valid = .false.
    integer :: nprops = 0, ntens = 0, ndi = 0, nstatv = 0
    real(real64) :: props(nprops_normal) = 0
  end type cache_t

  type(cache_t), save :: cache
  type(frame_t), save :: frames(2)
  !> The material of the PROPS last passed to prepare_material. Read-only outside.
  type(material_t), save, public, protected :: current_material
  !$omp threadprivate(cache, frames, current_material)

  public :: prepare_material

contains

  !> Make current_material that of PROPS, checked; code /= 0 (with message) if PROPS or the sizes are
  !> invalid. Handing the material over by reference (current_material) avoids copying it per call.
  subroutine prepare_material(props, nprops, nstatv, ntens, ndi, code, message)
    integer, intent(in) :: nprops, nstatv, ntens, ndi
    real(real64), intent(in) :: props(nprops)
    integer, intent(out) :: code
    character(len=message_len), intent(out) :: message
    integer :: n
    logical :: same_sizes, same_frames

    code = 0
    n = min(nprops, nprops_normal)
    same_sizes = cache%valid .and. cache%nprops == nprops .and. cache%ntens == ntens .and. &
                 cache%ndi == ndi .and. cache%nstatv == nstatv
    if (same_sizes) then
      if (all(props(1:n) == cache%props(1:n))) return
    end if
    call check_props(props, nprops, nstatv, ntens, ndi, code, message)
    if (code /= 0) then
      cache%valid = .false.
      return
    end if
    same_frames = same_sizes .and. all(props(2:n) == cache%props(2:n))
    if (.not. same_frames) call frames_from_props(props, nprops, frames(1), frames(2))
    current_material = material_new(frames(1), frames(2), props(ip_phi))
    cache%valid = .true.
    cache%nprops = nprops; cache%ntens = ntens; cache%ndi = ndi; cache%nstatv = nstatv
    cache%props = 0
    cache%props(1:n) = props(1:n)
  end subroutine prepare_material

end module ccix_material_cache
