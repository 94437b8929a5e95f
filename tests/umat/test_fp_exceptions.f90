!> No floating-point exception on the first call after new PROPS (issue 11): a host that traps
!> overflow, invalid or divide-by-zero (gfortran -ffpe-trap, feenableexcept) would die with SIGFPE.
!> The IEEE flags are cleared before each call and read after it; none may be raised.
!> 1. jacobi_eigen on matrices whose off-diagonal entries are tiny against the diagonal gap (the
!>    overflow of theta^2 found by fuzzing) and on a matrix of huge entries: no flag, and the result is
!>    an eigen-decomposition (A q_i = w_i q_i, Q^T Q = I, to round-off; an independent property).
!> 2. The UMAT's first call (new PROPS, uninitialised state) for awkward but valid PROPS: isotropic
!>    hard frames (exactly diagonal pencils), extreme modulus ratios, tiny/huge M, lambda_p, pc0, eta;
!>    no flag, finite STRESS and DDSDDE.
program test_fp_exceptions
  use, intrinsic :: iso_fortran_env, only: real64
  use, intrinsic :: ieee_exceptions, only: ieee_overflow, ieee_invalid, ieee_divide_by_zero, &
                                           ieee_set_flag, ieee_get_flag, ieee_flag_type
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use ccix_tensor, only: jacobi_eigen
  use test_support, only: props_with, call_umat, check_true, finish, nstatv_test
  implicit none
  type(ieee_flag_type), parameter :: watched(3) = [ieee_overflow, ieee_invalid, ieee_divide_by_zero]
  real(real64) :: a(3, 3), props(23)
  integer :: k

  ! 1. Jacobi: a larger off-diagonal keeps the sweep going while another is ~1e-200 (theta ~ 1e200),
  !    a subnormal one (the quotient alone overflows), and entries of 1e200 (squares overflow).
  a = reshape([1.0_real64, 1.0e-3_real64, 1.0e-200_real64, &
               1.0e-3_real64, 2.0_real64, 0.0_real64, &
               1.0e-200_real64, 0.0_real64, 3.0_real64], [3, 3])
  call check_jacobi('off-diagonal 1e-200 next to 1e-3', a)
  a(1, 3) = 1.0e-310_real64; a(3, 1) = 1.0e-310_real64
  call check_jacobi('subnormal off-diagonal', a)
  call check_jacobi('entries of 1e200', 1.0e200_real64 * a)

  ! 2. First UMAT calls with awkward PROPS (each one new, so the material is rebuilt every time).
  call first_call('Woodford', props_with(0.5_real64, [0.0_real64, 0.0_real64, 1.0_real64]))
  props = props_with(0.5_real64, [0.0_real64, 0.0_real64, 1.0_real64])
  props(2:6) = [2900.0_real64, 18000.0_real64, 18000.0_real64, 0.0_real64, 0.0_real64]
  props(9:11) = [1.0_real64, 0.0_real64, 0.0_real64]
  call first_call('isotropic hard frame, P = I', props)
  props(21:23) = [0.3_real64, 0.4_real64, 0.5_real64]
  call first_call('isotropic hard frame, oblique normal', props)
  props(9:11) = [1.0_real64, 1.0e-17_real64, -1.0e-17_real64]
  call first_call('nearly isotropic projection', props)
  do k = -8, 8, 4
    props = props_with(0.5_real64, [0.6_real64, 0.0_real64, 0.8_real64])
    props(2:6) = props(2:6) * 10.0_real64**k
    props(14:15) = props(14:15) * 10.0_real64**(-k)
    call first_call('hard moduli scaled by 10^k, soft by 10^-k', props)
    props(7) = 10.0_real64**k
    props(16) = 10.0_real64**(-k)
    call first_call('M = 10^k (hard), 10^-k (soft)', props)
    props(8) = 10.0_real64**k
    props(12) = 10.0_real64**(-k)
    props(13) = 10.0_real64**(4 * k)
    call first_call('lambda_p, pc0, eta scaled', props)
  end do
  props = 1.0e100_real64 * props_with(0.5_real64, [0.0_real64, 1.0_real64, 1.0_real64])
  props(1) = 0.5_real64
  props(7:11) = [1.46_real64, 0.00013_real64, 0.73_real64, -0.20_real64, 0.40_real64]
  props(16:17) = [1.46_real64, 0.0026_real64]
  props(20) = 0
  props(21:23) = [0.0_real64, 1.0_real64, 1.0_real64]
  call first_call('stiffness, pc0 and eta of 1e100', props)
  ! Three PROPS found by fuzzing (random valid PROPS) that raised overflow in jacobi_eigen.
  call first_call('fuzz case 1', [1.1383388249408100e-01_real64, 3.8173227214099686e-02_real64, &
    1.2692416396158089e+02_real64, 5.0102432906389618e+02_real64, 2.1792437551553643e+01_real64, &
    8.3115607795456947e+02_real64, 1.5716051648436420e+00_real64, 3.2084028900898662e-05_real64, &
    5.7281667962476757e-01_real64, -1.6070166998976143e-01_real64, -2.8753045926234522e-01_real64, &
    8.4858323397171731e-01_real64, 9.5691923916057510e+02_real64, 1.4258960267466987e+00_real64, &
    1.4884645568027625e+02_real64, 9.0208009252175110e+00_real64, 3.0738875504778506e-04_real64, &
    2.2740602717539378e+01_real64, 8.8689129222037918e+10_real64, 0.0_real64, &
    -4.6546826625649185e-01_real64, -2.9321203338093105e-01_real64, 4.3109987421096174e-02_real64])
  call first_call('fuzz case 2', [7.4066622147151806e-01_real64, 1.8404774266075609e+02_real64, &
    3.6351812566651907e+00_real64, 3.4151859968416112e+01_real64, 5.3179937074785826e+01_real64, &
    2.9084851772433008e-02_real64, 8.7130640388054044e+00_real64, 1.1713027457251417e-03_real64, &
    6.9012326712013394e-01_real64, -4.3985110156057527e-01_real64, -2.3311656861367680e-01_real64, &
    6.3591012462934179e+02_real64, 7.0882015475771652e+04_real64, 2.7925435215544482e+01_real64, &
    3.0047480016513191e+02_real64, 4.4235306805954783e-01_real64, 3.5324867852808600e-04_real64, &
    9.2652333712674526e+00_real64, 4.2489678193387708e+03_real64, 0.0_real64, &
    2.3195432131580362e-01_real64, -3.8650017394806402e-01_real64, 4.2191588307732841e-01_real64])
  call first_call('fuzz case 3 (isotropic hard stiffness)', [4.1895660029607940e-01_real64, &
    2.1815062928302677e+02_real64, 1.5230345914960493e+00_real64, 1.5230345914960493e+00_real64, &
    0.0_real64, 0.0_real64, 4.1839245839715045e-01_real64, 2.9523096761874135e-03_real64, &
    5.2419657516929163e-01_real64, -3.4584861264930311e-01_real64, 6.6120253349369462e-01_real64, &
    4.0985840592625085e+00_real64, 1.0693048860730942e+09_real64, 1.9610569344206748e+01_real64, &
    5.6610661837660846e+03_real64, 1.3748898857329175e-01_real64, 4.7511905119225234e-04_real64, &
    5.5547711847390872e+02_real64, 4.3774918357652863e+11_real64, 0.0_real64, &
    0.0_real64, 0.0_real64, 1.0_real64])
  call finish('test_fp_exceptions')

