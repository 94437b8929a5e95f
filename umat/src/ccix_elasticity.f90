!> Transversely isotropic elasticity of one solid frame (theory.md sec. 4.2, Yin et al. 2021 eq. 21),
!> in Walpole's basis of the bedding normal n (ccix_walpole).
module ccix_elasticity
  use, intrinsic :: iso_fortran_env, only: real64
  use ccix_tensor, only: sqrt2
  use ccix_walpole, only: ti_t
  implicit none
  private
  public :: ti_stiffness

contains

  !> The stiffness of theory.md sec. 4.2,
  !>   C_ijkl = lam d_ij d_kl + muT (d_ik d_jl + d_il d_jk) + a (d_ij n_k n_l + n_i n_j d_kl)
  !>          + b n_i n_j n_k n_l + (muL - muT)(d_jl n_i n_k + d_ik n_j n_l + d_il n_j n_k + d_jk n_i n_l),
  !> i.e. C:X = lam tr(X) 1 + 2 muT X + a (tr(X) m + (m:X) 1) + b (m:X) m + 2 (muL - muT)(m X + X m).
  !> Applied to the basis of ccix_walpole (tr u1 = sqrt2, m:u1 = 0, m u1 + u1 m = 0; tr m = m:m = 1,
  !> m m + m m = 2 m; w: traceless, m:w = 0, m w + w m = 0; s: traceless, m:s = 0, m s + s m = s):
  !>   C:u1 = 2(lam + muT) u1 + sqrt2 (lam + a) u2,
  !>   C:u2 = sqrt2 (lam + a) u1 + (lam + 2 muT + 2a + b + 4(muL - muT)) u2,
  !>   C:w = 2 muT w,   C:s = 2 muL s.
  !> mu_T = mu_L, a = b = 0 is isotropic.
  pure recursive function ti_stiffness(lam, mu_t, mu_l, a, b) result(c)
    real(real64), intent(in) :: lam, mu_t, mu_l, a, b
    type(ti_t) :: c
    c%a11 = 2 * (lam + mu_t)
    c%a12 = sqrt2 * (lam + a)
    c%a22 = lam + 2 * mu_t + 2 * a + b + 4 * (mu_l - mu_t)
    c%a5 = 2 * mu_t
    c%a6 = 2 * mu_l
  end function ti_stiffness

end module ccix_elasticity
