!> Elasticity, projection tensor (the UMAT's, in Walpole's basis of n) and yield function of one frame
!> against theory.md §4-5 and Yin et al. 2021 Table 1.
program test_elasticity
  use, intrinsic :: iso_fortran_env, only: real64
  use ccix_tensor, only: tangent_to_abaqus, sqrt2, one6
  use ccix_walpole, only: walpole_basis, ti_mandel
  use ccix_elasticity, only: ti_stiffness
  use ccix_projection, only: ti_projection
  use ccix_frame, only: frame_t, frame_new, flow_direction
  use reference_algebra, only: invert6, cholesky_is_spd
  use test_support
  implicit none
  real(real64) :: c(6, 6), v(6, 6), s(6, 6), expect(6, 6), p(6, 6), n(3), tr0, tr20, sig(6)
  real(real64) :: f, pp, q2, n_dir(6), u(3), ep, en
  type(frame_t) :: fr
  logical :: ok, all_spd
  integer :: k
  real(real64), parameter :: tol = 1e-10_real64

  ! theory.md §5.1, theta = 0 (n = e3): DDSDDE of the hard frame, Table 1 converted values.
  expect = reshape([38900, 2900, 7000, 0, 0, 0, &
                    2900, 38900, 7000, 0, 0, 0, &
                    7000, 7000, 34000, 0, 0, 0, &
                    0, 0, 0, 18000, 0, 0, &
                    0, 0, 0, 0, 13000, 0, &
                    0, 0, 0, 0, 0, 13000], [6, 6]) * 1.0_real64
  v = hard_voigt([0.0_real64, 0.0_real64, 1.0_real64])
  call check_close('theta=0 matrix', maxval(abs(v - expect)), 0.0_real64, tol * 38900)

  ! theta = 90 (n = e1): rows and columns permuted.
  expect = 0
  expect(1, :) = [34000, 7000, 7000, 0, 0, 0]
  expect(2, :) = [7000, 38900, 2900, 0, 0, 0]
  expect(3, :) = [7000, 2900, 38900, 0, 0, 0]
  expect(4, 4) = 13000; expect(5, 5) = 13000; expect(6, 6) = 18000
  v = hard_voigt([1.0_real64, 0.0_real64, 0.0_real64])
  call check_close('theta=90 matrix', maxval(abs(v - expect)), 0.0_real64, tol * 38900)

  ! theta = 45 (n = (1, 0, 1)/sqrt2), the listed entries of §5.1; the rest vanish.
  expect = 0
  expect(1, 1) = 34725; expect(3, 3) = 34725; expect(2, 2) = 38900
  expect(1, 2) = 4950; expect(2, 3) = 4950; expect(1, 3) = 8725
  expect(1, 5) = -1225; expect(3, 5) = -1225; expect(2, 5) = 2050
  expect(4, 4) = 15500; expect(6, 6) = 15500; expect(4, 6) = -2500; expect(5, 5) = 14725
  expect = max(expect, transpose(expect)) + min(expect, transpose(expect)) - merge(expect, 0.0_real64, &
           reshape([(k == 1 .or. k == 8 .or. k == 15 .or. k == 22 .or. k == 29 .or. k == 36, k = 1, 36)], [6, 6]))
  v = hard_voigt([1.0_real64, 0.0_real64, 1.0_real64] / sqrt2)
  call check_close('theta=45 matrix', maxval(abs(v - expect)), 0.0_real64, tol * 38900)

  ! Compliance of the theta = 0 stiffness -> engineering constants (S13 = -nu/Ep reading, §4.3):
  ! the [VER] values of theory.md and, within 5 %, Table 1's original column.
  call invert6(hard_voigt([0.0_real64, 0.0_real64, 1.0_real64]), s, ok)
  ep = 1 / s(1, 1); en = 1 / s(3, 3)
  call check_close('Ep vs theory.md 37402', ep, 37402.0_real64, 1.0_real64)
  call check_close('En vs theory.md 31655', en, 31655.0_real64, 1.0_real64)
  call check_close('S13 vs theory.md -5.290e-6', s(1, 3), -5.290e-6_real64, 0.0005e-6_real64)
  call check_close('Ep vs Table 1 (5%)', ep / 38000, 1.0_real64, 0.05_real64)
  call check_close('En vs Table 1 (5%)', en / 33000, 1.0_real64, 0.05_real64)
  call check_close('nu_pp vs Table 1 (5%)', -s(1, 2) * ep / 0.038_real64, 1.0_real64, 0.05_real64)
  call check_close('nu vs Table 1 (5%)', -s(1, 3) * ep / 0.19_real64, 1.0_real64, 0.05_real64)
  call check_close('G_np vs Table 1', 1 / s(5, 5), 13000.0_real64, 13000 * tol)

  ! Isotropic case: mu_T = mu_L, a = b = 0 is lambda 1(x)1 + 2 mu I for any normal.
  expect = 0
  expect(1:3, 1:3) = 4600
  do k = 1, 3
    expect(k, k) = 4600 + 2 * 3100
    expect(k + 3, k + 3) = 3100
  end do
  all_spd = .true.
  tr0 = trace(ti_stiffness_mandel(2900.0_real64, 18000.0_real64, 13000.0_real64, 4100.0_real64, &
                                  6900.0_real64, [0.0_real64, 0.0_real64, 1.0_real64]))
  c = ti_stiffness_mandel(2900.0_real64, 18000.0_real64, 13000.0_real64, 4100.0_real64, &
                          6900.0_real64, [0.0_real64, 0.0_real64, 1.0_real64])
  tr20 = trace(matmul(c, c))
  do k = 1, 1000
    n = random_unit(k)
    call tangent_to_abaqus(ti_stiffness_mandel(4600.0_real64, 3100.0_real64, 3100.0_real64, &
                           0.0_real64, 0.0_real64, n), 6, v)
    call check_close('isotropic case', maxval(abs(v - expect)), 0.0_real64, tol * 10800)
    ! Paper's values: positive definite for any normal, and the invariants do not depend on it.
    c = ti_stiffness_mandel(2900.0_real64, 18000.0_real64, 13000.0_real64, 4100.0_real64, &
                            6900.0_real64, n)
    all_spd = all_spd .and. cholesky_is_spd(6, c)
    call check_close('tr C invariant', trace(c), tr0, tol * tr0)
    call check_close('tr C^2 invariant', trace(matmul(c, c)), tr20, tol * tr20)
  end do
  call check_true('positive definite for 1000 random normals', all_spd)
  ! Mandel eigenvalues 26000 (x2), 27260, 36000 (x2), 48540 (theory.md §4.3): trace 199800.
  call check_close('tr C = sum of eigenvalues', tr0, 199800.0_real64, 1.0_real64)

  ! Projection tensor, theory.md §5.2.
  p = projection_mandel(0.73_real64, -0.20_real64, 0.40_real64, [0.0_real64, 0.0_real64, 1.0_real64])
  call check_close('P theta=0', maxval(abs(p - diag([0.73d0, 0.73d0, 0.93d0, 0.73d0, 0.93d0, 0.93d0]))), &
                   0.0_real64, tol)
  p = projection_mandel(0.73_real64, -0.20_real64, 0.40_real64, [1.0_real64, 0.0_real64, 0.0_real64])
  call check_close('P theta=90', maxval(abs(p - diag([0.93d0, 0.73d0, 0.73d0, 0.93d0, 0.93d0, 0.73d0]))), &
                   0.0_real64, tol)
  p = projection_mandel(0.73_real64, -0.20_real64, 0.40_real64, [1.0_real64, 0.0_real64, 1.0_real64] / sqrt2)
  expect = 0
  expect(1, 1) = 0.88_real64; expect(3, 3) = 0.88_real64; expect(1, 3) = -0.05_real64
  expect(3, 1) = -0.05_real64; expect(2, 2) = 0.73_real64
  expect(4, 4) = 0.83_real64; expect(5, 5) = 0.83_real64; expect(6, 6) = 0.83_real64
  expect(4, 6) = 0.10_real64; expect(6, 4) = 0.10_real64
  expect(1, 5) = 0.1_real64 / sqrt2; expect(5, 1) = expect(1, 5)
  expect(3, 5) = expect(1, 5); expect(5, 3) = expect(1, 5)
  call check_close('P theta=45 (Mandel)', maxval(abs(p - expect)), 0.0_real64, tol)
  call check_close('P = I for the soft frame', maxval(abs(projection_mandel(1.0_real64, 0.0_real64, &
                   0.0_real64, random_unit(7)) - diag([1d0, 1d0, 1d0, 1d0, 1d0, 1d0]))), 0.0_real64, tol)

  ! Yield function at sigma = -35 MPa 1, theory.md §5.3 (hard frame, theta = 0; printed to 5 digits).
  fr = woodford_hard([0.0_real64, 0.0_real64, 1.0_real64])
  sig = -35 * one6
  call flow_direction(fr, sig, 2.0_real64, f, pp, q2, n_dir)
  call check_close('f hard at -35 MPa', f, 744.70_real64, 0.005_real64)
  call check_close('p'' hard at -35 MPa', pp, 27.883_real64, 0.0005_real64)
  call check_close('q'' hard at -35 MPa', sqrt(q2), 7.000_real64, 0.0005_real64)
  call check_close('tr N hard', sum(n_dir(1:3)), -44.15_real64, 0.005_real64)
  call check_close('N11 hard', n_dir(1), -10.686_real64, 0.0005_real64)
  call check_close('N33 hard', n_dir(3), -22.776_real64, 0.0005_real64)
  call check_close('rate f/eta', f / 1.3e13_real64, 5.73e-11_real64, 0.005e-11_real64)
  ! The same state seen with theta = 90: f is invariant (§5.3).
  fr = woodford_hard([1.0_real64, 0.0_real64, 0.0_real64])
  call flow_direction(fr, sig, 2.0_real64, f, pp, q2, n_dir)
  call check_close('f hard theta=90', f, 744.70_real64, 0.005_real64)
  ! Finite-difference check of N = df/dsigma at a random state and normal.
  call check_gradient()

  call finish('test_elasticity')

