!> Transversely isotropic fourth-order tensors about one axis n, in Walpole's basis (Walpole 1984,
!> Proc. R. Soc. Lond. A 391, 149-179). Every tensor of a frame is of that kind: the stiffness C
!> (theory.md sec. 4.2), the projection P (sec. 1.2), K = (2/9) 1(x)1 + (3/M^2) I_dev and H = P:K:P
!> (sec. 1.3); the soft frame's are isotropic, the special case for any n.
!>
!> The basis. With m = n(x)n, p = 1 - m and (t1, t2, n) orthonormal, the six Mandel vectors
!>     u1 = p/sqrt2,            u2 = m,
!>     w1 = (t1(x)t1 - t2(x)t2)/sqrt2,   w2 = (t1(x)t2 + t2(x)t1)/sqrt2,
!>     s1 = (n(x)t1 + t1(x)n)/sqrt2,     s2 = (n(x)t2 + t2(x)n)/sqrt2
!> are orthonormal: the columns of an orthogonal 6 x 6 matrix Q. Walpole's projectors are
!> E1 = u1(x)u1, E2 = u2(x)u2, E3 = u1(x)u2, E4 = u2(x)u1, E5 = w1(x)w1 + w2(x)w2 (shear in the
!> bedding plane) and E6 = s1(x)s1 + s2(x)s2 (shear in the planes that contain n). A tensor with both
!> symmetries that is transversely isotropic about n is
!>     A = a11 E1 + a22 E2 + a12 (E3 + E4) + a5 E5 + a6 E6 = Q diag([a11 a12; a12 a22], a5, a5, a6, a6) Q^T,
!> and since the E's multiply like the entries of that block matrix (Walpole 1984), sums,
!> products and inverses act on the 2 x 2 block [a11 a12; a12 a22] and the scalars a5, a6 alone.
!>
!> The coefficients, from the index forms of theory.md, applied to u1, u2, w, s:
!>   C: [2(lam + mu_T), sqrt2 (lam + a); sqrt2 (lam + a), lam + 2 mu_T + 2a + b + 4(mu_L - mu_T)],
!>      a5 = 2 mu_T, a6 = 2 mu_L   (the bedding-axes matrix of theory.md sec. 4.2 and ccix_props);
!>   P: [c1, 0; 0, c1 + c2 + c3], a5 = c1, a6 = c1 + c3/2   (theory.md sec. 1.2, in bedding axes);
!>   K: (3/M^2) I + (2/9 - 1/M^2) 1(x)1 with 1 = sqrt2 u1 + u2: block (3/M^2) I2 + (2/9 - 1/M^2)
!>      [2, sqrt2; sqrt2, 1], a5 = a6 = 3/M^2.
!>
!> t1 is e_k x n normalised, e_k the coordinate axis with the smallest |n_k| (|e_k x n|^2 >= 2/3), and
!> t2 = n x t1. When n lies in the 1-2 plane (n3 = 0, as plane strain requires) or n = e3, every basis
!> vector then has either only in-plane (11, 22, 33, 12) or only out-of-plane (13, 23) components, so
!> the decoupling of theory.md sec. 4.1 holds exactly, not only to round-off (umat.test_walpole).
module ccix_walpole
  use, intrinsic :: iso_fortran_env, only: real64
  use ccix_tensor, only: sqrt2, one6
  implicit none
  private

  !> A symmetric transversely isotropic tensor: the block on (u1, u2) and the two shear coefficients.
  type, public :: ti_t
    real(real64) :: a11, a12, a22   !< block [a11 a12; a12 a22] on (u1, u2)
    real(real64) :: a5              !< on E5: (w1, w2), shear in the bedding plane
    real(real64) :: a6              !< on E6: (s1, s2), shear in planes containing n
  end type ti_t

  public :: walpole_basis, ti_mandel, ti_abaqus, ti_mix, ti_inverse, ti_sandwich, ti_apply, ti_trace, sym_eigen2

