!> One elasto-viscoplastic solid frame of Cam-Clay IX: transversely isotropic elasticity, the modified
!> Cam-Clay surface in the fictitious stress sigma' = P:sigma, exponential hardening of pc, and Perzyna
!> overstress flow, integrated by backward Euler (theory.md §1.3, §1.4, §3).
!>
!> Everything here is pure: one call integrates one frame over one step, from its converged state at
!> the start of the step, and returns the new state and the algorithmic tangent. The soft frame is the
!> isotropic special case (P = I) of the same frame.
module ccix_frame
  use, intrinsic :: iso_fortran_env, only: real64
  use ccix_tensor, only: one6, identity6, outer6, lu_factor, lu_solve, invert6, is_finite
  use ccix_elasticity, only: ti_stiffness_mandel
  use ccix_projection, only: projection_mandel
  implicit none
  private

  !> Material constants of one frame, with everything derived from them that the return map needs.
  type, public :: frame_t
    real(real64) :: c(6, 6) = 0       !< elastic stiffness (Mandel)
    real(real64) :: cinv(6, 6) = 0    !< its inverse
    real(real64) :: p(6, 6) = 0       !< projection tensor P (Mandel), theory.md §1.2
    real(real64) :: h(6, 6) = 0       !< H = dN/dsigma = P:[(2/9) 1(x)1 + (3/M^2) I_dev]:P, §1.3
    real(real64) :: p1(6) = 0         !< P:1
    real(real64) :: h1(6) = 0         !< H:1
    real(real64) :: tr_p1 = 0         !< tr(P:1) = 3 c1 + c2 + c3
    real(real64) :: m_slope = 1       !< M, slope of the critical state line
    real(real64) :: lambda_p = 1      !< plastic compressibility
    real(real64) :: pc0 = 1           !< initial preconsolidation pressure
    real(real64) :: eta = 0           !< Perzyna viscosity [stress^3 * time]
    real(real64) :: e_ref = 1         !< stiffness scale E_r = tr(C)/6, §3.3
    real(real64) :: p_floor = 0       !< lower bound of pc, §3.6
    logical :: isotropic = .true.     !< P = I: skip the projection products
  end type frame_t

  !> Outcome of one frame integration.
  integer, parameter, public :: frame_elastic = 0, frame_newton = 1, frame_fallback = 2, &
                                frame_failed = -1
  !> Bits of the flags word.
  integer, parameter, public :: flag_floor = 1, flag_tension = 2, flag_fallback = 4

  integer, parameter :: nx = 8              ! local unknowns: sigma(6), dgamma, y = ln(pc/pc_n)
  integer, parameter :: max_newton = 30
  real(real64), parameter :: newton_tol = 1.0e-11_real64
  real(real64), parameter :: y_max = 50.0_real64, dy_max = 2.0_real64

  public :: frame_new, yield_function, flow_direction, frame_integrate