contains

  !> The hard frame of Woodford shale (Table 1) for the unit normal n.
  function woodford_hard(normal) result(frh)
    real(real64), intent(in) :: normal(3)
    type(frame_t) :: frh
    call frame_new(frh, 2900.0_real64, 18000.0_real64, 13000.0_real64, 4100.0_real64, 6900.0_real64, &
                   1.46_real64, 0.00013_real64, 0.73_real64, -0.20_real64, 0.40_real64, 2.0_real64, &
                   1.3e13_real64, normal)
  end function woodford_hard

  !> The UMAT's stiffness and projection for the normal n, as Mandel matrices.
  pure function ti_stiffness_mandel(lam, mu_t, mu_l, a, b, normal) result(cm)
    real(real64), intent(in) :: lam, mu_t, mu_l, a, b, normal(3)
    real(real64) :: cm(6, 6), q(6, 6)
    call walpole_basis(normal, q)
    cm = ti_mandel(ti_stiffness(lam, mu_t, mu_l, a, b), q)
  end function ti_stiffness_mandel

  pure function projection_mandel(c1, c2, c3, normal) result(pm)
    real(real64), intent(in) :: c1, c2, c3, normal(3)
    real(real64) :: pm(6, 6), q(6, 6)
    call walpole_basis(normal, q)
    pm = ti_mandel(ti_projection(c1, c2, c3), q)
  end function projection_mandel

  function hard_voigt(normal) result(vv)
    real(real64), intent(in) :: normal(3)
    real(real64) :: vv(6, 6)
    call tangent_to_abaqus(ti_stiffness_mandel(2900.0_real64, 18000.0_real64, 13000.0_real64, &
                           4100.0_real64, 6900.0_real64, normal), 6, vv)
  end function hard_voigt

  pure function diag(d) result(a)
    real(real64), intent(in) :: d(6)
    real(real64) :: a(6, 6)
    integer :: i
    a = 0
    do i = 1, 6
      a(i, i) = d(i)
    end do
  end function diag

  pure real(real64) function trace(a)
    real(real64), intent(in) :: a(6, 6)
    integer :: i
    trace = 0
    do i = 1, 6
      trace = trace + a(i, i)
    end do
  end function trace

  !> A deterministic pseudo-random unit vector (seeded by k).
  function random_unit(k) result(un)
    integer, intent(in) :: k
    real(real64) :: un(3)
    integer :: seed(8)
    integer :: nseed
    call random_seed(size=nseed)
    seed = 12345 + k
    call random_seed(put=seed(1:min(nseed, 8)))
    call random_number(u)
    un = 2 * u - 1
    un = un / norm2(un)
  end function random_unit

  subroutine check_gradient()
    real(real64) :: s0(6), ds(6), fp, fm, h, nd(6), g
    integer :: i
    fr = woodford_hard(random_unit(3))
    s0 = [-30.0_real64, -12.0_real64, -41.0_real64, 5.0_real64, -3.0_real64, 7.0_real64]
    call flow_direction(fr, s0, 20.0_real64, f, pp, q2, nd)
    h = 1e-4_real64
    do i = 1, 6
      ds = 0; ds(i) = h
      call flow_direction(fr, s0 + ds, 20.0_real64, fp, pp, q2, n_dir)
      call flow_direction(fr, s0 - ds, 20.0_real64, fm, pp, q2, n_dir)
      g = (fp - fm) / (2 * h)
      call check_close('N = df/dsigma (central FD)', nd(i), g, 1e-7_real64 * maxval(abs(nd)))
    end do
  end subroutine check_gradient

end program test_elasticity
