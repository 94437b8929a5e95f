!> The UMAT itself stops on invalid PROPS with the message of the check routine (CTest matches the
!> message; the exit status is non-zero).
program umat_stops_on_bad_props
  use, intrinsic :: iso_fortran_env, only: real64
  use test_support
  implicit none
  real(real64) :: p(23), s(6), v(nstatv_test), d(6, 6), pn
  p = props_with(0.5_real64, [0.0_real64, 0.0_real64, 1.0_real64])
  p(17) = 0
  s = -35; s(4:6) = 0; v = 0; pn = 1
  call call_umat(p, 6, s, v, 0 * s, 0 * s, 1.0_real64, d, pn)
  print '(a)', 'umat_stops_on_bad_props: the UMAT returned instead of stopping'
end program umat_stops_on_bad_props
