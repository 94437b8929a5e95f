!> Tensor algebra in Mandel notation and small dense linear algebra.
!>
!> Mandel vectors are orthonormal: sigma_hat = [s11, s22, s33, r2*s12, r2*s13, r2*s23] with r2 = sqrt(2),
!> so A:B = dot(A_hat, B_hat) and fourth-order tensors with minor symmetries are 6x6 matrices
!> (theory.md sec. 1.1). The Abaqus boundary uses Voigt order 11, 22, 33, 12, 13, 23 with engineering
!> shear strains; the conversions live here and nowhere else.
module ccix_tensor
  use, intrinsic :: iso_fortran_env, only: real64
  implicit none
  private

  real(real64), parameter, public :: sqrt2 = 1.4142135623730951_real64
  !> Second-order identity as a Mandel vector.
  real(real64), parameter, public :: one6(6) = [1.0_real64, 1.0_real64, 1.0_real64, &
                                                0.0_real64, 0.0_real64, 0.0_real64]
  !> Voigt (i,j) index pairs of the six Mandel slots.
  integer, parameter, public :: voigt_i(6) = [1, 2, 3, 1, 1, 2]
  integer, parameter, public :: voigt_j(6) = [1, 2, 3, 2, 3, 3]
  !> Mandel weight of each slot: 1 for normal components, sqrt(2) for shears.
  real(real64), parameter, public :: mandel_w(6) = [1.0_real64, 1.0_real64, 1.0_real64, &
                                                    sqrt2, sqrt2, sqrt2]

  public :: identity6, outer6, stress_to_mandel, mandel_to_stress, strain_to_mandel, &
            mandel_to_strain, tangent_to_abaqus, mandel_to_matrix33, matrix33_to_mandel, &
            rotate_mandel, lu_factor, lu_solve, invert6, is_finite, cholesky_is_spd, &
            cholesky_lower, lower_inverse, jacobi_eigen, kronecker

