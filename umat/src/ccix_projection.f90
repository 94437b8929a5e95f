!> The rank-four projection tensor that maps the real stress of a frame to its fictitious stress
!> (theory.md sec. 1.2, Yin et al. 2021 eq. 24):
!>   P = c1 I + (c2/2)(m(+)m + m(-)m) + (c3/4)(1(+)m + m(+)1 + 1(-)m + m(-)1),   m = n (x) n
!> so that sigma' = P:sigma = c1 sigma + c2 (n.sigma.n) m + (c3/2)[n (x) sigma n + sigma n (x) n],
!> in Walpole's basis of n (ccix_walpole).
module ccix_projection
  use, intrinsic :: iso_fortran_env, only: real64
  use ccix_walpole, only: ti_t
  implicit none
  private
  public :: ti_projection

contains

  !> P:X = c1 X + c2 (m:X) m + (c3/2)(m X + X m) on the basis of ccix_walpole (as in ccix_elasticity):
  !> P:u1 = c1 u1, P:u2 = (c1 + c2 + c3) u2, P:w = c1 w, P:s = (c1 + c3/2) s; the bedding-axes diagonal
  !> of theory.md sec. 1.2. c1 = 1, c2 = c3 = 0 gives the identity (the soft frame).
  pure recursive function ti_projection(c1, c2, c3) result(p)
    real(real64), intent(in) :: c1, c2, c3
    type(ti_t) :: p
    p%a11 = c1
    p%a12 = 0
    p%a22 = c1 + c2 + c3
    p%a5 = c1
    p%a6 = c1 + c3 / 2
  end function ti_projection

end module ccix_projection
