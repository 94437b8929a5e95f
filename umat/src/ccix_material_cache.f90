!> The checked material of a PROPS vector, for one UMAT call.
!>
!> Deriving the two frames from PROPS (stiffness, projection tensor, their simultaneous
!> diagonalisation: theory.md sec. 3.3) costs about four viscoplastic steps (docs/performance.md,
!> "UMAT: time per call"). Two builds of this one source therefore differ, and only in speed:
!>
!> - The single-file UMATs that hosts compile themselves (camclay9_umat.f90, camclay9_umat_abaqus.for)
!>   are written by the build without the lines that start with the OpenMP sentinel "!$": they keep no
!>   module state at all, and every call derives its material into the caller's own storage. No flag a
!>   host compiles them with (none, -fopenmp-simd, -qopenmp-stubs, -fno-automatic) can make two threads
!>   share anything.
!> - The libraries and the object file built by CMake compile this file with OpenMP (umat/CMakeLists.txt),
!>   which activates the "!$" lines: each thread keeps the material of the last PROPS it saw in a
!>   threadprivate variable, which gfortran places in thread-local storage (one copy per thread,
!>   whatever created the thread; no OpenMP runtime call is made). The key is the whole PROPS vector
!>   and the sizes; PROPS(1) (phi, which a host may vary per element) does not enter the frames, so a
!>   change of phi alone rebuilds only the mixture (material_set_phi).
!>
!> Both give the same material bit for bit: the same routines compute it from the same PROPS.
module ccix_material_cache
  use, intrinsic :: iso_fortran_env, only: real64
  use ccix_props, only: check_props, frames_from_props, message_len, nprops_normal, ip_phi
  use ccix_mixture, only: material_t, material_set_phi, hard, soft
  implicit none
  private

!$ type :: cache_t
!$   logical :: valid = .false.
!$   integer :: nprops = 0, ntens = 0, ndi = 0, nstatv = 0
!$   real(real64) :: props(nprops_normal) = 0
!$   type(material_t) :: material
!$ end type cache_t
!$ type(cache_t), save, target :: cache
!$omp threadprivate(cache)

  public :: material_for

contains

  !> mat => the material of PROPS, checked. own is storage of the caller (declared TARGET there), where
  !> the material is derived when there is no cache. code /= 0 (with message) if PROPS or the sizes are
  !> invalid: then mat is not meaningful.
  recursive subroutine material_for(props, nprops, nstatv, ntens, ndi, own, mat, code, message)
    integer, intent(in) :: nprops, nstatv, ntens, ndi
    real(real64), intent(in) :: props(nprops)
    type(material_t), intent(inout), target :: own
    type(material_t), pointer, intent(out) :: mat
    integer, intent(out) :: code
    character(len=message_len), intent(out) :: message
    integer :: n
    logical :: keep_frames

    code = 0
    n = min(nprops, nprops_normal)
    mat => own
    keep_frames = .false.
!$  mat => cache%material
!$  if (cache%valid .and. cache%nprops == nprops .and. cache%ntens == ntens .and. cache%ndi == ndi .and. &
!$      cache%nstatv == nstatv) then
!$    if (all(props(1:n) == cache%props(1:n))) return
!$    keep_frames = all(props(2:n) == cache%props(2:n))
!$  end if
!$  cache%valid = .false.
    call check_props(props, nprops, nstatv, ntens, ndi, code, message)
    if (code /= 0) return
    if (.not. keep_frames) call frames_from_props(props, nprops, mat%frames(hard), mat%frames(soft))
    call material_set_phi(mat, props(ip_phi))
!$  cache%valid = .true.
!$  cache%nprops = nprops; cache%ntens = ntens; cache%ndi = ndi; cache%nstatv = nstatv
!$  cache%props = 0
!$  cache%props(1:n) = props(1:n)
  end subroutine material_for

end module ccix_material_cache