contains

  !> Build a frame from its constants and the unit bedding normal n.
  pure function frame_new(lam, mu_t, mu_l, a, b, m_slope, lambda_p, c1, c2, c3, pc0, eta, n) &
      result(fr)
    real(real64), intent(in) :: lam, mu_t, mu_l, a, b, m_slope, lambda_p, c1, c2, c3, pc0, eta, n(3)
    type(frame_t) :: fr
    real(real64) :: k(6, 6)
    logical :: ok
    fr%c = ti_stiffness_mandel(lam, mu_t, mu_l, a, b, n)
    call invert6(fr%c, fr%cinv, ok)
    fr%p = projection_mandel(c1, c2, c3, n)
    fr%isotropic = (c1 == 1.0_real64 .and. c2 == 0.0_real64 .and. c3 == 0.0_real64)
    ! K = d n'/d sigma' = (2/9) 1(x)1 + (3/M^2) I_dev ;  H = P:K:P   (theory.md §1.3)
    k = (3.0_real64 / m_slope**2) * (identity6() - outer6(one6, one6) / 3.0_real64) &
        + (2.0_real64 / 9.0_real64) * outer6(one6, one6)
    fr%h = matmul(fr%p, matmul(k, fr%p))
    fr%p1 = matmul(fr%p, one6)
    fr%h1 = matmul(fr%h, one6)
    fr%tr_p1 = sum(fr%p1(1:3))
    fr%m_slope = m_slope
    fr%lambda_p = lambda_p
    fr%pc0 = pc0
    fr%eta = eta
    fr%e_ref = (fr%c(1, 1) + fr%c(2, 2) + fr%c(3, 3) + fr%c(4, 4) + fr%c(5, 5) + fr%c(6, 6)) / 6
    ! p_floor = max(1e-6 pc0, 1e-4) (theory.md §3.6), never above 1% of pc0 for very small pc0.
    fr%p_floor = min(max(1.0e-6_real64 * pc0, 1.0e-4_real64), 1.0e-2_real64 * pc0)
  end function frame_new

  !> Fictitious-stress invariants: p' = -tr(sigma')/3 and q'^2 = 3/2 s':s' (theory.md §1.3).
  pure subroutine invariants(fr, sig, pp, q2, s_dev)
    type(frame_t), intent(in) :: fr
    real(real64), intent(in) :: sig(6)
    real(real64), intent(out) :: pp, q2, s_dev(6)
    real(real64) :: sp(6)
    if (fr%isotropic) then
      sp = sig
    else
      sp = matmul(fr%p, sig)
    end if
    pp = -(sp(1) + sp(2) + sp(3)) / 3
    s_dev = sp + pp * one6
    q2 = 1.5_real64 * dot_product(s_dev, s_dev)
  end subroutine invariants

  !> f(sigma, pc) = q'^2/M^2 + p'(p' - pc), in stress^2 (theory.md §1.3).
  pure real(real64) function yield_function(fr, sig, pc) result(f)
    type(frame_t), intent(in) :: fr
    real(real64), intent(in) :: sig(6), pc
    real(real64) :: pp, q2, s_dev(6)
    call invariants(fr, sig, pp, q2, s_dev)
    f = q2 / fr%m_slope**2 + pp * (pp - pc)
  end function yield_function

  !> f, p', q'^2 and the flow direction N = df/dsigma = P:n' = H:sigma + (pc/3) P:1 (theory.md §1.3).
  pure subroutine flow_direction(fr, sig, pc, f, pp, q2, n_dir)
    type(frame_t), intent(in) :: fr
    real(real64), intent(in) :: sig(6), pc
    real(real64), intent(out) :: f, pp, q2, n_dir(6)
    real(real64) :: s_dev(6), n_fict(6)
    call invariants(fr, sig, pp, q2, s_dev)
    f = q2 / fr%m_slope**2 + pp * (pp - pc)
    ! n' = df/dsigma' = -(2p' - pc)/3 1 + (3/M^2) s'
    n_fict = (3.0_real64 / fr%m_slope**2) * s_dev - ((2 * pp - pc) / 3) * one6
    if (fr%isotropic) then
      n_dir = n_fict
    else
      n_dir = matmul(fr%p, n_fict)
    end if
  end subroutine flow_direction

  !> Integrate one frame over one step by backward Euler (theory.md §3.2-3.6).
  !>
  !> sig_n, pc_n: state at the start of the step; deps: strain increment; dt: time increment.
  !> Returns the stress, pc and viscoplastic strain increment at the end of the step and the
  !> algorithmic tangent d = dsigma/deps (Mandel). If want_error, err_est is the local error estimate
  !> |deps_vp - dt * rate_vp(start of step)| of theory.md §3.6 (zero for eta = 0).
  pure subroutine frame_integrate(fr, sig_n, pc_n, deps, dt, want_error, sig, pc, devp, d, &
                                  iterations, status, flags, err_est)
    type(frame_t), intent(in) :: fr
    real(real64), intent(in) :: sig_n(6), pc_n, deps(6), dt
    logical, intent(in) :: want_error
    real(real64), intent(out) :: sig(6), pc, devp(6), d(6, 6)
    integer, intent(out) :: iterations, status, flags
    real(real64), intent(out) :: err_est

    real(real64) :: sig_tr(6), f_tr, pc_r, denom, sf, sg, y_floor, x(nx), x_start(nx)
    real(real64) :: lu(nx, nx), rs(nx), cs(nx), z(nx), f, pp, q2, n_dir(6)
    integer :: piv(nx), j, it2
    logical :: ok, at_floor

    flags = 0
    iterations = 0
    err_est = 0
    devp = 0
    pc = pc_n
    d = fr%c
    ! Trial step (§3.2).
    sig_tr = sig_n + matmul(fr%c, deps)
    sig = sig_tr
    if (.not. all(is_finite(sig_tr))) then
      status = frame_failed
      return
    end if
    f_tr = yield_function(fr, sig_tr, pc_n)
    if (dt <= 0 .or. .not. (f_tr > 0)) then
      status = frame_elastic
      if (want_error .and. dt > 0) err_est = start_rate_error(fr, sig_n, pc_n, dt, devp)
      return
    end if

    ! Scaled consistency residual R_f = sf*f - sg*dgamma (§3.3, division-free form):
    ! sf = dt E_r / (dt E_r pc_r^2 + eta), sg = eta E_r / (dt E_r pc_r^2 + eta).
    pc_r = max(pc_n, fr%p_floor)
    denom = dt * fr%e_ref * pc_r**2 + fr%eta
    sf = dt * fr%e_ref / denom
    sg = fr%eta * fr%e_ref / denom
    y_floor = log(fr%p_floor / pc_n)

    ! Newton from the elastic predictor (§3.4); pc bounded below by the floor while iterating.
    x_start = [sig_tr, 0.0_real64, 0.0_real64]
    x = x_start
    status = frame_newton
    call newton_solve(fr, sig_tr, pc_n, sf, sg, y_floor, .false., x, lu, piv, rs, cs, &
                      iterations, ok)
    at_floor = .false.
    if (.not. ok .and. x(8) <= y_floor) then
      ! The hardening wants pc below the floor: hold pc at the floor and solve again.
      x = x_start
      at_floor = .true.
      call newton_solve(fr, sig_tr, pc_n, sf, sg, y_floor, .true., x, lu, piv, rs, cs, it2, ok)
      iterations = iterations + it2
    end if
    if (.not. ok) then
      ! Bracketed fallback (§3.4), then a Newton polish that also gives the Jacobian.
      status = frame_fallback
      flags = ior(flags, flag_fallback)
      call fallback_solve(fr, sig_tr, pc_n, sf, sg, y_floor, x, at_floor, ok)
      if (ok) then
        call newton_solve(fr, sig_tr, pc_n, sf, sg, y_floor, at_floor, x, lu, piv, rs, cs, &
                          it2, ok)
        iterations = iterations + it2
      end if
    end if
    if (.not. ok) then
      status = frame_failed
      sig = sig_n
      pc = pc_n
      d = fr%c
      return
    end if

    sig = x(1:6)
    pc = pc_n * exp(x(8))
    call flow_direction(fr, sig, pc, f, pp, q2, n_dir)
    devp = x(7) * n_dir
    if (at_floor) flags = ior(flags, flag_floor)
    if (pp < 0) flags = ior(flags, flag_tension)
    ! Consistent tangent = top-left 6x6 block of J^-1 (§3.5). J was equilibrated as
    ! Jt = diag(rs) J diag(cs), so J^-1 = diag(cs) Jt^-1 diag(rs).
    do j = 1, 6
      z = 0
      z(j) = rs(j)
      call lu_solve(nx, lu, piv, z)
      d(:, j) = cs(1:6) * z(1:6)
    end do
    if (want_error) err_est = start_rate_error(fr, sig_n, pc_n, dt, devp)
  end subroutine frame_integrate

  !> |deps_vp - dt * rate_vp(sig_n, pc_n)|: backward minus forward Euler increment, the local error
  !> indicator of theory.md §3.6 (like Abaqus' CETOL for creep). Zero when eta = 0 (no rate exists).
  pure real(real64) function start_rate_error(fr, sig_n, pc_n, dt, devp) result(err)
    type(frame_t), intent(in) :: fr
    real(real64), intent(in) :: sig_n(6), pc_n, dt, devp(6)
    real(real64) :: f, pp, q2, n_dir(6)
    err = 0
    if (fr%eta <= 0) return
    call flow_direction(fr, sig_n, pc_n, f, pp, q2, n_dir)
    ! Perzyna rate at the start of the step: <f>/eta N (theory.md §3.1, Y21 eq. 27).
    err = norm2(devp - (dt * max(f, 0.0_real64) / fr%eta) * n_dir)
  end function start_rate_error

  !> Local residual R(x) and Jacobian J(x) of theory.md §3.3-3.4 (R_f row scaled), with the relative
  !> size err of the residual.
  pure subroutine local_system(fr, sig_tr, pc_n, sf, sg, y_floor, floor_active, x, r, jac, err)
    type(frame_t), intent(in) :: fr
    real(real64), intent(in) :: sig_tr(6), pc_n, sf, sg, y_floor, x(nx)
    logical, intent(in) :: floor_active
    real(real64), intent(out) :: r(nx), jac(nx, nx), err
    real(real64) :: sig(6), dg, y, pc, f, pp, q2, n_dir(6), trn, scale_sig, err_eps, err_y, err_f
    sig = x(1:6)
    dg = x(7)
    y = x(8)
    pc = pc_n * exp(y)
    call flow_direction(fr, sig, pc, f, pp, q2, n_dir)
    trn = n_dir(1) + n_dir(2) + n_dir(3)

    ! R_eps = C^-1:(sigma - sigma_tr) + dgamma N
    r(1:6) = matmul(fr%cinv, sig - sig_tr) + dg * n_dir
    jac(1:6, 1:6) = fr%cinv + dg * fr%h
    jac(1:6, 7) = n_dir
    jac(1:6, 8) = (dg * pc / 3) * fr%p1
    if (floor_active) then
      ! pc held at the floor: R_y = lambda_p (y - y_floor)
      r(7) = fr%lambda_p * (y - y_floor)
      jac(7, 1:7) = 0
      jac(7, 8) = fr%lambda_p
    else
      ! R_y = lambda_p y + dgamma tr N   (pc_n+1 = pc_n exp(-d eps_v^vp / lambda_p), §1.4)
      r(7) = fr%lambda_p * y + dg * trn
      jac(7, 1:6) = dg * fr%h1
      jac(7, 7) = trn
      jac(7, 8) = fr%lambda_p + (dg * pc / 3) * fr%tr_p1
    end if
    ! R_f = sf f - sg dgamma
    r(8) = sf * f - sg * dg
    jac(8, 1:6) = sf * n_dir
    jac(8, 7) = -sg
    jac(8, 8) = -sf * pp * pc

    ! Relative residuals: each against the size of the terms that make it up.
    scale_sig = max(norm2(sig), norm2(sig_tr), pc, fr%p_floor)
    err_eps = norm2(r(1:6)) * fr%e_ref / scale_sig
    err_y = abs(r(7)) / (fr%lambda_p * (1 + abs(y)) + abs(dg * trn))
    ! f against the size of its terms and of the current surface (pc^2), which keeps the test
    ! meaningful at the apex p' = q' = 0, where every term of f vanishes.
    err_f = abs(r(8)) / max(sf * (q2 / fr%m_slope**2 + pp**2 + abs(pp) * pc + pc**2) + sg * dg, &
                            tiny(1.0_real64))
    err = max(err_eps, err_y, err_f)
  end subroutine local_system

  !> Clipped, projected Newton on the local system (theory.md §3.4). On success the equilibrated
  !> Jacobian at the converged point is returned factorised (lu, piv, rs, cs) for the tangent. One
  !> more Newton step is taken after the test passes, so that the stress is exact to round-off.
  pure subroutine newton_solve(fr, sig_tr, pc_n, sf, sg, y_floor, floor_active, x, lu, piv, rs, &
                               cs, iterations, ok)
    type(frame_t), intent(in) :: fr
    real(real64), intent(in) :: sig_tr(6), pc_n, sf, sg, y_floor
    logical, intent(in) :: floor_active
    real(real64), intent(inout) :: x(nx)
    real(real64), intent(out) :: lu(nx, nx), rs(nx), cs(nx)
    integer, intent(out) :: piv(nx), iterations
    logical, intent(out) :: ok
    real(real64) :: r(nx), dx(nx), err, y_low
    integer :: it, i
    logical :: converged, factored

    y_low = merge(-y_max, max(y_floor, -y_max), floor_active)
    converged = .false.
    ok = .false.
    iterations = 0
    do it = 1, max_newton + 1
      call local_system(fr, sig_tr, pc_n, sf, sg, y_floor, floor_active, x, r, lu, err)
      if (.not. (all(is_finite(r)) .and. all(is_finite(lu)))) return
      ! Row then column equilibration of J before LU.
      do i = 1, nx
        rs(i) = 1 / max(maxval(abs(lu(i, :))), tiny(1.0_real64))
        lu(i, :) = lu(i, :) * rs(i)
      end do
      do i = 1, nx
        cs(i) = 1 / max(maxval(abs(lu(:, i))), tiny(1.0_real64))
        lu(:, i) = lu(:, i) * cs(i)
      end do
      call lu_factor(nx, lu, piv, factored)
      if (.not. factored) return
      if (converged) then
        ok = err <= 1.0e3_real64 * newton_tol
        return
      end if
      if (it > max_newton) return
      converged = err <= newton_tol
      dx = -rs * r
      call lu_solve(nx, lu, piv, dx)
      dx = cs * dx
      x(1:6) = x(1:6) + dx(1:6)
      x(7) = max(0.0_real64, x(7) + dx(7))
      x(8) = min(max(x(8) + min(max(dx(8), -dy_max), dy_max), y_low), y_max)
      iterations = iterations + 1
    end do
  end subroutine newton_solve

  !> Fallback of theory.md §3.4 for the states where Newton stalls: for a fixed dgamma the stress is
  !> linear in pc, sigma = a - pc b, so the hardening equation is one scalar equation in y, solved by
  !> bracketing; the scaled consistency g(dgamma) = sf f - sg dgamma is then bracketed in dgamma.
  pure subroutine fallback_solve(fr, sig_tr, pc_n, sf, sg, y_floor, x, at_floor, ok)
    type(frame_t), intent(in) :: fr
    real(real64), intent(in) :: sig_tr(6), pc_n, sf, sg, y_floor
    real(real64), intent(out) :: x(nx)
    logical, intent(out) :: at_floor, ok
    real(real64) :: dg_lo, dg_hi, g_lo, g_hi, dg, g, sig(6), y, f, pp, q2, n_tr(6), cn
    integer :: k
    logical :: fl, okg

    ok = .false.
    at_floor = .false.
    x = [sig_tr, 0.0_real64, 0.0_real64]
    dg_lo = 0
    g_lo = sf * yield_function(fr, sig_tr, pc_n)
    ! First guess of the upper bracket: the elastic-predictor estimate f_tr / (N:C:N).
    call flow_direction(fr, sig_tr, pc_n, f, pp, q2, n_tr)
    cn = dot_product(n_tr, matmul(fr%c, n_tr))
    dg_hi = merge(f / cn, 1 / (fr%e_ref * pc_n), cn > 0 .and. f / cn > 0)
    do k = 1, 200
      call consistency_at(dg_hi, g_hi, sig, y, fl, okg)
      if (okg .and. g_hi < 0) exit
      if (okg) then
        dg_lo = dg_hi
        g_lo = g_hi
      end if
      dg_hi = 4 * dg_hi
      if (k == 200 .or. .not. is_finite(dg_hi)) return
    end do
    ! Illinois regula falsi on [dg_lo, dg_hi], g_lo > 0 > g_hi.
    do k = 1, 300
      dg = (dg_lo * g_hi - dg_hi * g_lo) / (g_hi - g_lo)
      if (.not. (dg > dg_lo .and. dg < dg_hi)) dg = 0.5_real64 * (dg_lo + dg_hi)
      call consistency_at(dg, g, sig, y, fl, okg)
      if (.not. okg) return
      if (g > 0) then
        dg_lo = dg; g_lo = g
        g_hi = 0.5_real64 * g_hi
      else
        dg_hi = dg; g_hi = g
        g_lo = 0.5_real64 * g_lo
      end if
      if (dg_hi - dg_lo <= 1.0e-15_real64 * dg_hi .or. g == 0) exit
    end do
    x = [sig, dg, y]
    at_floor = fl
    ok = .true.

  contains

    !> g(dgamma) with the hardening equation solved exactly for this dgamma.
    pure subroutine consistency_at(dgam, gval, sig_out, y_out, floor_hit, okc)
      real(real64), intent(in) :: dgam
      real(real64), intent(out) :: gval, sig_out(6), y_out
      logical, intent(out) :: floor_hit, okc
      real(real64) :: amat(6, 6), va(6), vb(6), alpha, beta, ylo, yhi, rlo, rhi, ym, rm, pcv
      integer :: pv(6), kk
      logical :: okf
      okc = .false.
      floor_hit = .false.
      gval = 0
      sig_out = sig_tr
      y_out = 0
      ! (C^-1 + dgamma H) sigma = C^-1 sigma_tr - dgamma (pc/3) P:1   =>   sigma = a - pc b
      amat = fr%cinv + dgam * fr%h
      call lu_factor(6, amat, pv, okf)
      if (.not. okf) return
      va = matmul(fr%cinv, sig_tr)
      call lu_solve(6, amat, pv, va)
      vb = (dgam / 3) * fr%p1
      call lu_solve(6, amat, pv, vb)
      ! tr N = alpha + beta pc ;  R_y(y) = lambda_p y + dgamma (alpha + beta pc_n e^y)
      alpha = dot_product(fr%h1, va)
      beta = fr%tr_p1 / 3 - dot_product(fr%h1, vb)
      ylo = max(y_floor, -y_max)
      yhi = y_max
      rlo = fr%lambda_p * ylo + dgam * (alpha + beta * pc_n * exp(ylo))
      rhi = fr%lambda_p * yhi + dgam * (alpha + beta * pc_n * exp(yhi))
      if (rlo >= 0) then
        y_out = ylo
        floor_hit = .true.
      else if (rhi <= 0) then
        return
      else
        do kk = 1, 200
          ym = 0.5_real64 * (ylo + yhi)
          rm = fr%lambda_p * ym + dgam * (alpha + beta * pc_n * exp(ym))
          if (rm < 0) then
            ylo = ym
          else
            yhi = ym
          end if
          if (yhi - ylo <= 1.0e-15_real64 * max(1.0_real64, abs(ym))) exit
        end do
        y_out = 0.5_real64 * (ylo + yhi)
      end if
      pcv = pc_n * exp(y_out)
      sig_out = va - pcv * vb
      gval = sf * yield_function(fr, sig_out, pcv) - sg * dgam
      okc = is_finite(gval)
    end subroutine consistency_at

  end subroutine fallback_solve

end module ccix_frame