contains

  !> Q = [u1 u2 w1 w2 s1 s2] (Mandel columns) for the unit axis n.
  pure recursive subroutine walpole_basis(n, q)
    real(real64), intent(in) :: n(3)
    real(real64), intent(out) :: q(6, 6)
    real(real64) :: a(3), b(3), t
    real(real64), parameter :: h = 0.7071067811865476_real64   ! 1/sqrt2
    ! a = t1 = e_k x n / |e_k x n| for the first k of smallest |n_k|, b = t2 = n x t1.
    if (abs(n(1)) <= abs(n(2)) .and. abs(n(1)) <= abs(n(3))) then
      a(1) = 0
      a(2) = -n(3)
      a(3) = n(2)
    else if (abs(n(2)) <= abs(n(3))) then
      a(1) = n(3)
      a(2) = 0
      a(3) = -n(1)
    else
      a(1) = -n(2)
      a(2) = n(1)
      a(3) = 0
    end if
    t = 1 / sqrt(a(1)**2 + a(2)**2 + a(3)**2)
    a = t * a
    b(1) = n(2) * a(3) - n(3) * a(2)
    b(2) = n(3) * a(1) - n(1) * a(3)
    b(3) = n(1) * a(2) - n(2) * a(1)
    ! Mandel components, written one by one (array constructors cost a temporary each at -O2):
    ! (x(x)x)_ii, sqrt2 x_i x_j; sym(x(x)y)_ii = x_i y_i, (x_i y_j + x_j y_i)/sqrt2 (i /= j).
    q(1, 2) = n(1)**2
    q(2, 2) = n(2)**2
    q(3, 2) = n(3)**2
    q(4, 2) = sqrt2 * n(1) * n(2)
    q(5, 2) = sqrt2 * n(1) * n(3)
    q(6, 2) = sqrt2 * n(2) * n(3)
    q(1, 1) = h * (1 - q(1, 2))
    q(2, 1) = h * (1 - q(2, 2))
    q(3, 1) = h * (1 - q(3, 2))
    q(4, 1) = -n(1) * n(2)
    q(5, 1) = -n(1) * n(3)
    q(6, 1) = -n(2) * n(3)
    q(1, 3) = h * (a(1)**2 - b(1)**2)
    q(2, 3) = h * (a(2)**2 - b(2)**2)
    q(3, 3) = h * (a(3)**2 - b(3)**2)
    q(4, 3) = a(1) * a(2) - b(1) * b(2)
    q(5, 3) = a(1) * a(3) - b(1) * b(3)
    q(6, 3) = a(2) * a(3) - b(2) * b(3)
    call sym_pair(a, b, q(:, 4))
    call sym_pair(n, a, q(:, 5))
    call sym_pair(n, b, q(:, 6))
  end subroutine walpole_basis

  !> v = (x (x) y + y (x) x)/sqrt2 in Mandel form.
  pure recursive subroutine sym_pair(x, y, v)
    real(real64), intent(in) :: x(3), y(3)
    real(real64), intent(out) :: v(6)
    v(1) = sqrt2 * x(1) * y(1)
    v(2) = sqrt2 * x(2) * y(2)
    v(3) = sqrt2 * x(3) * y(3)
    v(4) = x(1) * y(2) + x(2) * y(1)
    v(5) = x(1) * y(3) + x(3) * y(1)
    v(6) = x(2) * y(3) + x(3) * y(2)
  end subroutine sym_pair

  !> The Mandel 6 x 6 matrix Q diag(A) Q^T of a, written as a5 I + (a11 - a5) u1 u1^T + a12 (u1 u2^T +
  !> u2 u1^T) + (a22 - a5) u2 u2^T + (a6 - a5) E6 (E1 + E2 + E5 + E6 = I): no term of E5, and an
  !> isotropic tensor comes out isotropic (P = I exactly). Exactly symmetric.
  pure recursive function ti_mandel(a, q) result(m)
    type(ti_t), intent(in) :: a
    real(real64), intent(in) :: q(6, 6)
    real(real64) :: m(6, 6)
    real(real64) :: x1(6), x2(6), x5(6), x6(6)
    integer :: i, j
    x1 = (a%a11 - a%a5) * q(:, 1) + a%a12 * q(:, 2)
    x2 = a%a12 * q(:, 1) + (a%a22 - a%a5) * q(:, 2)
    x5 = (a%a6 - a%a5) * q(:, 5)
    x6 = (a%a6 - a%a5) * q(:, 6)
    do j = 1, 6
      do i = j, 6
        m(i, j) = q(i, 1) * x1(j) + q(i, 2) * x2(j) + q(i, 5) * x5(j) + q(i, 6) * x6(j)
        m(j, i) = m(i, j)
      end do
      m(j, j) = m(j, j) + a%a5
    end do
  end function ti_mandel

  !> A as an Abaqus DDSDDE (first n slots, engineering shear): the entries of ti_mandel divided by
  !> w_i w_j (w = 1 normal, sqrt2 shear; theory.md sec. 1.1), built directly for the n x n block.
  pure recursive subroutine ti_abaqus(a, q, n, dd)
    type(ti_t), intent(in) :: a
    real(real64), intent(in) :: q(6, 6)
    integer, intent(in) :: n
    real(real64), intent(out) :: dd(n, n)
    real(real64), parameter :: h = 0.7071067811865476_real64   ! 1/sqrt2
    real(real64), parameter :: w_inv(6) = [1.0_real64, 1.0_real64, 1.0_real64, h, h, h]
    real(real64) :: x1(6), x2(6), x5(6), x6(6), qs(6, 4)
    integer :: i, j
    do i = 1, n
      qs(i, 1) = w_inv(i) * q(i, 1)
      qs(i, 2) = w_inv(i) * q(i, 2)
      qs(i, 3) = w_inv(i) * q(i, 5)
      qs(i, 4) = w_inv(i) * q(i, 6)
      x1(i) = (a%a11 - a%a5) * qs(i, 1) + a%a12 * qs(i, 2)
      x2(i) = a%a12 * qs(i, 1) + (a%a22 - a%a5) * qs(i, 2)
      x5(i) = (a%a6 - a%a5) * qs(i, 3)
      x6(i) = (a%a6 - a%a5) * qs(i, 4)
    end do
    do j = 1, n
      do i = j, n
        dd(i, j) = qs(i, 1) * x1(j) + qs(i, 2) * x2(j) + qs(i, 3) * x5(j) + qs(i, 4) * x6(j)
        dd(j, i) = dd(i, j)
      end do
      dd(j, j) = dd(j, j) + a%a5 * w_inv(j)**2
    end do
  end subroutine ti_abaqus

  !> x A + y B.
  pure recursive function ti_mix(x, a, y, b) result(c)
    real(real64), intent(in) :: x, y
    type(ti_t), intent(in) :: a, b
    type(ti_t) :: c
    c%a11 = x * a%a11 + y * b%a11
    c%a12 = x * a%a12 + y * b%a12
    c%a22 = x * a%a22 + y * b%a22
    c%a5 = x * a%a5 + y * b%a5
    c%a6 = x * a%a6 + y * b%a6
  end function ti_mix

  !> A^-1: the inverse block and the reciprocal shear coefficients (A positive definite).
  pure recursive function ti_inverse(a) result(b)
    type(ti_t), intent(in) :: a
    type(ti_t) :: b
    real(real64) :: rdet
    rdet = 1 / (a%a11 * a%a22 - a%a12**2)
    b%a11 = a%a22 * rdet
    b%a12 = -a%a12 * rdet
    b%a22 = a%a11 * rdet
    b%a5 = 1 / a%a5
    b%a6 = 1 / a%a6
  end function ti_inverse

  !> B:A:B for symmetric A and B (block products B A B; a5 b5^2, a6 b6^2).
  pure recursive function ti_sandwich(b, a) result(c)
    type(ti_t), intent(in) :: b, a
    type(ti_t) :: c
    real(real64) :: x11, x12, x21, x22
    x11 = a%a11 * b%a11 + a%a12 * b%a12     ! X = A B
    x12 = a%a11 * b%a12 + a%a12 * b%a22
    x21 = a%a12 * b%a11 + a%a22 * b%a12
    x22 = a%a12 * b%a12 + a%a22 * b%a22
    c%a11 = b%a11 * x11 + b%a12 * x21       ! B X
    c%a12 = b%a11 * x12 + b%a12 * x22
    c%a22 = b%a12 * x12 + b%a22 * x22
    c%a5 = b%a5 * a%a5 * b%a5
    c%a6 = b%a6 * a%a6 * b%a6
  end function ti_sandwich

  !> y = A:X for a Mandel vector x, without Q (a subroutine: an array-valued function passes its result
  !> through a descriptor, which costs as much as the product here). Every such A is also
  !>   A:X = al1 tr(X) 1 + al2 X + al3 (tr(X) m + (m:X) 1) + al4 (m:X) m + al5 (m X + X m)
  !> (the shape of theory.md sec. 4.2, with al = (lam, 2 mu_T, a, b, 2 (mu_L - mu_T)) for C), and applied
  !> to u1, u2, w, s as in ccix_elasticity this gives a11 = 2 al1 + al2, a12 = sqrt2 (al1 + al3),
  !> a22 = al1 + al2 + 2 al3 + al4 + 2 al5, a5 = al2, a6 = al2 + al5, solved here for al. n is the axis
  !> (unit), mh = m in Mandel form.
  pure recursive subroutine ti_apply(a, n, mh, x, y)
    type(ti_t), intent(in) :: a
    real(real64), intent(in) :: n(3), mh(6), x(6)
    real(real64), intent(out) :: y(6)
    real(real64) :: al1, al3, al4, al5, tr, mx, s0, s1, t2, tr2, xn1, xn2, xn3
    real(real64), parameter :: h = 0.7071067811865476_real64   ! 1/sqrt2
    al1 = (a%a11 - a%a5) / 2
    al3 = h * a%a12 - al1
    al5 = a%a6 - a%a5
    al4 = a%a22 - al1 - a%a5 - 2 * al3 - 2 * al5
    tr = x(1) + x(2) + x(3)
    mx = mh(1) * x(1) + mh(2) * x(2) + mh(3) * x(3) + mh(4) * x(4) + mh(5) * x(5) + mh(6) * x(6)
    ! X n, with X_12 = x(4)/sqrt2, X_13 = x(5)/sqrt2, X_23 = x(6)/sqrt2
    xn1 = x(1) * n(1) + h * (x(4) * n(2) + x(5) * n(3))
    xn2 = x(2) * n(2) + h * (x(4) * n(1) + x(6) * n(3))
    xn3 = x(3) * n(3) + h * (x(5) * n(1) + x(6) * n(2))
    s0 = al1 * tr + al3 * mx
    s1 = al3 * tr + al4 * mx
    ! m X + X m = n (x) Xn + Xn (x) n
    t2 = 2 * al5
    tr2 = sqrt2 * al5
    y(1) = a%a5 * x(1) + s1 * mh(1) + s0 + t2 * n(1) * xn1
    y(2) = a%a5 * x(2) + s1 * mh(2) + s0 + t2 * n(2) * xn2
    y(3) = a%a5 * x(3) + s1 * mh(3) + s0 + t2 * n(3) * xn3
    y(4) = a%a5 * x(4) + s1 * mh(4) + tr2 * (n(1) * xn2 + n(2) * xn1)
    y(5) = a%a5 * x(5) + s1 * mh(5) + tr2 * (n(1) * xn3 + n(3) * xn1)
    y(6) = a%a5 * x(6) + s1 * mh(6) + tr2 * (n(2) * xn3 + n(3) * xn2)
  end subroutine ti_apply

  !> Trace of the Mandel matrix of A (invariant: Q is orthogonal).
  pure recursive real(real64) function ti_trace(a) result(t)
    type(ti_t), intent(in) :: a
    t = a%a11 + a%a22 + 2 * (a%a5 + a%a6)
  end function ti_trace

  !> Eigen-decomposition of the symmetric 2 x 2 matrix [a11 a12; a12 a22] = R diag(w) R^T with the
  !> rotation R = [c s; -s c]: one Jacobi rotation, exact for 2 x 2 (Golub & Van Loan, Matrix
  !> Computations, 4th ed., sec. 8.5.2, sym.schur2). There t = tan of the angle is the smaller root of
  !> t^2 + 2 theta t - 1 = 0, theta = (a22 - a11)/(2 a12), c = 1/sqrt(1 + t^2), s = t c; the same
  !> numbers are written here with h = a22 - a11, e = 2 a12, r = sqrt(h^2 + e^2) and p = |h| + r as
  !>     t = sign(h) e / p,   c = p / sqrt(p^2 + e^2),   s = sign(h) e / sqrt(p^2 + e^2),
  !> which needs two square roots and one division in sequence instead of five such operations, and
  !> no theta (whose square overflowed for a12 tiny against the gap). h and e are scaled by their
  !> larger magnitude where their squares could overflow or underflow.
  pure recursive subroutine sym_eigen2(a11, a12, a22, w, c, s)
    real(real64), intent(in) :: a11, a12, a22
    real(real64), intent(out) :: w(2), c, s
    real(real64) :: h, e, m, r, p, rn, t
    if (a12 == 0) then
      c = 1
      s = 0
      w(1) = a11
      w(2) = a22
      return
    end if
    h = a22 - a11
    e = 2 * a12
    m = max(abs(h), abs(e))
    if (m > 1.0e150_real64 .or. m < 1.0e-150_real64) then
      h = h / m
      e = e / m
    end if
    r = sqrt(h**2 + e**2)
    p = abs(h) + r
    rn = 1 / sqrt(p**2 + e**2)
    c = p * rn
    s = sign(1.0_real64, h) * e * rn
    t = sign(1.0_real64, h) * e / p
    w(1) = a11 - t * a12
    w(2) = a22 + t * a12
  end subroutine sym_eigen2

end module ccix_walpole
