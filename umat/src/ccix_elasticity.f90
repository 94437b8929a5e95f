!> Transversely isotropic elasticity of one solid frame (theory.md sec. 4.2, Yin et al. 2021 eq. 21).
module ccix_elasticity
  use, intrinsic :: iso_fortran_env, only: real64
  use ccix_tensor, only: voigt_i, voigt_j, mandel_w, kron => kronecker
  implicit none
  private
  public :: ti_stiffness_mandel

contains

  !> Mandel 6x6 stiffness for any unit bedding normal n (theory.md sec. 4.2):
  !>   C_ijkl = lam d_ij d_kl + muT (d_ik d_jl + d_il d_jk) + a (d_ij n_k n_l + n_i n_j d_kl)
  !>          + b n_i n_j n_k n_l + (muL - muT)(d_jl n_i n_k + d_ik n_j n_l + d_il n_j n_k + d_jk n_i n_l)
  !> Built in global axes from n, without rotation matrices. mu_T = mu_L, a = b = 0 is isotropic.
  pure recursive function ti_stiffness_mandel(lam, mu_t, mu_l, a, b, n) result(c)
    real(real64), intent(in) :: lam, mu_t, mu_l, a, b, n(3)
    real(real64) :: c(6, 6)
    integer :: p, q, i, j, k, l
    real(real64) :: cijkl
    do q = 1, 6
      k = voigt_i(q); l = voigt_j(q)
      do p = q, 6
        i = voigt_i(p); j = voigt_j(p)
        cijkl = lam * kron(i, j) * kron(k, l) &
              + mu_t * (kron(i, k) * kron(j, l) + kron(i, l) * kron(j, k)) &
              + a * (kron(i, j) * n(k) * n(l) + n(i) * n(j) * kron(k, l)) &
              + b * n(i) * n(j) * n(k) * n(l) &
              + (mu_l - mu_t) * (kron(j, l) * n(i) * n(k) + kron(i, k) * n(j) * n(l) &
                                 + kron(i, l) * n(j) * n(k) + kron(j, k) * n(i) * n(l))
        c(p, q) = cijkl * mandel_w(p) * mandel_w(q)
        c(q, p) = c(p, q)
      end do
    end do
  end function ti_stiffness_mandel

end module ccix_elasticity