contains

  pure recursive function identity6() result(eye)
    real(real64) :: eye(6, 6)
    integer :: i
    eye = 0.0_real64
    do i = 1, 6
      eye(i, i) = 1.0_real64
    end do
  end function identity6

  pure recursive function outer6(a, b) result(ab)
    real(real64), intent(in) :: a(6), b(6)
    real(real64) :: ab(6, 6)
    integer :: j
    do j = 1, 6
      ab(:, j) = a * b(j)
    end do
  end function outer6

  !> Voigt stress (tensor shear components) -> Mandel. theory.md sec. 1.1: sigma_hat = W*STRESS.
  pure recursive function stress_to_mandel(v) result(m)
    real(real64), intent(in) :: v(6)
    real(real64) :: m(6)
    m = v * mandel_w
  end function stress_to_mandel

  pure recursive function mandel_to_stress(m) result(v)
    real(real64), intent(in) :: m(6)
    real(real64) :: v(6)
    v = m / mandel_w
  end function mandel_to_stress

  !> Engineering-shear Voigt strain -> Mandel. theory.md sec. 1.1: eps_hat = W^-1*STRAN.
  pure recursive function strain_to_mandel(v) result(m)
    real(real64), intent(in) :: v(6)
    real(real64) :: m(6)
    m = v / mandel_w
  end function strain_to_mandel

  pure recursive function mandel_to_strain(m) result(v)
    real(real64), intent(in) :: m(6)
    real(real64) :: v(6)
    v = m * mandel_w
  end function mandel_to_strain

  !> Mandel tangent -> Abaqus DDSDDE (first n slots). theory.md sec. 1.1: DDSDDE = W^-1 D_hat W^-1.
  pure recursive subroutine tangent_to_abaqus(d_hat, n, ddsdde)
    real(real64), intent(in) :: d_hat(6, 6)
    integer, intent(in) :: n
    real(real64), intent(out) :: ddsdde(n, n)
    ! 1/(w_i w_j): 1 normal-normal, 1/sqrt2 normal-shear, 1/2 shear-shear
    real(real64), parameter :: h = 0.7071067811865476_real64
    real(real64), parameter :: winv2(6, 6) = reshape([ &
      1.0_real64, 1.0_real64, 1.0_real64, h, h, h, &
      1.0_real64, 1.0_real64, 1.0_real64, h, h, h, &
      1.0_real64, 1.0_real64, 1.0_real64, h, h, h, &
      h, h, h, 0.5_real64, 0.5_real64, 0.5_real64, &
      h, h, h, 0.5_real64, 0.5_real64, 0.5_real64, &
      h, h, h, 0.5_real64, 0.5_real64, 0.5_real64], [6, 6])
    ddsdde = d_hat(1:n, 1:n) * winv2(1:n, 1:n)
  end subroutine tangent_to_abaqus

  pure recursive function mandel_to_matrix33(m) result(a)
    real(real64), intent(in) :: m(6)
    real(real64) :: a(3, 3)
    integer :: k
    do k = 1, 6
      a(voigt_i(k), voigt_j(k)) = m(k) / mandel_w(k)
      a(voigt_j(k), voigt_i(k)) = m(k) / mandel_w(k)
    end do
  end function mandel_to_matrix33

  pure recursive function matrix33_to_mandel(a) result(m)
    real(real64), intent(in) :: a(3, 3)
    real(real64) :: m(6)
    integer :: k
    do k = 1, 6
      m(k) = 0.5_real64 * (a(voigt_i(k), voigt_j(k)) + a(voigt_j(k), voigt_i(k))) * mandel_w(k)
    end do
  end function matrix33_to_mandel

  !> R . A . R^T for a symmetric tensor A given in Mandel form.
  pure recursive function rotate_mandel(r, m) result(mr)
    real(real64), intent(in) :: r(3, 3), m(6)
    real(real64) :: mr(6), a(3, 3), art(3, 3)
    ! R (A R^T), each product of named arrays: matmul of a function result, inlined by gfortran, drew
    ! five false "used uninitialized" warnings (-Wall, and -O3 without it) from the single file.
    a = mandel_to_matrix33(m)
    art = matmul(a, transpose(r))
    mr = matrix33_to_mandel(matmul(r, art))
  end function rotate_mandel

  !> LU factorisation with partial pivoting, in place. ok = .false. on an exactly singular pivot.
  !> Written with scalar loops (no array temporaries): it runs in the innermost loop of the UMAT.
  pure recursive subroutine lu_factor(n, a, piv, ok)
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
  pure recursive subroutine lu_solve(n, lu, piv, b)
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
  pure recursive subroutine invert6(a, ainv, ok)
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
  pure recursive function cholesky_is_spd(n, a) result(spd)
    integer, intent(in) :: n
    real(real64), intent(in) :: a(n, n)
    logical :: spd
    real(real64) :: l(n, n)
    call cholesky_lower(n, a, l, spd)
  end function cholesky_is_spd

  !> Lower Cholesky factor L of a symmetric positive definite matrix (A = L L^T); ok = .false. if not SPD.
  pure recursive subroutine cholesky_lower(n, a, l, ok)
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
  pure recursive function lower_inverse(n, l) result(li)
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
  !> rotations. Used once per material, never per call.
  pure recursive subroutine jacobi_eigen(n, a, w, q)
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
  pure recursive real(real64) function kronecker(i, j)
    integer, intent(in) :: i, j
    kronecker = merge(1.0_real64, 0.0_real64, i == j)
  end function kronecker

  !> True for a finite x (NaN compares false). Scalar and RECURSIVE, not ELEMENTAL: a function result
  !> is a local, which -fno-automatic (or ifort's -save) makes static in a non-recursive procedure,
  !> shared by the host's threads; Fortran 2008 does not allow RECURSIVE ELEMENTAL.
  pure recursive function is_finite(x) result(ok)
    real(real64), intent(in) :: x
    logical :: ok
    ok = (x == x) .and. abs(x) <= huge(x)
  end function is_finite

end module ccix_tensor
