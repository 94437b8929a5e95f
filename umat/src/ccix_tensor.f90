!> Tensor algebra in Mandel notation.
!>
!> Mandel vectors are orthonormal: sigma_hat = [s11, s22, s33, r2*s12, r2*s13, r2*s23] with r2 = sqrt(2),
!> so A:B = dot(A_hat, B_hat) and fourth-order tensors with minor symmetries are 6x6 matrices
!> (theory.md sec. 1.1). The Abaqus boundary uses Voigt order 11, 22, 33, 12, 13, 23 with engineering
!> shear strains; the conversions live here and nowhere else.
module ccix_tensor
  use, intrinsic :: iso_fortran_env, only: real64, int64
  implicit none
  private

  real(real64), parameter, public :: sqrt2 = 1.4142135623730951_real64
  !> Second-order identity as a Mandel vector.
  real(real64), parameter, public :: one6(6) = [1.0_real64, 1.0_real64, 1.0_real64, &
                                                0.0_real64, 0.0_real64, 0.0_real64]
  !> Voigt (i,j) index pairs of the six Mandel slots.
  integer, parameter, public :: voigt_i(6) = [1, 2, 3, 1, 1, 2]
  integer, parameter, public :: voigt_j(6) = [1, 2, 3, 2, 3, 3]
  !> The exponent field of an IEEE binary64 number (bits 52-62), all ones for +-Inf and NaN. The tests
  !> of finiteness below read the bits (transfer to an integer), never compare the number: an ordered
  !> comparison of a NaN (abs(x) <= huge(x), x >= 0) raises the invalid exception, which a host with
  !> floating-point traps on (gfortran -ffpe-trap=invalid) turns into SIGFPE. Not ieee_arithmetic's
  !> ieee_is_finite, quiet too: gfortran then saves and restores the floating-point state around every
  !> external procedure that uses a module using it (the UMAT: 2 calls into libgfortran per call).
  integer(int64), parameter, public :: exponent_bits = shiftl(2047_int64, 52)
  !> Mandel weight of each slot: 1 for normal components, sqrt(2) for shears.
  real(real64), parameter, public :: mandel_w(6) = [1.0_real64, 1.0_real64, 1.0_real64, &
                                                    sqrt2, sqrt2, sqrt2]

  public :: stress_to_mandel, mandel_to_stress, strain_to_mandel, mandel_to_strain, &
            tangent_to_abaqus, mandel_to_matrix33, matrix33_to_mandel, rotate_mandel, is_finite, &
            is_nan, first_not_finite

contains

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

  !> True for a finite x; never signals, whatever x (its bits, exponent_bits). Scalar and RECURSIVE, not
  !> ELEMENTAL: a function result is a local, which -fno-automatic (or ifort's -save) makes static in a
  !> non-recursive procedure, shared by the host's threads; Fortran 2008 does not allow RECURSIVE
  !> ELEMENTAL.
  pure recursive function is_finite(x) result(ok)
    real(real64), intent(in) :: x
    logical :: ok
    ok = iand(transfer(x, 0_int64), exponent_bits) /= exponent_bits
  end function is_finite

  !> True for a NaN (exponent all ones, fraction not zero: its bits without the sign above those of
  !> +Inf); never signals.
  pure recursive function is_nan(x) result(nan)
    real(real64), intent(in) :: x
    logical :: nan
    nan = iand(transfer(x, 0_int64), huge(0_int64)) > exponent_bits
  end function is_nan

  !> The index of the first of x(1:n) that is NaN or +-Inf, 0 if all are finite; never signals. Explicit
  !> shape, so that a matrix (DROT) is passed as it is stored. The usual case in one pass without
  !> branches that vectorises: the exponent field plus one, ORed over x, has its bit 11 set only if a
  !> field is all ones (2047 + 1 = 2048; no field + 1 exceeds 2048, and nothing overflows).
  pure recursive function first_not_finite(n, x) result(k)
    integer, intent(in) :: n
    real(real64), intent(in) :: x(n)
    integer :: k
    integer(int64) :: fields
    fields = 0
    do k = 1, n
      fields = ior(fields, iand(shiftr(transfer(x(k), 0_int64), 52), 2047_int64) + 1)
    end do
    if (.not. btest(fields, 11)) then
      k = 0
      return
    end if
    do k = 1, n
      if (.not. is_finite(x(k))) return
    end do
  end function first_not_finite

end module ccix_tensor
