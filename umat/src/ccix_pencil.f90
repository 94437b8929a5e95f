!> The pencil (H, C^-1) of one frame diagonalised together, in closed form, and the products with its
!> eigenvectors that the return map needs: V^T C^-1 V = I, V^T H V = diag(lambda_h) (ccix_frame,
!> theory.md sec. 3.3). It replaces a Cholesky factorisation of the 6 x 6 C and cyclic Jacobi on
!> L^T H L (about 4.5 us per material): the single-file UMAT derives the material in every call
!> (ccix_material_cache), so this had to be cheap.
!>
!> The closed form. C, P, K and H are transversely isotropic about the bedding normal n (isotropic in
!> the soft frame), so in Walpole's orthonormal basis Q = [u1 u2 w1 w2 s1 s2] of n (ccix_walpole;
!> Walpole 1984) each is Q diag(A_b, a5, a5, a6, a6) Q^T with a 2 x 2 block A_b on (u1, u2). Take
!>     V = Q B,   B = diag(W, sqrt(c5), sqrt(c5), sqrt(c6), sqrt(c6)),
!> c5 = 2 mu_T, c6 = 2 mu_L the shear coefficients of C. Then
!>     V^T C^-1 V = diag(W^T C_b^-1 W, 1, 1, 1, 1),   V^T H V = diag(W^T H_b W, c5 h5, c5 h5, c6 h6, c6 h6):
!> the shear pairs are generalised eigenvectors of (H, C^-1), each eigenvalue the product c h of the
!> pair's coefficients, and what is left is the 2 x 2 problem W^T C_b^-1 W = I, W^T H_b W =
!> diag(lambda_1, lambda_2). It is solved as the 6 x 6 one was: C_b = L L^T (Cholesky),
!> L^T H_b L = R diag(lambda_1, lambda_2) R^T (one Jacobi rotation, ccix_walpole's sym_eigen2),
!> W = L R, W^-1 = R^T L^-1; and V^-1 = B^-1 Q^T. Since P:1 and H:1 lie in the span of u1 and u2
!> (1 = sqrt2 u1 + u2, so P:1 = Q (P_b (sqrt2, 1), 0, 0, 0, 0)), b = V^T P:1 and h1 = V^T H:1 have only
!> two non-zero components, W^T P_b (sqrt2, 1) and W^T H_b (sqrt2, 1). The coefficients: C in
!> ccix_elasticity, P in ccix_projection, K = (3/M^2) I + (2/9 - 1/M^2) 1(x)1 (theory.md sec. 1.3) with
!> the block (3/M^2) I2 + (2/9 - 1/M^2) [2 sqrt2; sqrt2 1] and a5 = a6 = 3/M^2, and H = P:K:P as
!> products of coefficients (ccix_walpole's ti_sandwich): H_b = P_b K_b P_b, h5 = c1^2 (3/M^2),
!> h6 = (c1 + c3/2)^2 (3/M^2).
!>
!> V and V^-1 are never formed: products go through Q and B (v_times, v_inv_times, v_inv_t_times), at
!> the cost of the 6 x 6 products with V they replace.
module ccix_pencil
  use, intrinsic :: iso_fortran_env, only: real64
  use ccix_tensor, only: sqrt2
  use ccix_walpole, only: ti_t, ti_sandwich, sym_eigen2
  implicit none
  private

  !> The eigenvectors V = Q B, B = diag(W, r(3:6)), of the pencil, with what the return map needs.
  type, public :: pencil_t
    real(real64) :: w(2, 2), w_inv(2, 2)  !< W and W^-1: B on (u1, u2)
    real(real64) :: r(6), r_inv(6)        !< B on the shear pairs (3:6) and its inverse; 1 in (1:2)
    real(real64) :: lambda_h(6)           !< generalised eigenvalues of (H, C^-1), >= 0
    real(real64) :: b(6)                  !< V^T P:1
    real(real64) :: h1(6)                 !< V^T H:1
  end type pencil_t

  public :: pencil_diagonalise, v_times, v_inv_times, v_inv_t_times

contains

  !> The pencil (H, C^-1) of C and P with H = P:K:P (K of theory.md sec. 1.3 with M), in the closed form
  !> derived at the top of this module.
  !>
  !> Where C is isotropic and P = I (the soft frame) the 2 x 2 problem needs no computing: C and K share
  !> the hydrostatic and deviatoric directions e_h = (sqrt2, 1)/sqrt3 and e_d = (1, -sqrt2)/sqrt3 of the
  !> block (1 = sqrt3 e_h), with C = 3 kappa, 2 mu and K = 2/3, 3/M^2 on them (kappa = lam + 2 mu/3), so
  !> W = [sqrt(3 kappa) e_h, sqrt(2 mu) e_d], W^-1 = W^T C_b^-1 = [e_h^T / sqrt(3 kappa); e_d^T / sqrt(2 mu)],
  !> lambda = 2 kappa, 6 mu/M^2, b = W^T (sqrt2, 1) = (3 sqrt(kappa), 0), h1 = (2 sqrt(kappa), 0).
  pure recursive subroutine pencil_diagonalise(cw, pw, m_slope, isotropic, pe)
    type(ti_t), intent(in) :: cw, pw     !< C and P in Walpole's basis
    real(real64), intent(in) :: m_slope  !< M
    logical, intent(in) :: isotropic     !< C isotropic and P = I
    type(pencil_t), intent(out) :: pe
    type(ti_t) :: kw
    real(real64) :: m2, k1
    ! K = (2/9) 1(x)1 + (3/M^2) I_dev = (3/M^2) I + (2/9 - 1/M^2) 1(x)1, 1 = sqrt2 u1 + u2 (sec. 1.3)
    m2 = 1 / m_slope**2
    k1 = 2.0_real64 / 9.0_real64 - m2
    kw%a11 = 3 * m2 + 2 * k1
    kw%a12 = sqrt2 * k1
    kw%a22 = 3 * m2 + k1
    kw%a5 = 3 * m2
    kw%a6 = kw%a5
    if (isotropic) then
      call isotropic_pencil(cw, kw, pe)
    else
      call ti_pencil(cw, pw, kw, pe)
    end if
  end subroutine pencil_diagonalise

  !> pencil_diagonalise where C is isotropic and P = I: W, W^-1, lambda, b and h1 as written above.
  pure recursive subroutine isotropic_pencil(cw, kw, pe)
    type(ti_t), intent(in) :: cw, kw     !< C and K in Walpole's basis
    type(pencil_t), intent(out) :: pe
    real(real64), parameter :: rsqrt3 = 0.5773502691896258_real64   ! 1/sqrt3
    real(real64) :: sk, sg, r5, i5, kappa
    associate (w => pe%w, w_inv => pe%w_inv, lambda_h => pe%lambda_h, b => pe%b, h1 => pe%h1)
      kappa = (2 * cw%a11 + 2 * sqrt2 * cw%a12 + cw%a22) * (1.0_real64 / 9)   ! e_h.C_b.e_h/3
      sk = sqrt(kappa)                        ! sqrt(3 kappa) e_h = sk (sqrt2, 1)
      r5 = sqrt(cw%a5)                        ! sqrt(2 mu)
      sg = r5 * rsqrt3                        ! sqrt(2 mu) e_d = sg (1, -sqrt2)
      i5 = 1 / (sk * r5)                      ! one division for 1/sk and 1/r5
      w(1, 1) = sqrt2 * sk
      w(2, 1) = sk
      w(1, 2) = sg
      w(2, 2) = -sqrt2 * sg
      w_inv(1, 1) = sqrt2 * (r5 * i5 / 3)
      w_inv(1, 2) = r5 * i5 / 3
      i5 = sk * i5
      w_inv(2, 1) = i5 * rsqrt3
      w_inv(2, 2) = -sqrt2 * (i5 * rsqrt3)
      call set_shears(r5, r5, i5, i5, cw%a5 * kw%a5, cw%a5 * kw%a5, pe%r, pe%r_inv, lambda_h)
      lambda_h(1) = 2 * kappa
      lambda_h(2) = cw%a5 * kw%a5
      b = 0
      b(1) = 3 * sk
      h1 = 0
      h1(1) = 2 * sk
    end associate
  end subroutine isotropic_pencil

  !> pencil_diagonalise in general: H = P:K:P, the 2 x 2 problem on (u1, u2) by Cholesky and one Jacobi
  !> rotation, the shear pairs from the coefficients.
  pure recursive subroutine ti_pencil(cw, pw, kw, pe)
    type(ti_t), intent(in) :: cw, pw, kw     !< C, P and K in Walpole's basis
    type(pencil_t), intent(out) :: pe
    type(ti_t) :: hw
    real(real64) :: l11, l21, l22, i11, i22, g11, g12, g21, g22, lam2(2), c, s, r5, r6, i5, i6, &
                    p1_b(2), h1_b(2)
    associate (w => pe%w, w_inv => pe%w_inv, lambda_h => pe%lambda_h, b => pe%b, h1 => pe%h1)
      hw = ti_sandwich(pw, kw)                 ! H = P:K:P
      p1_b(1) = sqrt2 * pw%a11 + pw%a12        ! P:1 = P_b (sqrt2, 1)
      p1_b(2) = sqrt2 * pw%a12 + pw%a22
      h1_b(1) = sqrt2 * hw%a11 + hw%a12        ! H:1 = H_b (sqrt2, 1)
      h1_b(2) = sqrt2 * hw%a12 + hw%a22
      ! C_b = L L^T, G = H_b L, L^T H_b L = L^T G = R diag(lam2) R^T, W = L R, W^-1 = R^T L^-1.
      ! L = [l11 0; l21 l22] with l11 = sqrt(c11), l21 = c12/l11, l22 = sqrt(det C_b / c11): the two
      ! square roots and 1/c11 independent of each other.
      l11 = sqrt(cw%a11)
      l22 = sqrt(cw%a11 * cw%a22 - cw%a12**2)   ! sqrt(det C_b), times 1/l11 below
      i11 = l11 / cw%a11
      l21 = cw%a12 * i11
      i22 = l11 / l22
      l22 = l22 * i11
      g11 = hw%a11 * l11 + hw%a12 * l21
      g12 = hw%a12 * l22
      g21 = hw%a12 * l11 + hw%a22 * l21
      g22 = hw%a22 * l22
      call sym_eigen2(l11 * g11 + l21 * g21, l11 * g12 + l21 * g22, l22 * g22, lam2, c, s)
      w(1, 1) = l11 * c
      w(2, 1) = l21 * c - l22 * s
      w(1, 2) = l11 * s
      w(2, 2) = l21 * s + l22 * c
      w_inv(1, 1) = (c + s * l21 * i22) * i11
      w_inv(2, 1) = (s - c * l21 * i22) * i11
      w_inv(1, 2) = -s * i22
      w_inv(2, 2) = c * i22
      r5 = sqrt(cw%a5)
      r6 = sqrt(cw%a6)
      i6 = 1 / (r5 * r6)                     ! one division for 1/r5 and 1/r6
      i5 = r6 * i6
      i6 = r5 * i6
      call set_shears(r5, r6, i5, i6, cw%a5 * hw%a5, cw%a6 * hw%a6, pe%r, pe%r_inv, lambda_h)
      ! H is positive semi-definite: drop round-off below 0.
      lambda_h(1) = max(lam2(1), 0.0_real64)
      lambda_h(2) = max(lam2(2), 0.0_real64)
      b = 0
      b(1) = w(1, 1) * p1_b(1) + w(2, 1) * p1_b(2)   ! W^T P_b (sqrt2, 1)
      b(2) = w(1, 2) * p1_b(1) + w(2, 2) * p1_b(2)
      h1 = 0
      h1(1) = w(1, 1) * h1_b(1) + w(2, 1) * h1_b(2)  ! W^T H_b (sqrt2, 1)
      h1(2) = w(1, 2) * h1_b(1) + w(2, 2) * h1_b(2)
    end associate
  end subroutine ti_pencil

  !> The shear pairs of pencil_diagonalise: r = B, r_inv = B^-1 and lambda_h on (3:6); r = r_inv = 1 on
  !> the block. Component by component: array constructors here cost a store-forwarding stall each.
  pure recursive subroutine set_shears(r5, r6, i5, i6, lam5, lam6, r, r_inv, lambda_h)
    real(real64), intent(in) :: r5, r6, i5, i6, lam5, lam6
    real(real64), intent(out) :: r(6), r_inv(6)
    real(real64), intent(inout) :: lambda_h(6)
    r(1) = 1
    r(2) = 1
    r(3) = r5
    r(4) = r5
    r(5) = r6
    r(6) = r6
    r_inv(1) = 1
    r_inv(2) = 1
    r_inv(3) = i5
    r_inv(4) = i5
    r_inv(5) = i6
    r_inv(6) = i6
    lambda_h(3) = max(lam5, 0.0_real64)
    lambda_h(4) = lambda_h(3)
    lambda_h(5) = max(lam6, 0.0_real64)
    lambda_h(6) = lambda_h(5)
  end subroutine set_shears

  !> x = V xi = Q (B xi). These three products are subroutines written out in full: array-valued
  !> functions pass their results through descriptors, and helper functions for B and Q are not inlined
  !> under gfortran -O2 -fPIC, a host's flags (7 % more instructions per viscoplastic call, measured).
  pure recursive subroutine v_times(q, pe, xi, x)
    real(real64), intent(in) :: q(6, 6), xi(6)
    type(pencil_t), intent(in) :: pe
    real(real64), intent(out) :: x(6)
    real(real64) :: y1, y2
    y1 = pe%w(1, 1) * xi(1) + pe%w(1, 2) * xi(2)
    y2 = pe%w(2, 1) * xi(1) + pe%w(2, 2) * xi(2)
    x = q(:, 1) * y1 + q(:, 2) * y2 + q(:, 3) * (pe%r(3) * xi(3)) + q(:, 4) * (pe%r(4) * xi(4)) &
        + q(:, 5) * (pe%r(5) * xi(5)) + q(:, 6) * (pe%r(6) * xi(6))
  end subroutine v_times

  !> xi = V^-1 x = B^-1 (Q^T x).
  pure recursive subroutine v_inv_times(q, pe, x, xi)
    real(real64), intent(in) :: q(6, 6), x(6)
    type(pencil_t), intent(in) :: pe
    real(real64), intent(out) :: xi(6)
    real(real64) :: z(6)
    integer :: k
    do k = 1, 6
      z(k) = q(1, k) * x(1) + q(2, k) * x(2) + q(3, k) * x(3) + q(4, k) * x(4) &
             + q(5, k) * x(5) + q(6, k) * x(6)
    end do
    xi(1) = pe%w_inv(1, 1) * z(1) + pe%w_inv(1, 2) * z(2)
    xi(2) = pe%w_inv(2, 1) * z(1) + pe%w_inv(2, 2) * z(2)
    xi(3:6) = pe%r_inv(3:6) * z(3:6)
  end subroutine v_inv_times

  !> x = V^-T y = Q (B^-T y).
  pure recursive subroutine v_inv_t_times(q, pe, y, x)
    real(real64), intent(in) :: q(6, 6), y(6)
    type(pencil_t), intent(in) :: pe
    real(real64), intent(out) :: x(6)
    real(real64) :: z1, z2
    z1 = pe%w_inv(1, 1) * y(1) + pe%w_inv(2, 1) * y(2)
    z2 = pe%w_inv(1, 2) * y(1) + pe%w_inv(2, 2) * y(2)
    x = q(:, 1) * z1 + q(:, 2) * z2 + q(:, 3) * (pe%r_inv(3) * y(3)) + q(:, 4) * (pe%r_inv(4) * y(4)) &
        + q(:, 5) * (pe%r_inv(5) * y(5)) + q(:, 6) * (pe%r_inv(6) * y(6))
  end subroutine v_inv_t_times

end module ccix_pencil
