!> The closed-form material (Walpole's basis, ccix_walpole; the pencil, ccix_pencil) against
!> references computed independently (tests/umat/reference_algebra.f90): the index forms of C and P
!> (theory.md sec. 4.2, 1.2), H = P:K:P by 6 x 6 products (sec. 1.3), and the simultaneous
!> diagonalisation by Cholesky and 6 x 6 Jacobi that the UMAT used before. For 9 normals (the axes,
!> inclined ones in a coordinate plane, oblique and nearly axial ones) and 6 materials (Woodford's hard
!> and soft frames, an isotropic hard frame with P = I and with P /= I, and two extreme ones found by
!> fuzzing):
!> - Q is orthogonal; Q diag(A) Q^T (ti_mandel), A:x (ti_apply) and the Abaqus form (ti_abaqus) equal
!>   the index forms of C and P; ti_inverse is the inverse; H's coefficients give P:K:P;
!> - V = Q B and V^-1 = B^-1 Q^T of pencil_diagonalise: V V^T = C (i.e. V^T C^-1 V = I),
!>   V^T H V = diag(lambda_h), V^-1 V = I, b = V^T P:1, h1 = V^T H:1, and the eigenvalues and the
!>   operator (C^-1 + g H)^-1 = V diag(1/(1 + g lambda)) V^T of the return map (ccix_frame) equal those
!>   of the Jacobi derivation; all to 1e-12 relative (measured: printed);
!> - with the normal in the 1-2 plane (plane strain) every basis vector and V column is exactly in-plane
!>   or exactly out-of-plane (theory.md sec. 4.1: the blocks decouple exactly).
program test_walpole
  use, intrinsic :: iso_fortran_env, only: real64, output_unit
  use ccix_tensor, only: one6, tangent_to_abaqus
  use ccix_walpole, only: ti_t, walpole_basis, ti_mandel, ti_apply, ti_abaqus, ti_inverse, ti_sandwich
  use ccix_elasticity, only: ti_stiffness
  use ccix_projection, only: ti_projection
  use ccix_frame, only: frame_t, frame_new
  use ccix_pencil, only: pencil_t, pencil_diagonalise
  use reference_algebra, only: ti_stiffness_mandel, projection_mandel, h_mandel, invert6, identity6, &
                               jacobi_diagonalisation
  use test_support, only: check_true, finish
  implicit none
  real(real64), parameter :: tol = 1.0e-12_real64, pi = 3.141592653589793_real64
  integer, parameter :: nnormal = 9, nmat = 6
  real(real64) :: normals(3, nnormal), mats(12, nmat), worst(10), th
  character(len=40), parameter :: names(10) = [character(len=40) :: 'Q^T Q = I', &
    'ti_mandel vs index forms (C, P)', 'ti_apply vs index forms', 'ti_abaqus vs index form', &
    'ti_inverse', 'H = P:K:P', 'V V^T = C, V^-1 V = I', 'V^T H V = diag(lambda_h), b, h1', &
    'lambda_h vs Jacobi', '(C^-1 + g H)^-1 vs Jacobi']
  integer :: i, j

  th = 30 * pi / 180
  normals(:, 1) = [0.0_real64, 0.0_real64, 1.0_real64]
  normals(:, 2) = [1.0_real64, 0.0_real64, 0.0_real64]
  normals(:, 3) = [0.0_real64, 1.0_real64, 0.0_real64]
  normals(:, 4) = [sin(th), 0.0_real64, cos(th)]
  normals(:, 5) = [sin(th), cos(th), 0.0_real64]
  normals(:, 6) = [0.3_real64, -0.4_real64, 0.5_real64]
  normals(:, 7) = [1.0e-9_real64, 0.0_real64, 1.0_real64]
  normals(:, 8) = [-0.6_real64, 0.0_real64, -0.8_real64]
  normals(:, 9) = [1.0_real64, 1.0_real64, 1.0_real64]
  do j = 1, nnormal
    normals(:, j) = normals(:, j) / norm2(normals(:, j))
  end do
  !            lambda  mu_T     mu_L     a       b       M     c1    c2     c3     (lambda_p, pc0, eta unused)
  mats(:, 1) = [2900.0_real64, 18000.0_real64, 13000.0_real64, 4100.0_real64, 6900.0_real64, 1.46_real64, &
                0.73_real64, -0.20_real64, 0.40_real64, 1.3e-4_real64, 2.0_real64, 1.3e13_real64]
  mats(:, 2) = [4600.0_real64, 3100.0_real64, 3100.0_real64, 0.0_real64, 0.0_real64, 1.46_real64, &
                1.0_real64, 0.0_real64, 0.0_real64, 2.6e-3_real64, 35.0_real64, 1.3e10_real64]
  mats(:, 3) = [2900.0_real64, 18000.0_real64, 18000.0_real64, 0.0_real64, 0.0_real64, 1.46_real64, &
                1.0_real64, 0.0_real64, 0.0_real64, 1.3e-4_real64, 2.0_real64, 1.3e13_real64]
  mats(:, 4) = [2900.0_real64, 18000.0_real64, 18000.0_real64, 0.0_real64, 0.0_real64, 1.46_real64, &
                0.73_real64, -0.20_real64, 0.40_real64, 1.3e-4_real64, 2.0_real64, 1.3e13_real64]
  ! Two of the fuzzing cases of test_fp_exceptions (hard frames).
  mats(:, 5) = [3.8173227214099686e-02_real64, 1.2692416396158089e+02_real64, 5.0102432906389618e+02_real64, &
                2.1792437551553643e+01_real64, 8.3115607795456947e+02_real64, 1.5716051648436420e+00_real64, &
                5.7281667962476757e-01_real64, -1.6070166998976143e-01_real64, -2.8753045926234522e-01_real64, &
                3.2084028900898662e-05_real64, 8.4858323397171731e-01_real64, 9.5691923916057510e+02_real64]
  mats(:, 6) = [1.8404774266075609e+02_real64, 3.6351812566651907e+00_real64, 3.4151859968416112e+01_real64, &
                5.3179937074785826e+01_real64, 2.9084851772433008e-02_real64, 8.7130640388054044e+00_real64, &
                6.9012326712013394e-01_real64, -4.3985110156057527e-01_real64, -2.3311656861367680e-01_real64, &
                1.1713027457251417e-03_real64, 6.3591012462934179e+02_real64, 7.0882015475771652e+04_real64]
  worst = 0
  do j = 1, nnormal
    do i = 1, nmat
      call check_material(mats(:, i), normals(:, j))
    end do
  end do
  call check_plane_strain()
  write (output_unit, '(a)') 'largest relative differences:'
  do i = 1, size(names)
    write (output_unit, '(2x,a40,es10.2)') names(i), worst(i)
    call check_true(trim(names(i)) // ' within 1e-12', worst(i) <= tol)
  end do
  call finish('test_walpole')

contains

  subroutine check_material(m, n)
    real(real64), intent(in) :: m(12), n(3)
    real(real64) :: q(6, 6), c(6, 6), p(6, 6), h(6, 6), c_inv(6, 6), mh(6), x(6), y(6), dd(6, 6), vj(6, 6), &
                    vij(6, 6), lj(6), v(6, 6), v_inv(6, 6), b(6, 6), b_inv(6, 6), g, a1(6, 6), a2(6, 6), &
                    vhv(6, 6)
    type(ti_t) :: cw, pw, kw, hw
    type(frame_t) :: fr
    type(pencil_t) :: pe
    logical :: ok
    integer :: k, seed(8), nseed
    call walpole_basis(n, q)
    c = ti_stiffness_mandel(m(1), m(2), m(3), m(4), m(5), n)
    p = projection_mandel(m(7), m(8), m(9), n)
    h = h_mandel(p, m(6))
    call invert6(c, c_inv, ok)
    cw = ti_stiffness(m(1), m(2), m(3), m(4), m(5))
    pw = ti_projection(m(7), m(8), m(9))
    call note(1, maxval(abs(matmul(transpose(q), q) - identity6())))
    call note(2, maxval(abs(ti_mandel(cw, q) - c)) / maxval(abs(c)))
    call note(2, maxval(abs(ti_mandel(pw, q) - p)) / maxval(abs(p)))
    mh = q(:, 2)
    call random_seed(size=nseed)
    seed = 4321
    call random_seed(put=seed(1:min(nseed, 8)))
    do k = 1, 3
      call random_number(x)
      x = x - 0.5_real64
      call ti_apply(cw, n, mh, x, y)
      call note(3, maxval(abs(y - matmul(c, x))) / (maxval(abs(c)) * maxval(abs(x))))
      call ti_apply(pw, n, mh, x, y)
      call note(3, maxval(abs(y - matmul(p, x))) / (maxval(abs(p)) * maxval(abs(x))))
    end do
    call ti_abaqus(cw, q, 6, dd)
    call tangent_to_abaqus(c, 6, a1)
    call note(4, maxval(abs(dd - a1)) / maxval(abs(a1)))
    call note(5, maxval(abs(matmul(ti_mandel(ti_inverse(cw), q), c) - identity6())))
    ! H = P:K:P from the coefficients (K as in ccix_pencil: (3/M^2) I + (2/9 - 1/M^2) 1(x)1).
    kw%a11 = 3 / m(6)**2 + 2 * (2.0_real64 / 9 - 1 / m(6)**2)
    kw%a12 = sqrt(2.0_real64) * (2.0_real64 / 9 - 1 / m(6)**2)
    kw%a22 = 3 / m(6)**2 + (2.0_real64 / 9 - 1 / m(6)**2)
    kw%a5 = 3 / m(6)**2
    kw%a6 = kw%a5
    hw = ti_sandwich(pw, kw)
    call note(6, maxval(abs(ti_mandel(hw, q) - h)) / maxval(abs(h)))

    ! The pencil, as the UMAT derives it for this frame.
    call frame_new(fr, m(1), m(2), m(3), m(4), m(5), m(6), m(10), m(7), m(8), m(9), m(11), m(12), n)
    call pencil_diagonalise(fr%cw, fr%pw, fr%m_slope, fr%isotropic_pencil, pe)
    b = 0
    b_inv = 0
    b(1:2, 1:2) = pe%w
    b_inv(1:2, 1:2) = pe%w_inv
    do k = 3, 6
      b(k, k) = pe%r(k)
      b_inv(k, k) = pe%r_inv(k)
    end do
    v = matmul(q, b)
    v_inv = matmul(b_inv, transpose(q))
    call note(7, maxval(abs(matmul(v, transpose(v)) - c)) / maxval(abs(c)))
    call note(7, maxval(abs(matmul(v_inv, v) - identity6())))
    vhv = matmul(transpose(v), matmul(h, v))
    do k = 1, 6
      vhv(k, k) = vhv(k, k) - pe%lambda_h(k)
    end do
    call note(8, maxval(abs(vhv)) / maxval(pe%lambda_h))
    x = matmul(transpose(v), matmul(p, one6))
    call note(8, maxval(abs(pe%b - x)) / maxval(abs(x)))
    x = matmul(transpose(v), matmul(h, one6))
    call note(8, maxval(abs(pe%h1 - x)) / maxval(abs(x)))

    ! The Jacobi derivation: the same eigenvalues and the same operators of the return map.
    call jacobi_diagonalisation(c, h, vj, vij, lj)
    ! The same eigenvalues: each of either set next to one of the other (Hausdorff distance).
    do k = 1, 6
      call note(9, minval(abs(lj - pe%lambda_h(k))) / maxval(lj))
      call note(9, minval(abs(pe%lambda_h - lj(k))) / maxval(lj))
    end do
    do k = -2, 2
      g = 10.0_real64**(2 * k) / maxval(lj)
      a1 = matmul(v, diag(1 / (1 + g * pe%lambda_h), transpose(v)))
      a2 = matmul(vj, diag(1 / (1 + g * lj), transpose(vj)))
      call note(10, maxval(abs(a1 - a2)) / maxval(abs(a2)))
    end do
  end subroutine check_material

  !> n = (sin 30, cos 30, 0): Q and V of Woodford's hard frame have no entry coupling the in-plane
  !> slots (1-4) with the out-of-plane ones (5-6).
  subroutine check_plane_strain()
    real(real64) :: q(6, 6), n(3), v(6, 6), b(6, 6), m(12)
    type(frame_t) :: fr
    type(pencil_t) :: pe
    logical :: split_q, split_v
    integer :: k
    n = [sin(th), cos(th), 0.0_real64]
    m = mats(:, 1)
    call walpole_basis(n, q)
    call frame_new(fr, m(1), m(2), m(3), m(4), m(5), m(6), m(10), m(7), m(8), m(9), m(11), m(12), n)
    call pencil_diagonalise(fr%cw, fr%pw, fr%m_slope, fr%isotropic_pencil, pe)
    b = 0
    b(1:2, 1:2) = pe%w
    do k = 3, 6
      b(k, k) = pe%r(k)
    end do
    v = matmul(q, b)
    split_q = .true.
    split_v = .true.
    do k = 1, 6
      split_q = split_q .and. (all(q(1:4, k) == 0) .or. all(q(5:6, k) == 0))
      split_v = split_v .and. (all(v(1:4, k) == 0) .or. all(v(5:6, k) == 0))
    end do
    call check_true('plane strain: each basis vector exactly in-plane or out-of-plane', split_q)
    call check_true('plane strain: each column of V exactly in-plane or out-of-plane', split_v)
  end subroutine check_plane_strain

  subroutine note(k, e)
    integer, intent(in) :: k
    real(real64), intent(in) :: e
    if (worst(k) /= worst(k)) return            ! a NaN stays
    if (.not. (e <= worst(k))) worst(k) = e     ! NaN included
  end subroutine note

  !> diag(d) a
  pure function diag(d, a) result(da)
    real(real64), intent(in) :: d(6), a(6, 6)
    real(real64) :: da(6, 6)
    integer :: k
    do k = 1, 6
      da(k, :) = d(k) * a(k, :)
    end do
  end function diag

end program test_walpole
