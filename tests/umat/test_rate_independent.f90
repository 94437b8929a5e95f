!> Rate-independent limit (eta = 0) against independently known states (issue #2):
!>  - isotropic compression on the normal compression line: p = pc = pc0 exp(-eps_v^vp / lambda_p),
!>    with eps_v^vp = eps_v - eps_v^e solved here as one scalar equation (theory.md §1.4);
!>  - drained triaxial compression ends where hardening stops: f = 0 and tr N = 0 (theory.md §1.3);
!>    for an isotropic surface, and for any projection with c2 + c3 = 0, that is q' = M p'.
program test_rate_independent
  use, intrinsic :: iso_fortran_env, only: real64, output_unit
  use test_support
  implicit none
  real(real64), parameter :: th = 30 * pi / 180

  call normal_compression_line()
  call drained_triaxial('soft frame (isotropic)', 0.0_real64, [0.73_real64, -0.20_real64, 0.40_real64])
  call drained_triaxial('hard frame, c2 + c3 = 0', 1.0_real64, [0.73_real64, -0.40_real64, 0.40_real64])
  call drained_triaxial('hard frame, Woodford c', 1.0_real64, [0.73_real64, -0.20_real64, 0.40_real64])
  call finish('test_rate_independent')

contains

  !> Soft frame from -35 MPa (normally consolidated, pc0 = 35) under isotropic compression.
  subroutine normal_compression_line()
    real(real64) :: props(23), stress(6), statev(nstatv_test), stran(6), dstran(6), d(6, 6), pnewdt
    real(real64) :: k_bulk, ev, p, p_exact, ev_vp
    integer :: step
    props = props_with(0.0_real64, [0.0_real64, 0.0_real64, 1.0_real64], 0.0_real64, 0.0_real64)
    k_bulk = props(14) + 2 * props(15) / 3
    stress = [-35.0_real64, -35.0_real64, -35.0_real64, 0.0_real64, 0.0_real64, 0.0_real64]
    statev = 0; stran = 0
    do step = 1, 50
      ! Uneven steps, 0.1 % to 1 % of volumetric compression each.
      dstran = -(1.0e-3_real64 + 1.8e-4_real64 * mod(step * 7, 11)) / 3 * [1, 1, 1, 0, 0, 0]
      pnewdt = 1
      call call_umat(props, 6, stress, statev, stran, dstran, 1.0_real64, d, pnewdt)
      stran = stran + dstran
      ev = sum(stran(1:3))
      p = -sum(stress(1:3)) / 3
      p_exact = ncl_pressure(ev, 35.0_real64, k_bulk, props(17))
      call check_close('NCL p', p / p_exact, 1.0_real64, 1e-10_real64)
      call check_close('NCL pc = p', statev(26) / p_exact, 1.0_real64, 1e-10_real64)
      ev_vp = sum(statev(20:22))
      call check_close('NCL pc = pc0 exp(-ev_vp/lambda_p)', statev(26) / (35 * exp(-ev_vp / props(17))), &
                       1.0_real64, 1e-10_real64)
    end do
    write (output_unit, '(a,f10.4,a,f10.4,a)') 'NCL: eps_v = ', ev, ', p = pc = ', p, ' MPa'
  end subroutine normal_compression_line

  !> p on the NCL for total volumetric strain ev: p = pc0 exp(-(ev + (p - pc0)/K)/lambda_p), bisection.
  pure real(real64) function ncl_pressure(ev, pc0, k_bulk, lambda_p) result(p)
    real(real64), intent(in) :: ev, pc0, k_bulk, lambda_p
    real(real64) :: lo, hi, g
    integer :: it
    lo = pc0; hi = pc0 * exp(-ev / lambda_p)
    do it = 1, 200
      p = 0.5_real64 * (lo + hi)
      g = p - pc0 * exp(-(ev + (p - pc0) / k_bulk) / lambda_p)
      if (g > 0) then
        hi = p
      else
        lo = p
      end if
    end do
  end function ncl_pressure

  !> Axial strain control along x3, lateral stresses held at -35 MPa and shears at 0 (mixed control).
  subroutine drained_triaxial(name, phi, c)
    character(len=*), intent(in) :: name
    real(real64), intent(in) :: phi, c(3)
    real(real64) :: props(23), stress(6), statev(nstatv_test), stran(6), dstran(6), d(6, 6), target(6)
    real(real64) :: n(3), sig(3, 3), sp(3, 3), sn(3), pp, q, s_dev(3, 3), nf(3, 3), ndir(3, 3), trn, pc, f
    real(real64) :: m_slope, lam_p
    integer :: step, i
    logical :: ok, mask(6)
    n = [sin(th), 0.0_real64, cos(th)]
    props = props_with(phi, n, 0.0_real64, 0.0_real64)
    props(9:11) = c
    stress = [-35.0_real64, -35.0_real64, -35.0_real64, 0.0_real64, 0.0_real64, 0.0_real64]
    target = stress
    mask = [.true., .true., .false., .true., .true., .true.]
    statev = 0; stran = 0
    do step = 1, 3000
      dstran = 0
      dstran(3) = -1.0e-4_real64
      call mixed_step(props, 6, stress, statev, stran, dstran, mask, target, 1.0_real64, d, ok)
      if (.not. ok) then
        call check_true('triaxial ' // name // ' step converged', .false.)
        return
      end if
      stran = stran + dstran
    end do
    ! Final state of the loaded frame, and its invariants computed here from theory.md §1.2-1.3.
    if (phi > 0) then
      sig = tensor(statev(1:6)); pc = statev(13); m_slope = props(7); lam_p = props(8)
    else
      sig = tensor(statev(14:19)); pc = statev(26); m_slope = props(16); lam_p = props(17)
      n = 0  ! P = I: c2 and c3 have no effect when the normal terms vanish
    end if
    sn = matmul(sig, n)
    if (phi > 0) then
      sp = c(1) * sig + c(2) * dot_product(n, sn) * outer(n, n) + 0.5_real64 * c(3) * (outer(n, sn) + outer(sn, n))
    else
      sp = sig
    end if
    pp = -(sp(1, 1) + sp(2, 2) + sp(3, 3)) / 3
    s_dev = sp
    do i = 1, 3
      s_dev(i, i) = s_dev(i, i) + pp
    end do
    q = sqrt(1.5_real64 * sum(s_dev**2))
    f = q**2 / m_slope**2 + pp * (pp - pc)
    nf = (3 / m_slope**2) * s_dev
    do i = 1, 3
      nf(i, i) = nf(i, i) - (2 * pp - pc) / 3
    end do
    if (phi > 0) then
      ndir = c(1) * nf + c(2) * dot_product(n, matmul(nf, n)) * outer(n, n) &
           + 0.5_real64 * c(3) * (outer(n, matmul(nf, n)) + outer(matmul(nf, n), n))
    else
      ndir = nf
    end if
    trn = ndir(1, 1) + ndir(2, 2) + ndir(3, 3)
    write (output_unit, '(a,a,a,f9.4,a,f9.4,a,f9.4,a,es9.2,a,es9.2)') 'triaxial ', name, ': p'' = ', pp, &
      ', q'' = ', q, ', q''/(M p'') = ', q / (m_slope * pp), ', f/pc^2 = ', f / pc**2, &
      ', tr N/|N| = ', trn / sqrt(sum(ndir**2))
    call check_close('triaxial ' // name // ': on the surface f = 0', f / pc**2, 0.0_real64, 1e-10_real64)
    call check_close('triaxial ' // name // ': hardening stopped, tr N = 0', trn / sqrt(sum(ndir**2)), &
                     0.0_real64, 1e-6_real64)
    if (phi == 0 .or. abs(c(2) + c(3)) < 1e-14_real64) then
      call check_close('triaxial ' // name // ': q'' = M p''', q / (m_slope * pp), 1.0_real64, 1e-6_real64)
    end if
    if (phi == 0) then
      ! Drained path from p0 = 35 MPa: q = 3 (p - p0); with q = M p, p = 3 p0 / (3 - M).
      call check_close('triaxial ' // name // ': p at critical state = 3 p0/(3 - M)', pp, &
                       3 * 35 / (3 - m_slope), 1e-6_real64 * pp)
    end if
  end subroutine drained_triaxial

  pure function tensor(v) result(a)
    real(real64), intent(in) :: v(6)
    real(real64) :: a(3, 3)
    a = reshape([v(1), v(4), v(5), v(4), v(2), v(6), v(5), v(6), v(3)], [3, 3])
  end function tensor

  pure function outer(a, b) result(ab)
    real(real64), intent(in) :: a(3), b(3)
    real(real64) :: ab(3, 3)
    integer :: i
    do i = 1, 3
      ab(:, i) = a * b(i)
    end do
  end function outer

end program test_rate_independent
