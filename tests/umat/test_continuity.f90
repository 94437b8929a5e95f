!> Continuity of the local solution across every switch of the local solve (issue 34; theory.md
!> sec. 3.4, "Steps that outrun the softening"). Seeded random states of one frame (phi = 1: the hard
!> frame, phi = 0: the soft one; the ranges of test_extremes' random calls) whose strain increment,
!> scaled by s from 0.5 to 1.5, crosses the yield surface (elastic at s = 0.5, viscoplastic at 1.5) or
!> calls the fallback solver somewhere. Along each sweep:
!> - two neighbouring accepted calls: the stress moves at most twice as far as either tangent says (a
!>   kink, at the yield surface or the pc floor, passes; a jump does not) unless a call says why: the
!>   step outruns the frame's softening (STATEV 34, bit 32 or 64), where backward Euler has no root
!>   that continues the trial;
!> - two neighbouring viscoplastic calls, one with the fallback solver and one without: the stress
!>   follows the trapezoidal rule of their tangents to 1e-3 of the move and the tangents agree to 1e-2
!>   (they are the consistent tangents of one continuous root);
!> The jumps are where backward Euler itself has none to continue (theory.md sec. 3.4): at the yield
!> surface, with dt S >= eta. Without the flag (31cac65) this test fails on the 10 jumps it finds, all
!> there and none at a switch of the solver.
program test_continuity
  use, intrinsic :: iso_fortran_env, only: real64, int64, output_unit
  use test_support
  implicit none
  integer, parameter :: n_points = 500, n_cases_wanted = 400, ntens = 6
  integer :: n_cases = 0, n_yield = 0, n_fallback = 0, jumps = 0, flagged_jumps = 0, tangent_breaks = 0
  integer :: solver_switches = 0, rejected = 0, nseed, seed(64)
  integer(int64) :: k
  real(real64) :: u(24)

  !> One case: a state, its properties and the increment swept.
  type :: case_t
    real(real64) :: props(23), stress0(6), statev0(nstatv_test), dstran(6), dtime, eta
  end type case_t

  call random_seed(size=nseed)
  seed = 20261129
  call random_seed(put=seed(1:nseed))
  do k = 1, 2000000
    call random_number(u)
    call try_case(u)
    if (n_cases >= n_cases_wanted) exit
  end do
  write (output_unit, '(7(a,i0))') 'cases ', n_cases, ' (yield crossings ', n_yield, ', fallback ', &
    n_fallback, '); unflagged jumps ', jumps, ', jumps flagged as outrunning the softening ', flagged_jumps, &
    '; solver switches ', &
    solver_switches, ', tangent breaks ', tangent_breaks
  write (output_unit, '(a,i0)') 'calls that failed (PNEWDT < 1) ', rejected
  call hold_point()
  call check_true('enough cases', n_cases >= n_cases_wanted .and. n_yield >= 20 .and. n_fallback >= 20)
  call check_true('no unexplained jump of the stress', jumps == 0)
  call check_true('tangent continuous across the solver switch', tangent_breaks == 0)
  call check_true('the jumps found (at least 5), each flagged', flagged_jumps >= 5)
  call finish('test_continuity')

contains

  !> One random state and increment; swept when it is a case.
  subroutine try_case(u)
    real(real64), intent(in) :: u(24)
    type(case_t) :: c
    real(real64) :: n(3), p, mag, s(6), v(nstatv_test), d(6, 6), pn
    integer :: which, it_lo, it_hi, fl_mid
    which = merge(1, 0, u(5) < 0.5_real64)    ! phi = 1: the hard frame alone; 0: the soft one
    n = 2 * u(2:4) - 1
    if (norm2(n) < 1e-3_real64) n = [0.0_real64, 1.0_real64, 0.0_real64]
    c%props = props_with(real(which, real64), n / norm2(n), eta_of(u(6)), eta_of(u(7)))
    c%eta = merge(c%props(13), c%props(19), which == 1)
    c%dtime = 10**(-12 + 24 * u(8))
    c%dstran = 2 * u(9:14) - 1
    mag = 10**(-8 + 7 * u(15))
    c%dstran = c%dstran / norm2(c%dstran) * mag
    p = -20 + 320 * u(16)**2
    c%stress0 = -p * [1, 1, 1, 0, 0, 0] + (abs(p) + 20) * (2 * u(17:22) - 1)
    c%statev0 = 0
    c%statev0(1:6) = c%stress0
    c%statev0(14:19) = c%stress0
    c%statev0(13) = 10**(-6 + 9 * u(24))
    c%statev0(26) = c%statev0(13)
    call one_call(c, 0.5_real64, s, v, d, pn)
    it_lo = nint(v(33))
    call one_call(c, 1.5_real64, s, v, d, pn)
    it_hi = nint(v(33))
    call one_call(c, 1.0_real64, s, v, d, pn)
    fl_mid = nint(v(34))
    if (it_lo == 0 .and. (it_hi > 0 .or. pn < 1)) then
      n_yield = n_yield + 1
    else if (pn >= 1 .and. iand(fl_mid, 16) /= 0) then
      n_fallback = n_fallback + 1
    else
      return
    end if
    n_cases = n_cases + 1
    call sweep(c)
  end subroutine try_case

  !> The call from the case's state with its increment scaled by scale.
  subroutine one_call(c, scale, s, v, d, pn)
    type(case_t), intent(in) :: c
    real(real64), intent(in) :: scale
    real(real64), intent(out) :: s(6), v(nstatv_test), d(6, 6), pn
    s = c%stress0; v = c%statev0; pn = huge(1.0_real64)   ! as Abaqus: large before each call
    call call_umat(c%props, ntens, s, v, 0 * c%dstran, scale * c%dstran, c%dtime, d, pn)
  end subroutine one_call

  !> The sweep over s, checked as the program's header says.
  subroutine sweep(c)
    type(case_t), intent(in) :: c
    real(real64) :: s(6), v(nstatv_test), d(6, 6), pn, s_prev(6), d_prev(6, 6), pred(6), sc, x
    integer :: i, fl, fl_prev, it, it_prev
    logical :: have_prev
    have_prev = .false.
    s_prev = 0; d_prev = 0; fl_prev = 0; it_prev = 0
    do i = 0, n_points
      x = 0.5_real64 + real(i, real64) / n_points
      call one_call(c, x, s, v, d, pn)
      if (pn < 1) then
        rejected = rejected + 1   ! a failed local solve (docs/umat.md): nothing to compare
        have_prev = .false.
        cycle
      end if
      fl = nint(v(34))
      it = nint(v(33))
      if (have_prev) then
        ! A jump: the stress moves more than twice as far as either tangent says (a kink, where the
        ! tangent changes at the yield surface or the pc floor, moves between the two).
        sc = max(norm2(s), norm2(s_prev), tiny(1.0_real64))
        if (norm2(s - s_prev) > 2 * max(norm2(matmul(d_prev, c%dstran)), norm2(matmul(d, c%dstran))) / n_points &
            + 1e-9_real64 * sc) then
          if (iand(ior(fl, fl_prev), 32 + 64) /= 0) then
            flagged_jumps = flagged_jumps + 1
          else
            jumps = jumps + 1
            if (jumps <= 5) write (output_unit, '(a,i0,a,f8.5,a,2i3,a,2es10.2)') 'jump: case ', n_cases, &
              ' s ', x, ' flags ', fl_prev, fl, ' eta, dt ', c%eta, c%dtime
          end if
        end if
        ! Across a switch of the solver (both calls viscoplastic, one with the fallback): smooth, the
        ! trapezoidal rule of the two tangents to 1e-3 of the move, and the tangents alike.
        if (it > 0 .and. it_prev > 0 .and. iand(ieor(fl, fl_prev), 16) /= 0) then
          solver_switches = solver_switches + 1
          pred = s_prev + 0.5_real64 * matmul(d_prev + d, c%dstran / n_points)
          if (norm2(s - pred) > 1e-3_real64 * norm2(s - s_prev) + 1e-9_real64 * sc .or. &
              norm2(d - d_prev) > 1e-2_real64 * norm2(d)) tangent_breaks = tangent_breaks + 1
        end if
      end if
      s_prev = s; d_prev = d; fl_prev = fl; it_prev = it
      have_prev = .true.
    end do
  end subroutine sweep

  !> The call of loading_rate_a1's hold where the fallback fired (test_support's hold_stress): the soft
  !> frame's step outruns its softening (flags 64 + 16), as all of the first 20 such calls of that hold
  !> did; and the flag agrees with dt S >= eta computed here from theory.md sec. 3.4 at the trial
  !> stress, on either side of it (dt S / eta = 1.025 there, 0.974 over 0.95 dt) (the soft frame is isotropic: P = I, C = lambda 1(x)1 + 2 mu I; plane strain, tensor
  !> components 11, 22, 33, 12).
  subroutine hold_point()
    real(real64) :: props(23), stress(4), statev(nstatv_test), d(4, 4), pn, sig(4), pp, s(4), nd(4), trn
    real(real64) :: ncn, soft_mod, ratio
    real(real64), parameter :: lam = 4600, mu = 3100, m_slope = 1.46_real64, lambda_p = 2.6e-3_real64, &
                               eta = 1.3e10_real64, w(4) = [1, 1, 1, 2]   ! the tensor inner product's weights
    props = props_with(0.0_real64, [0.0_real64, 1.0_real64, 0.0_real64])
    stress = hold_stress
    statev = 0
    statev(13) = 2
    statev(14:17) = hold_stress
    statev(26) = hold_pc_soft
    pn = huge(1.0_real64)
    call call_umat(props, 4, stress, statev, 0 * hold_dstran, hold_dstran, hold_dtime, d, pn)
    ! The trial stress, N = (3/M^2) s - (2p' - pc)/3 1, and S = -N:C:N + p' pc tr N / lambda_p.
    sig = hold_stress + 2 * mu * [hold_dstran(1:3), hold_dstran(4) / 2]
    sig(1:3) = sig(1:3) + lam * sum(hold_dstran(1:3))
    pp = -sum(sig(1:3)) / 3
    s = sig + pp * [1, 1, 1, 0]
    nd = (3 / m_slope**2) * s - ((2 * pp - hold_pc_soft) / 3) * [1, 1, 1, 0]
    trn = sum(nd(1:3))
    ncn = lam * trn**2 + 2 * mu * sum(w * nd**2)
    soft_mod = -ncn + pp * hold_pc_soft * trn / lambda_p
    ratio = hold_dtime * soft_mod / eta
    write (output_unit, '(a,i0,a,f7.3)') 'loading_rate_a1 hold point: flags ', nint(statev(34)), &
      ', dt S / eta at the trial ', ratio
    call check_true('loading_rate_a1 hold point: soft frame outruns its softening, fallback', &
                    nint(statev(34)) == 80 .and. pn >= 1)
    call check_true('loading_rate_a1 hold point: the flag is dt S >= eta, S by hand', ratio >= 1 .and. &
                    iand(nint(statev(34)), 64) /= 0)
    ! The same increment over 0.95 dt (the trial unchanged, dt S / eta just below 1): no flag.
    stress = hold_stress
    statev(14:17) = hold_stress
    statev(26) = hold_pc_soft
    call call_umat(props, 4, stress, statev, 0 * hold_dstran, hold_dstran, 0.95_real64 * hold_dtime, d, pn)
    call check_true('loading_rate_a1 hold point over 0.95 dt: dt S / eta below 1, not flagged', &
                    0.95_real64 * ratio < 1 .and. iand(nint(statev(34)), 64) == 0)
  end subroutine hold_point

  !> 0 in one case out of five, else 1 ... 1e30 (test_extremes).
  pure real(real64) function eta_of(v)
    real(real64), intent(in) :: v
    eta_of = merge(0.0_real64, 10**(30 * (v - 0.2_real64) / 0.8_real64), v < 0.2_real64)
  end function eta_of

end program test_continuity
