!> The material cache (ccix_material_cache) is threadprivate: 4 OpenMP threads integrating points of two
!> different materials at once (alternating job by job, so every thread keeps switching material) give,
!> bit for bit, the results of the same jobs run serially. A cache shared between threads would hand
!> one thread the other's frames (stiffness, normal, pc0) between its prepare and integrate.
program test_thread_cache
  use, intrinsic :: iso_fortran_env, only: real64, output_unit
  use omp_lib, only: omp_get_max_threads
  use test_support
  implicit none
  integer, parameter :: njobs = 4000
  real(real64) :: serial(6, njobs), parallel(6, njobs)
  integer :: i, nbad

  do i = 1, njobs
    serial(:, i) = job(i)
  end do
  !$omp parallel do num_threads(4) schedule(static, 1)
  do i = 1, njobs
    parallel(:, i) = job(i)
  end do
  !$omp end parallel do
  nbad = count(any(serial /= parallel, dim=1))
  write (output_unit, '(a,i0,a,i0,a,i0)') 'jobs ', njobs, ' (max threads ', omp_get_max_threads(), &
    '): differing from serial ', nbad
  call check_true('threaded = serial, bit for bit', nbad == 0)
  call check_true('the two materials differ', any(serial(:, 1) /= serial(:, 2)))
  call finish('test_thread_cache')

contains

  !> Five viscoplastic steps of material mod(i, 2) (theta 0 vs 60 degrees, pc0_hard 2 vs 3 MPa).
  function job(i) result(s)
    integer, intent(in) :: i
    real(real64) :: s(6), props(23), v(nstatv_test), d(6, 6), pn, e(6), de(6), th
    integer :: k
    th = merge(0.0_real64, 60.0_real64, mod(i, 2) == 0) * pi / 180
    props = props_with(0.5_real64, [sin(th), 0.0_real64, cos(th)])
    if (mod(i, 2) == 1) props(12) = 3
    s = [-35.0_real64, -35.0_real64, -35.0_real64, 0.0_real64, 0.0_real64, 0.0_real64]
    v = 0; e = 0
    de = 1.0e-5_real64 * [-1.0_real64, 0.5_real64, -3.0_real64, 0.7_real64, -0.2_real64, 0.4_real64]
    do k = 1, 5
      pn = 1
      call call_umat(props, 6, s, v, e, de, 100.0_real64, d, pn)
      e = e + de
    end do
  end function job

end program test_thread_cache