contains

  subroutine clear_flags()
    call ieee_set_flag(watched, .false.)
  end subroutine clear_flags

  !> .true. when none of overflow, invalid, divide-by-zero was raised since clear_flags.
  logical function no_flags(what)
    character(len=*), intent(in) :: what
    logical :: raised(3)
    call ieee_get_flag(watched, raised)
    no_flags = .not. any(raised)
    if (.not. no_flags) print '(a,a,3l2)', what, ': flags overflow, invalid, divide-by-zero =', raised
  end function no_flags

  subroutine check_jacobi(name, a)
    character(len=*), intent(in) :: name
    real(real64), intent(in) :: a(3, 3)
    real(real64) :: w(3), q(3, 3), res, orth
    integer :: i
    call clear_flags()
    call jacobi_eigen(3, a, w, q)
    call check_true('jacobi_eigen raises no FP flag: ' // name, no_flags(name))
    res = 0
    do i = 1, 3
      res = max(res, maxval(abs(matmul(a, q(:, i)) - w(i) * q(:, i))))
    end do
    orth = maxval(abs(matmul(transpose(q), q) - reshape([1, 0, 0, 0, 1, 0, 0, 0, 1], [3, 3])))
    call check_true('A q = w q to round-off: ' // name, res <= 1.0e-14_real64 * maxval(abs(a)))
    call check_true('Q orthonormal: ' // name, orth <= 1.0e-14_real64)
  end subroutine check_jacobi

  !> First call after new PROPS: zero state, a small compressive strain increment, dt = 1.
  subroutine first_call(name, props)
    character(len=*), intent(in) :: name
    real(real64), intent(in) :: props(23)
    real(real64) :: stress(6), statev(nstatv_test), ddsdde(6, 6), pnewdt, dstran(6)
    stress = [-1.0_real64, -1.0_real64, -3.0_real64, 0.0_real64, 0.0_real64, 0.0_real64] * props(12)
    statev = 0
    dstran = [-1.0_real64, 0.5_real64, -2.0_real64, 0.3_real64, 0.0_real64, 0.1_real64] * 1.0e-4_real64
    pnewdt = 1
    call clear_flags()
    call call_umat(props, 6, stress, statev, [0.0_real64, 0.0_real64, 0.0_real64, 0.0_real64, &
                   0.0_real64, 0.0_real64], dstran, 1.0_real64, ddsdde, pnewdt)
    call check_true('first UMAT call raises no FP flag: ' // name, no_flags(name))
    call check_true('finite STRESS and DDSDDE: ' // name, &
                    all(ieee_is_finite(stress)) .and. all(ieee_is_finite(ddsdde)))
  end subroutine first_call

end program test_fp_exceptions
