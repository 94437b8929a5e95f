!> Reference algebra of the UMAT tests, no longer part of the UMAT: dense LU, Cholesky and Jacobi
!> eigen-decomposition, the index forms of the TI stiffness (theory.md sec. 4.2, Y21 eq. 21) and of the
!> projection tensor (sec. 1.2, Y21 eq. 24), and the simultaneous diagonalisation of (H, C^-1) as the
!> UMAT derived it until it used Walpole's closed form (Cholesky of C, Jacobi on L^T H L): the
!> independent references of the closed forms in umat/src (test_walpole).
module reference_algebra
  use, intrinsic :: iso_fortran_env, only: real64
  use ccix_tensor, only: voigt_i, voigt_j, mandel_w, one6
  implicit none
  private

  public :: identity6, lu_factor, lu_solve, invert6, cholesky_is_spd, cholesky_lower, lower_inverse, &
            jacobi_eigen, kronecker, ti_stiffness_mandel, projection_mandel, h_mandel, jacobi_diagonalisation

contains

  pure function identity6() result(eye)
    real(real64) :: eye(6, 6)
    integer :: i
    eye = 0.0_real64
    do i = 1, 6
      eye(i, i) = 1.0_real64
    end do
  end function identity6

  !> LU factorisation with partial pivoting, in place. ok = .false. on an exactly singular pivot.
  pure subroutine lu_factor(n, a, piv, ok)
    integer, intent(in) :: n
    real(real64), intent(inout) :: a(n, n)
    integer, intent(out) :: piv(n)
    logical, intent(out) :: ok
    integer :: i, j, k, p
    real(real64) :: t, big, rpiv
    ok = .true.
    do k = 1, n
      p = k
      big = abs(a(k, k))
      do i = k + 1, n
        if (abs(a(i, k)) > big) then
          big = abs(a(i, k))
          p = i
        end if
      end do
      piv(k) = p
      if (big == 0.0_real64) then
        ok = .false.
        return
      end if
      if (p /= k) then
        do j = 1, n
          t = a(k, j); a(k, j) = a(p, j); a(p, j) = t
        end do
      end if
      rpiv = 1 / a(k, k)
      do i = k + 1, n
        a(i, k) = a(i, k) * rpiv
      end do
      do j = k + 1, n
        t = a(k, j)
        do i = k + 1, n
          a(i, j) = a(i, j) - a(i, k) * t
        end do
      end do
    end do
  end subroutine lu_factor

  !> Solve with the factors of lu_factor; b is overwritten by the solution.
  pure subroutine lu_solve(n, lu, piv, b)
    integer, intent(in) :: n
    real(real64), intent(in) :: lu(n, n)
    integer, intent(in) :: piv(n)
    real(real64), intent(inout) :: b(n)
    integer :: i, k
    real(real64) :: t
    do k = 1, n
      if (piv(k) /= k) then
        t = b(k); b(k) = b(piv(k)); b(piv(k)) = t
      end if
    end do
    ! Forward (unit lower) and back substitution, column by column (contiguous access).
    do k = 1, n - 1
      t = b(k)
      do i = k + 1, n
        b(i) = b(i) - lu(i, k) * t
      end do
    end do
    do k = n, 1, -1
      b(k) = b(k) / lu(k, k)
      t = b(k)
      do i = 1, k - 1
        b(i) = b(i) - lu(i, k) * t
      end do
    end do
  end subroutine lu_solve

  !> Inverse of a 6x6 matrix; ok = .false. if singular.
  pure subroutine invert6(a, ainv, ok)
    real(real64), intent(in) :: a(6, 6)
    real(real64), intent(out) :: ainv(6, 6)
    logical, intent(out) :: ok
    real(real64) :: lu(6, 6)
    integer :: piv(6), j
    lu = a
    call lu_factor(6, lu, piv, ok)
    ainv = identity6()
    if (.not. ok) return
    do j = 1, 6
      call lu_solve(6, lu, piv, ainv(:, j))
    end do
  end subroutine invert6

  !> True when a symmetric n x n matrix is positive definite (Cholesky succeeds).
  pure function cholesky_is_spd(n, a) result(spd)
    integer, intent(in) :: n
    real(real64), intent(in) :: a(n, n)
    logical :: spd
    real(real64) :: l(n, n)
    call cholesky_lower(n, a, l, spd)
  end function cholesky_is_spd

  !> Lower Cholesky factor L of a symmetric positive definite matrix (A = L L^T); ok = .false. if not SPD.
  pure subroutine cholesky_lower(n, a, l, ok)
    integer, intent(in) :: n
    real(real64), intent(in) :: a(n, n)
    real(real64), intent(out) :: l(n, n)
    logical, intent(out) :: ok
    real(real64) :: s
    integer :: i, j
    l = 0.0_real64
    ok = .false.
    do j = 1, n
      s = a(j, j) - dot_product(l(j, 1:j-1), l(j, 1:j-1))
      if (.not. (s > 0.0_real64)) return
      l(j, j) = sqrt(s)
      do i = j + 1, n
        l(i, j) = (a(i, j) - dot_product(l(i, 1:j-1), l(j, 1:j-1))) / l(j, j)
      end do
    end do
    ok = .true.
  end subroutine cholesky_lower

  !> Inverse of a non-singular lower triangular matrix.
  pure function lower_inverse(n, l) result(li)
    integer, intent(in) :: n
    real(real64), intent(in) :: l(n, n)
    real(real64) :: li(n, n)
    integer :: i, j
    li = 0.0_real64
    do j = 1, n
      li(j, j) = 1 / l(j, j)
      do i = j + 1, n
        li(i, j) = -dot_product(l(i, j:i-1), li(j:i-1, j)) / l(i, i)
      end do
    end do
  end function lower_inverse

  !> Eigenvalues w and orthonormal eigenvectors (columns of q) of a symmetric matrix, by cyclic Jacobi
  !> rotations (the UMAT's routine until the closed form of ccix_pencil).
  pure subroutine jacobi_eigen(n, a, w, q)
    integer, intent(in) :: n
    real(real64), intent(in) :: a(n, n)
    real(real64), intent(out) :: w(n), q(n, n)
    real(real64) :: b(n, n), off, theta, t, c, s, bip, biq, h, scale
    integer :: sweep, p, r, i
    b = 0.5_real64 * (a + transpose(a))
    q = 0.0_real64
    do i = 1, n
      q(i, i) = 1.0_real64
    end do
    do sweep = 1, 100
      ! Off-diagonal norm relative to the largest entry (scaled: no overflow for any finite A).
      scale = maxval(abs(b))
      if (.not. (scale > 0)) exit
      off = 0.0_real64
      do p = 1, n - 1
        do r = p + 1, n
          off = off + (b(p, r) / scale)**2
        end do
      end do
      if (off <= 1.0e-34_real64) exit
      do p = 1, n - 1
        do r = p + 1, n
          if (b(p, r) == 0.0_real64) cycle
          ! t = tan of the rotation angle, the smaller root of t^2 + 2 theta t - 1 = 0 with
          ! theta = (b_rr - b_pp) / (2 b_pr). For |theta| > 1e150 (b_pr tiny against the diagonal gap)
          ! theta^2 would overflow, and the quotient itself for a subnormal b_pr: there t = 1/(2 theta)
          ! to within 1e-300 relative, computed as b_pr / (b_rr - b_pp) without forming theta.
          h = b(r, r) - b(p, p)
          if (abs(b(p, r)) < 1.0e-150_real64 * abs(h)) then
            t = b(p, r) / h
          else
            theta = h / (2 * b(p, r))
            t = sign(1.0_real64, theta) / (abs(theta) + sqrt(theta**2 + 1))
          end if
          c = 1 / sqrt(t**2 + 1)
          s = t * c
          do i = 1, n
            bip = b(i, p); biq = b(i, r)
            b(i, p) = c * bip - s * biq
            b(i, r) = s * bip + c * biq
          end do
          do i = 1, n
            bip = b(p, i); biq = b(r, i)
            b(p, i) = c * bip - s * biq
            b(r, i) = s * bip + c * biq
          end do
          do i = 1, n
            bip = q(i, p); biq = q(i, r)
            q(i, p) = c * bip - s * biq
            q(i, r) = s * bip + c * biq
          end do
        end do
      end do
    end do
    do i = 1, n
      w(i) = b(i, i)
    end do
  end subroutine jacobi_eigen

  !> Kronecker delta as a real number.
  pure real(real64) function kronecker(i, j)
    integer, intent(in) :: i, j
    kronecker = merge(1.0_real64, 0.0_real64, i == j)
  end function kronecker

  !> Mandel 6x6 stiffness for any unit bedding normal n (theory.md sec. 4.2):
  !>   C_ijkl = lam d_ij d_kl + muT (d_ik d_jl + d_il d_jk) + a (d_ij n_k n_l + n_i n_j d_kl)
  !>          + b n_i n_j n_k n_l + (muL - muT)(d_jl n_i n_k + d_ik n_j n_l + d_il n_j n_k + d_jk n_i n_l)
  !> Built in global axes from n, without rotation matrices. mu_T = mu_L, a = b = 0 is isotropic.
  pure function ti_stiffness_mandel(lam, mu_t, mu_l, a, b, n) result(c)
    real(real64), intent(in) :: lam, mu_t, mu_l, a, b, n(3)
    real(real64) :: c(6, 6)
    integer :: p, q, i, j, k, l
    real(real64) :: cijkl
    do q = 1, 6
      k = voigt_i(q); l = voigt_j(q)
      do p = q, 6
        i = voigt_i(p); j = voigt_j(p)
        cijkl = lam * kronecker(i, j) * kronecker(k, l) &
              + mu_t * (kronecker(i, k) * kronecker(j, l) + kronecker(i, l) * kronecker(j, k)) &
              + a * (kronecker(i, j) * n(k) * n(l) + n(i) * n(j) * kronecker(k, l)) &
              + b * n(i) * n(j) * n(k) * n(l) &
              + (mu_l - mu_t) * (kronecker(j, l) * n(i) * n(k) + kronecker(i, k) * n(j) * n(l) &
                                 + kronecker(i, l) * n(j) * n(k) + kronecker(j, k) * n(i) * n(l))
        c(p, q) = cijkl * mandel_w(p) * mandel_w(q)
        c(q, p) = c(p, q)
      end do
    end do
  end function ti_stiffness_mandel

  !> Symmetric Mandel 6x6 form of P. c1 = 1, c2 = c3 = 0 gives the identity (the soft frame).
  pure function projection_mandel(c1, c2, c3, n) result(p6)
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
        pijkl = 0.5_real64 * c1 * (kronecker(i, k) * kronecker(j, l) + kronecker(i, l) * kronecker(j, k)) &
              + 0.5_real64 * c2 * (m(j, l) * m(i, k) + m(i, l) * m(j, k)) &
              + 0.25_real64 * c3 * (kronecker(j, l) * m(i, k) + m(j, l) * kronecker(i, k) &
                                    + kronecker(i, l) * m(j, k) + m(i, l) * kronecker(j, k))
        p6(p, q) = pijkl * mandel_w(p) * mandel_w(q)
        p6(q, p) = p6(p, q)
      end do
    end do
  end function projection_mandel

  !> H = P:K:P with K = (2/9) 1(x)1 + (3/M^2) I_dev (theory.md sec. 1.3), by 6 x 6 products.
  pure function h_mandel(p, m_slope) result(h)
    real(real64), intent(in) :: p(6, 6), m_slope
    real(real64) :: h(6, 6), k(6, 6)
    integer :: j
    do j = 1, 6
      k(:, j) = (2.0_real64 / 9.0_real64 - 1 / m_slope**2) * one6 * one6(j)
    end do
    k = k + (3 / m_slope**2) * identity6()
    h = matmul(p, matmul(k, p))
  end function h_mandel

  !> The UMAT's derivation until the closed form: C = L L^T, L^T H L = Q Lambda Q^T (Jacobi),
  !> V = L Q, V^-1 = Q^T L^-1; lambda clipped at 0 as there.
  pure subroutine jacobi_diagonalisation(c, h, v, v_inv, lambda_h)
    real(real64), intent(in) :: c(6, 6), h(6, 6)
    real(real64), intent(out) :: v(6, 6), v_inv(6, 6), lambda_h(6)
    real(real64) :: l(6, 6), q(6, 6)
    logical :: ok
    call cholesky_lower(6, c, l, ok)
    call jacobi_eigen(6, matmul(transpose(l), matmul(h, l)), lambda_h, q)
    lambda_h = max(lambda_h, 0.0_real64)
    v = matmul(l, q)
    v_inv = matmul(transpose(q), lower_inverse(6, l))
  end subroutine jacobi_diagonalisation

end module reference_algebra
