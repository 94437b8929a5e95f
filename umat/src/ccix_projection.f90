!> The rank-four projection tensor that maps the real stress of a frame to its fictitious stress
!> (theory.md sec. 1.2, Yin et al. 2021 eq. 24):
!>   P = c1 I + (c2/2)(m(+)m + m(-)m) + (c3/4)(1(+)m + m(+)1 + 1(-)m + m(-)1),   m = n (x) n
!> so that sigma' = P:sigma = c1 sigma + c2 (n.sigma.n) m + (c3/2)[n (x) sigma n + sigma n (x) n].
module ccix_projection
  use, intrinsic :: iso_fortran_env, only: real64
  use ccix_tensor, only: voigt_i, voigt_j, mandel_w, kron => kronecker
  implicit none
  private
  public :: projection_mandel

contains

  !> Symmetric Mandel 6x6 form of P. c1 = 1, c2 = c3 = 0 gives the identity (the soft frame).
  pure recursive function projection_mandel(c1, c2, c3, n) result(p6)
    real(real64), intent(in) :: c1, c2, c3, n(3)
    real(real64) :: p6(6, 6)
    integer :: p, q, i, j, k, l
    real(real64) :: pijkl, m(3, 3)
    do j = 1, 3
      do i = 1, 3
        m(i, j) = n(i) * n(j)
      end do
    end do
    do q = 1, 6
      k = voigt_i(q); l = voigt_j(q)
      do p = q, 6
        i = voigt_i(p); j = voigt_j(p)
        ! (A(+)B)_ijkl = A_jl B_ik, (A(-)B)_ijkl = A_il B_jk  (Yin et al. 2021, notation)
        pijkl = 0.5_real64 * c1 * (kron(i, k) * kron(j, l) + kron(i, l) * kron(j, k)) &
              + 0.5_real64 * c2 * (m(j, l) * m(i, k) + m(i, l) * m(j, k)) &
              + 0.25_real64 * c3 * (kron(j, l) * m(i, k) + m(j, l) * kron(i, k) &
                                    + kron(i, l) * m(j, k) + m(i, l) * kron(j, k))
        p6(p, q) = pijkl * mandel_w(p) * mandel_w(q)
        p6(q, p) = p6(p, q)
      end do
    end do
  end function projection_mandel

end module ccix_projection
