!> One elasto-viscoplastic solid frame of Cam-Clay IX: transversely isotropic elasticity, the modified
!> Cam-Clay surface in the fictitious stress sigma' = P:sigma, exponential hardening of pc, and Perzyna
!> overstress flow, integrated by backward Euler (theory.md sec. 1.3, sec. 1.4, sec. 3).
!>
!> Everything here is pure: one call integrates one frame over one step, from its converged state at
!> the start of the step, and returns the new state and the algorithmic tangent. The soft frame is the
!> isotropic special case (P = I) of the same frame.
!>
!> How the 8 x 8 local problem of theory.md sec. 3.3 is solved. With N = H:sigma + (pc/3) P:1 linear in
!> sigma (sec. 1.3), the strain residual R_eps = C^-1:(sigma - sigma_tr) + dgamma N = 0 gives sigma exactly
!> for given (dgamma, pc):  (C^-1 + dgamma H) sigma = C^-1 sigma_tr - dgamma (pc/3) P:1  (the
!> observation behind the fallback of sec. 3.4). C^-1 and H are diagonalised together:
!> V^T C^-1 V = I, V^T H V = Lambda (H is positive semi-definite, Lambda >= 0). In those coordinates,
!> sigma = V xi with
!>     xi_i = (a_i - dgamma (pc/3) b_i) / (1 + dgamma Lambda_i),  a = V^-1 sigma_tr,  b = V^T P:1,
!> and f = 1/2 xi.Lambda.xi + (pc/3) b.xi (f is quadratic in sigma with Hessian H). What remains are the
!> two scalar equations R_y = 0 and R_f = 0 of sec. 3.3 in (dgamma, y), each evaluation O(6). The
!> consistent tangent is the same top-left block of J^-1 as in sec. 3.5, written in these coordinates.
!>
!> The simultaneous diagonalisation is in closed form (ccix_pencil): C, P and H are transversely
!> isotropic about the bedding normal. Only a step that leaves the surface needs it.
module ccix_frame
  use, intrinsic :: iso_fortran_env, only: real64, int64
  use ccix_tensor, only: sqrt2, one6, is_finite, exponent_bits
  use ccix_walpole, only: ti_t, ti_mandel, ti_apply, ti_trace
  use ccix_pencil, only: pencil_t, pencil_diagonalise, v_times, v_inv_times, v_inv_t_times
  use ccix_elasticity, only: ti_stiffness
  use ccix_projection, only: ti_projection
  implicit none
  private

  !> Material constants of one frame, with what every step needs derived from them: the tensors as
  !> their Walpole coefficients (applied with ccix_walpole's ti_apply, as matrices only where a tangent
  !> needs them: frame_add_stiffness). No default initialisation: frame_new sets every component, and a
  !> local frame_t costs nothing per call.
  type, public :: frame_t
    real(real64) :: n(3), mh(6)       !< bedding normal n and m = n(x)n (Mandel)
    type(ti_t) :: cw                  !< elastic stiffness C, theory.md sec. 4.2
    type(ti_t) :: pw                  !< projection tensor P, theory.md sec. 1.2
    real(real64) :: tr_p1             !< tr(P:1) = 3 c1 + c2 + c3
    real(real64) :: m_slope           !< M, slope of the critical state line
    real(real64) :: lambda_p          !< plastic compressibility
    real(real64) :: pc0               !< initial preconsolidation pressure
    real(real64) :: eta               !< Perzyna viscosity [stress^3 * time]
    real(real64) :: e_ref             !< stiffness scale E_r = tr(C)/6, sec. 3.3
    real(real64) :: p_floor           !< lower bound of pc, sec. 3.6
    logical :: isotropic              !< P = I: skip the projection products
    logical :: isotropic_pencil       !< C isotropic and P = I (the soft frame): ccix_pencil's short form
    logical :: prepared               !< pe and c are set (frame_prepare); else derived where needed
    type(pencil_t) :: pe              !< the pencil (H, C^-1) diagonalised, where prepared
    real(real64) :: c(6, 6)           !< C as a Mandel matrix, where prepared
  end type frame_t

  !> Outcome of one frame integration.
  integer, parameter, public :: frame_elastic = 0, frame_newton = 1, frame_fallback = 2, &
                                frame_failed = -1
  !> Bits of the flags word. flag_outrun: the step is longer than the frame's softening time
  !> (theory.md sec. 3.4, "Steps that outrun the softening"): its solution does not continue the
  !> elastic trial.
  integer, parameter, public :: flag_floor = 1, flag_tension = 2, flag_fallback = 4, flag_outrun = 8

  integer, parameter :: max_newton = 40
  real(real64), parameter :: newton_tol = 1.0e-12_real64
  real(real64), parameter :: y_max = 50.0_real64, dy_max = 2.0_real64

  !> The two scalar equations of one step, evaluated at (dgamma, y): everything the Newton iteration,
  !> the fallback and the tangent need.
  type :: local_eval_t
    real(real64) :: pc, xi(6), n_xi(6), d(6)   ! pc, stress and flow direction in V-coordinates, 1/(1+g lambda)
    real(real64) :: f, trn, r_y, r_f, err
    real(real64) :: j_yg, j_yy, j_fg, j_fy      ! d(R_y, R_f)/d(dgamma, y)
  end type local_eval_t

  !> Fixed data of one viscoplastic step, with the pencil's eigenvectors (ccix_pencil).
  type :: step_t
    type(pencil_t) :: pe
    real(real64) :: a(6), pc_n, sf, sg, y_floor
    logical :: floor_active
  end type step_t

  public :: frame_new, frame_prepare, frame_add_stiffness, yield_function, flow_direction, frame_integrate

contains

  !> fr: the frame of the constants and the unit bedding normal n.
  pure recursive subroutine frame_new(fr, lam, mu_t, mu_l, a, b, m_slope, lambda_p, c1, c2, c3, pc0, eta, n)
    type(frame_t), intent(out) :: fr
    real(real64), intent(in) :: lam, mu_t, mu_l, a, b, m_slope, lambda_p, c1, c2, c3, pc0, eta, n(3)
    fr%n = n
    fr%mh(1:3) = n**2
    fr%mh(4) = sqrt2 * n(1) * n(2)
    fr%mh(5) = sqrt2 * n(1) * n(3)
    fr%mh(6) = sqrt2 * n(2) * n(3)
    fr%cw = ti_stiffness(lam, mu_t, mu_l, a, b)
    fr%pw = ti_projection(c1, c2, c3)
    fr%isotropic = (c1 == 1.0_real64 .and. c2 == 0.0_real64 .and. c3 == 0.0_real64)
    fr%isotropic_pencil = fr%isotropic .and. mu_l == mu_t .and. a == 0.0_real64 .and. b == 0.0_real64
    fr%prepared = .false.
    fr%tr_p1 = 3 * c1 + c2 + c3
    fr%m_slope = m_slope
    fr%lambda_p = lambda_p
    fr%pc0 = pc0
    fr%eta = eta
    fr%e_ref = ti_trace(fr%cw) * (1.0_real64 / 6)
    ! p_floor = max(1e-6 pc0, 1e-4) (theory.md sec. 3.6), never above 1% of pc0 for very small pc0.
    fr%p_floor = min(max(1.0e-6_real64 * pc0, 1.0e-4_real64), 1.0e-2_real64 * pc0)
  end subroutine frame_new

  !> Derive now what fr would otherwise derive in each step that needs it (a material kept for many
  !> calls): the pencil and C as a matrix. q is walpole_basis(fr%n).
  pure recursive subroutine frame_prepare(fr, q)
    type(frame_t), intent(inout) :: fr
    real(real64), intent(in) :: q(6, 6)
    call pencil_diagonalise(fr%cw, fr%pw, fr%m_slope, fr%isotropic_pencil, fr%pe)
    fr%c = ti_mandel(fr%cw, q)
    fr%prepared = .true.
  end subroutine frame_prepare

  !> d = d + w C, C the frame's stiffness (the tangent of a frame whose step is elastic); q is
  !> walpole_basis(fr%n).
  pure recursive subroutine frame_add_stiffness(fr, q, w, d)
    type(frame_t), intent(in) :: fr
    real(real64), intent(in) :: q(6, 6), w
    real(real64), intent(inout) :: d(6, 6)
    if (fr%prepared) then
      d = d + w * fr%c
    else
      d = d + w * ti_mandel(fr%cw, q)
    end if
  end subroutine frame_add_stiffness

  !> Fictitious-stress invariants: p' = -tr(sigma')/3 and q'^2 = 3/2 s':s' (theory.md sec. 1.3).
  pure recursive subroutine invariants(fr, sig, pp, q2, s_dev)
    type(frame_t), intent(in) :: fr
    real(real64), intent(in) :: sig(6)
    real(real64), intent(out) :: pp, q2, s_dev(6)
    real(real64) :: sp(6)
    if (fr%isotropic) then
      sp = sig
    else
      call ti_apply(fr%pw, fr%n, fr%mh, sig, sp)
    end if
    pp = -(sp(1) + sp(2) + sp(3)) / 3
    s_dev = sp + pp * one6
    q2 = 1.5_real64 * dot_product(s_dev, s_dev)
  end subroutine invariants

  !> f(sigma, pc) = q'^2/M^2 + p'(p' - pc), in stress^2 (theory.md sec. 1.3).
  pure recursive real(real64) function yield_function(fr, sig, pc) result(f)
    type(frame_t), intent(in) :: fr
    real(real64), intent(in) :: sig(6), pc
    real(real64) :: pp, q2, s_dev(6)
    call invariants(fr, sig, pp, q2, s_dev)
    f = q2 / fr%m_slope**2 + pp * (pp - pc)
  end function yield_function

  !> f, p', q'^2 and the flow direction N = df/dsigma = P:n' (theory.md sec. 1.3).
  pure recursive subroutine flow_direction(fr, sig, pc, f, pp, q2, n_dir)
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
      call ti_apply(fr%pw, fr%n, fr%mh, n_fict, n_dir)
    end if
  end subroutine flow_direction

  !> Integrate one frame over one step by backward Euler (theory.md sec. 3.2-3.6).
  !>
  !> sig_n, pc_n: state at the start of the step; deps: strain increment; dt: time increment.
  !> Returns the stress, pc and viscoplastic strain increment at the end of the step and the
  !> algorithmic tangent d = dsigma/deps (Mandel; only on viscoplastic steps, else it is C,
  !> frame_add_stiffness).
  !> If want_error, err_est is the local error estimate
  !> |deps_vp - dt * rate_vp(start of step)| of theory.md sec. 3.6 (zero for eta = 0).
  !> flags: flag_outrun when the step is at least the frame's softening time at the trial state
  !> (outruns_softening, local_solve).
  pure recursive subroutine frame_integrate(fr, q, sig_n, pc_n, deps, dt, want_error, sig, pc, devp, d, &
                                            iterations, status, flags, err_est, f_end)
    type(frame_t), intent(in) :: fr
    real(real64), intent(in) :: q(6, 6)   !< walpole_basis(fr%n)
    real(real64), intent(in) :: sig_n(6), pc_n, deps(6), dt
    logical, intent(in) :: want_error
    real(real64), intent(out) :: sig(6), pc, devp(6), d(6, 6)
    integer, intent(out) :: iterations, status, flags
    real(real64), intent(out) :: err_est
    real(real64), intent(out) :: f_end   !< yield function at the end of the step

    type(step_t) :: st
    type(local_eval_t) :: ev
    real(real64) :: sig_tr(6), f_tr, g, y

    flags = 0
    iterations = 0
    err_est = 0
    devp = 0
    pc = pc_n
    ! Trial step (sec. 3.2). On elastic and failed steps d is not set: the tangent is C.
    call ti_apply(fr%cw, fr%n, fr%mh, deps, sig_tr)
    sig_tr = sig_n + sig_tr
    sig = sig_tr
    if (.not. is_finite(sum(sig_tr))) then
      status = frame_failed
      return
    end if
    f_tr = yield_function(fr, sig_tr, pc_n)
    f_end = f_tr
    if (dt <= 0 .or. .not. (f_tr > 0)) then
      status = frame_elastic
      if (want_error .and. dt > 0) err_est = start_rate_error(fr, sig_n, pc_n, dt, devp)
      return
    end if

    call step_new(fr, q, sig_tr, pc_n, dt, st)
    call local_solve(fr, st, g, y, ev, iterations, status, flags)
    if (status == frame_failed) then
      f_end = f_tr
      sig = sig_n
      pc = pc_n
      return
    end if
    call step_result(q, st, g, ev, sig, pc, devp, d, flags, f_end)
    if (want_error) err_est = start_rate_error(fr, sig_n, pc_n, dt, devp)
  end subroutine frame_integrate

  !> The fixed data of the viscoplastic step from sigma_tr (theory.md sec. 3.3): the scaled consistency
  !> residual R_f = sf*f - sg*dgamma in division-free form, sf = dt E_r / (dt E_r pc_r^2 + eta),
  !> sg = eta E_r / (dt E_r pc_r^2 + eta); the floor of y = ln(pc/pc_n); the pencil and a = V^-1 sigma_tr.
  pure recursive subroutine step_new(fr, q, sig_tr, pc_n, dt, st)
    type(frame_t), intent(in) :: fr
    real(real64), intent(in) :: q(6, 6), sig_tr(6), pc_n, dt
    type(step_t), intent(out) :: st
    real(real64) :: pc_r, denom
    pc_r = max(pc_n, fr%p_floor)
    denom = dt * fr%e_ref * pc_r**2 + fr%eta
    st%sf = dt * fr%e_ref / denom
    st%sg = fr%eta * fr%e_ref / denom
    st%pc_n = pc_n
    st%y_floor = log(fr%p_floor / pc_n)
    if (fr%prepared) then
      st%pe = fr%pe
    else
      call pencil_diagonalise(fr%cw, fr%pw, fr%m_slope, fr%isotropic_pencil, st%pe)
    end if
    call v_inv_times(q, st%pe, sig_tr, st%a)
    st%floor_active = .false.
  end subroutine step_new

  !> The step is at least the frame's softening time t_s = eta/S (theory.md sec. 3.4, "Steps that
  !> outrun the softening"); ev is the evaluation at the trial, (dgamma, y) = 0. Along the hardening
  !> equation R_y = 0, dy/ddgamma = -j_yg/j_yy, and the scaled consistency residual
  !> R_f = sf f - sg dgamma has the slope sf S - sg, S = df/ddgamma = -N:C:N + p' pc tr N / lambda_p
  !> the frame's softening modulus and sg/sf = eta/dt. Where the slope is >= 0 (dt S >= eta), R_f
  !> rises from its trial value: no root continues the trial, and as the increment crosses f_tr = 0
  !> the solution jumps to a far root. With eta = 0: whenever the trial softens (S >= 0).
  pure recursive logical function outruns_softening(ev) result(outruns)
    type(local_eval_t), intent(in) :: ev
    ! j_yy = lambda_p > 0 at dgamma = 0 (sec. 3.4)
    outruns = ev%j_fg - ev%j_fy * ev%j_yg / ev%j_yy >= 0
  end function outruns_softening

  !> The local problem of the step (theory.md sec. 3.4) solved for (dgamma, y) = (g, y), ev the
  !> evaluation there: Newton from the elastic predictor, pc bounded below by the floor while
  !> iterating; if it fails with pc at the floor, again with pc held there; if it still fails, the
  !> bracketed fallback, then Newton from its solution for the exact root and the tangent. status:
  !> frame_newton, frame_fallback (flag_fallback in flags) or frame_failed; flag_outrun from the
  !> evaluation at the trial (outruns_softening).
  pure recursive subroutine local_solve(fr, st, g, y, ev, iterations, status, flags)
    type(frame_t), intent(in) :: fr
    type(step_t), intent(inout) :: st
    real(real64), intent(out) :: g, y
    type(local_eval_t), intent(out) :: ev
    integer, intent(out) :: iterations, status
    integer, intent(inout) :: flags
    integer :: it2
    logical :: ok, outruns
    status = frame_newton
    g = 0
    y = 0
    call newton_solve(fr, st, g, y, ev, iterations, ok, outruns)
    if (outruns) flags = ior(flags, flag_outrun)
    if (.not. ok .and. y <= st%y_floor) then
      ! The hardening wants pc below the floor: hold pc at the floor and solve again.
      st%floor_active = .true.
      g = 0
      y = 0
      call newton_solve(fr, st, g, y, ev, it2, ok)
      iterations = iterations + it2
    end if
    if (.not. ok) then
      status = frame_fallback
      flags = ior(flags, flag_fallback)
      call fallback_solve(fr, st, g, y, ok)
      if (ok) then
        call newton_solve(fr, st, g, y, ev, it2, ok)
        iterations = iterations + it2
      end if
    end if
    if (.not. ok) status = frame_failed
  end subroutine local_solve

  !> The end of a converged step from its solution (g, ev): stress, pc, the viscoplastic strain
  !> increment, the floor and tension flags, the yield function and the consistent tangent d.
  pure recursive subroutine step_result(q, st, g, ev, sig, pc, devp, d, flags, f_end)
    real(real64), intent(in) :: q(6, 6), g
    type(step_t), intent(in) :: st
    type(local_eval_t), intent(in) :: ev
    real(real64), intent(out) :: sig(6), pc, devp(6), d(6, 6), f_end
    integer, intent(inout) :: flags
    real(real64) :: n_dir(6)
    pc = ev%pc
    call v_times(q, st%pe, ev%xi, sig)
    f_end = ev%f
    ! N = H:sigma + (pc/3) P:1 (sec. 1.3) from its V-coordinates: V^T N = n_xi, N = V^-T n_xi.
    call v_inv_t_times(q, st%pe, ev%n_xi, n_dir)
    devp = g * n_dir
    if (st%floor_active) flags = ior(flags, flag_floor)
    if (dot_product(st%pe%b, ev%xi) > 0) flags = ior(flags, flag_tension)   ! p' = -b.xi/3 < 0
    d = consistent_tangent(q, st, g, ev)
  end subroutine step_result

  !> |deps_vp - dt * rate_vp(sig_n, pc_n)|: backward minus forward Euler increment, the local error
  !> indicator of theory.md sec. 3.6 (like Abaqus' CETOL for creep). Zero when eta = 0 (no rate exists).
  pure recursive real(real64) function start_rate_error(fr, sig_n, pc_n, dt, devp) result(err)
    type(frame_t), intent(in) :: fr
    real(real64), intent(in) :: sig_n(6), pc_n, dt, devp(6)
    real(real64) :: f, pp, q2, n_dir(6)
    err = 0
    if (fr%eta <= 0) return
    call flow_direction(fr, sig_n, pc_n, f, pp, q2, n_dir)
    ! Perzyna rate at the start of the step: <f>/eta N (theory.md sec. 3.1, Y21 eq. 27).
    err = norm2(devp - (dt * max(f, 0.0_real64) / fr%eta) * n_dir)
  end function start_rate_error

  !> R_y and R_f of theory.md sec. 3.3 at (dgamma, y) with sigma eliminated exactly, their Jacobian and
  !> the relative size of the residual.
  pure recursive function local_eval(fr, st, g, y) result(ev)
    type(frame_t), intent(in) :: fr
    type(step_t), intent(in) :: st
    real(real64), intent(in) :: g, y
    type(local_eval_t) :: ev
    real(real64) :: c3, pc3, q_terms, bxi, f_g, f_y, trn_g, trn_y, nd(6)
    ev%pc = st%pc_n * exp(y)
    pc3 = ev%pc / 3
    c3 = g * pc3
    ev%d = 1 / (1 + g * st%pe%lambda_h)
    ev%xi = (st%a - c3 * st%pe%b) * ev%d                 ! stress
    ev%n_xi = st%pe%lambda_h * ev%xi + pc3 * st%pe%b        ! flow direction N, V^T N
    q_terms = 0.5_real64 * dot_product(st%pe%lambda_h * ev%xi, ev%xi)   ! q'^2/M^2 + p'^2
    bxi = dot_product(st%pe%b, ev%xi)                                    ! = -3 p'
    ev%f = q_terms + pc3 * bxi
    ev%trn = dot_product(st%pe%h1, ev%xi) + pc3 * fr%tr_p1
    ! d xi/d dgamma = -n_xi d ;  d xi/dy = -c3 b d ;  d f/d xi = n_xi ;  d f/d pc = bxi/3
    nd = ev%n_xi * ev%d
    f_g = -dot_product(ev%n_xi, nd)
    f_y = -c3 * dot_product(st%pe%b, nd) + pc3 * bxi
    trn_g = -dot_product(st%pe%h1, nd)
    trn_y = -c3 * dot_product(st%pe%h1, st%pe%b * ev%d) + pc3 * fr%tr_p1
    if (st%floor_active) then
      ! pc held at the floor: R_y = lambda_p (y - y_floor)
      ev%r_y = fr%lambda_p * (y - st%y_floor)
      ev%j_yg = 0
      ev%j_yy = fr%lambda_p
    else
      ! R_y = lambda_p y + dgamma tr N   (pc_n+1 = pc_n exp(-d eps_v^vp / lambda_p), sec. 1.4)
      ev%r_y = fr%lambda_p * y + g * ev%trn
      ev%j_yg = ev%trn + g * trn_g
      ev%j_yy = fr%lambda_p + g * trn_y
    end if
    ! R_f = sf f - sg dgamma
    ev%r_f = st%sf * ev%f - st%sg * g
    ev%j_fg = st%sf * f_g - st%sg
    ev%j_fy = st%sf * f_y
    ! Relative residuals: each against the size of its terms; f also against the surface size pc^2,
    ! which keeps the test meaningful at the apex p' = q' = 0 where every term of f vanishes.
    ev%err = max(abs(ev%r_y) / (fr%lambda_p * (1 + abs(y)) + abs(g * ev%trn)), &
                 abs(ev%r_f) / max(st%sf * (q_terms + abs(pc3 * bxi) + ev%pc**2) + st%sg * g, &
                                   tiny(1.0_real64)))
  end function local_eval

  !> Clipped, projected Newton on (dgamma, y) (theory.md sec. 3.4). One more Newton step is taken after
  !> the test passes, so that the state is exact to round-off; ev is the evaluation at the result.
  pure recursive subroutine newton_solve(fr, st, g, y, ev, iterations, ok, start_outruns)
    type(frame_t), intent(in) :: fr
    type(step_t), intent(in) :: st
    real(real64), intent(inout) :: g, y
    type(local_eval_t), intent(out) :: ev
    integer, intent(out) :: iterations
    logical, intent(out) :: ok
    !> outruns_softening at the start point (false where its evaluation is not finite)
    logical, intent(out), optional :: start_outruns
    real(real64) :: det, dg, dy, y_low, lam_ref, z, w
    integer :: it
    logical :: converged

    y_low = merge(-y_max, max(st%y_floor, -y_max), st%floor_active)
    ! Newton's dgamma-update is applied to z = 1/(1 + dgamma lam_ref) in (0, 1]: far outside the
    ! surface f falls like (1 + dgamma lam)^-2, on which plain Newton from dgamma = 0 gains only a
    ! factor 1.5 per iteration, while f is close to quadratic in z. Same root, same Jacobian.
    lam_ref = max(maxval(st%pe%lambda_h), tiny(1.0_real64))
    converged = .false.
    ok = .false.
    iterations = 0
    if (present(start_outruns)) start_outruns = .false.
    do it = 1, max_newton + 1
      ev = local_eval(fr, st, g, y)
      ! is_finite of the sum, written inline in this loop (its bits: no comparison of a NaN): a call
      ! to the public function is not inlined under -fPIC and cost about 2 % of a viscoplastic call.
      z = ev%err + ev%j_yg + ev%j_yy + ev%j_fg + ev%j_fy
      if (iand(transfer(z, 0_int64), exponent_bits) == exponent_bits) return
      ! after the finiteness test: no ordered comparison of a NaN (traps on in a host)
      if (it == 1 .and. present(start_outruns)) start_outruns = outruns_softening(ev)
      if (converged) then
        ok = ev%err <= 1.0e3_real64 * newton_tol
        return
      end if
      if (it > max_newton) return
      converged = ev%err <= newton_tol
      det = ev%j_yg * ev%j_fy - ev%j_yy * ev%j_fg
      if (.not. (abs(det) > 0)) return
      dg = -(ev%j_fy * ev%r_y - ev%j_yy * ev%r_f) / det
      dy = -(ev%j_yg * ev%r_f - ev%j_fg * ev%r_y) / det
      ! z_new = z - lam_ref z^2 dg = z (1 - w) with w = lam_ref z dg, written without cancellation
      ! as dgamma_new = (dgamma + w/lam_ref) / (1 - w); w <= 0.9 caps the growth of 1/z at 10x.
      z = 1 / (1 + g * lam_ref)
      w = min(lam_ref * z * dg, 0.9_real64)
      g = max(0.0_real64, (g + w / lam_ref) / (1 - w))
      y = min(max(y + min(max(dy, -dy_max), dy_max), y_low), y_max)
      iterations = iterations + 1
    end do
  end subroutine newton_solve

  !> The consistent tangent dsigma/deps (theory.md sec. 3.5): with sigma = V xi(a, dgamma, y) and
  !> a = V^-1 (sigma_n + C deps), d xi/deps at fixed (dgamma, y) is diag(d) V^T, so
  !>   D = V diag(d) V^T - u_n (x) dg/deps - (dgamma pc/3) u_b (x) dy/deps,
  !> with u_n = V (n_xi d), u_b = V (b d), and (dg, dy)/deps from the 2 x 2 Jacobian G of (R_y, R_f):
  !>   G (dg, dy)/deps = -(dgamma u_h, sf u_n),  u_h = V (h1 d)  (u_h absent when pc is at the floor).
  pure recursive function consistent_tangent(q, st, g, ev) result(d)
    real(real64), intent(in) :: q(6, 6)
    type(step_t), intent(in) :: st
    real(real64), intent(in) :: g
    type(local_eval_t), intent(in) :: ev
    real(real64) :: d(6, 6), u_n(6), u_b(6), u_h(6), ry_e(6), rf_e(6), dg_e(6), dy_e(6), det, c3
    real(real64) :: m11, m12, m22, y1(6), y2(6), mk(6)
    integer :: j, k
    call v_times(q, st%pe, ev%n_xi * ev%d, u_n)
    call v_times(q, st%pe, st%pe%b * ev%d, u_b)
    c3 = g * ev%pc / 3
    if (st%floor_active) then
      ry_e = 0
    else
      call v_times(q, st%pe, st%pe%h1 * ev%d, u_h)
      ry_e = g * u_h
    end if
    rf_e = st%sf * u_n
    det = ev%j_yg * ev%j_fy - ev%j_yy * ev%j_fg
    dg_e = -(ev%j_fy * ry_e - ev%j_yy * rf_e) / det
    dy_e = -(ev%j_yg * rf_e - ev%j_fg * ry_e) / det
    ! V diag(d) V^T = Q M Q^T with M = B diag(d) B^T = diag(W diag(d1, d2) W^T, r_k^2 d_k):
    ! D = q1 y1^T + q2 y2^T + sum_k>2 mk q_k q_k^T - u_n dg_e^T - c3 u_b dy_e^T, column by column.
    m11 = st%pe%w(1, 1)**2 * ev%d(1) + st%pe%w(1, 2)**2 * ev%d(2)
    m12 = st%pe%w(1, 1) * st%pe%w(2, 1) * ev%d(1) + st%pe%w(1, 2) * st%pe%w(2, 2) * ev%d(2)
    m22 = st%pe%w(2, 1)**2 * ev%d(1) + st%pe%w(2, 2)**2 * ev%d(2)
    y1 = m11 * q(:, 1) + m12 * q(:, 2)
    y2 = m12 * q(:, 1) + m22 * q(:, 2)
    mk = st%pe%r**2 * ev%d
    do j = 1, 6
      d(:, j) = -u_n * dg_e(j) - c3 * u_b * dy_e(j) + q(:, 1) * y1(j) + q(:, 2) * y2(j)
      do k = 3, 6
        d(:, j) = d(:, j) + (mk(k) * q(j, k)) * q(:, k)
      end do
    end do
  end function consistent_tangent

  !> Fallback of theory.md sec. 3.4 for the states where Newton stalls: for a fixed dgamma the hardening
  !> equation R_y = 0 is one scalar equation in y, solved by safeguarded Newton in a bracket; the
  !> scaled consistency R_f(dgamma) is then bracketed in dgamma (Illinois regula falsi). The result
  !> only starts the Newton iteration that gives the final state (frame_integrate), so the bracket is
  !> closed to 1e-12 relative, not to round-off: near the root R_f is round-off noise and a tighter
  !> bracket cost up to 300 iterations (ms per call) without changing the answer.
  pure recursive subroutine fallback_solve(fr, st, g, y, ok)
    type(frame_t), intent(in) :: fr
    type(step_t), intent(inout) :: st
    real(real64), intent(out) :: g, y
    logical, intent(out) :: ok
    real(real64) :: g_lo, g_hi, r_lo, r_hi, r, y_hi_sol, n2
    type(local_eval_t) :: ev
    integer :: k
    logical :: okc

    ok = .false.
    st%floor_active = .false.
    g = 0
    y = 0
    g_lo = 0
    ev = local_eval(fr, st, 0.0_real64, 0.0_real64)
    r_lo = ev%r_f
    ! First guess of the upper bracket: the elastic-predictor estimate f_tr / (N:C:N).
    n2 = dot_product(ev%n_xi, ev%n_xi)
    g_hi = merge(ev%f / n2, 1 / (fr%e_ref * st%pc_n), n2 > 0 .and. ev%f > 0)
    do k = 1, 200
      call consistency_at(fr, st, g_hi, r_hi, y_hi_sol, okc)
      if (okc .and. r_hi < 0) exit
      if (okc) then
        g_lo = g_hi
        r_lo = r_hi
      end if
      g_hi = 4 * g_hi
      if (k == 200 .or. .not. is_finite(g_hi)) return
    end do
    do k = 1, 300
      g = (g_lo * r_hi - g_hi * r_lo) / (r_hi - r_lo)
      if (.not. (g > g_lo .and. g < g_hi)) g = 0.5_real64 * (g_lo + g_hi)
      call consistency_at(fr, st, g, r, y, okc)
      if (.not. okc) return
      if (r > 0) then
        g_lo = g; r_lo = r
        r_hi = 0.5_real64 * r_hi
      else
        g_hi = g; r_hi = r
        r_lo = 0.5_real64 * r_lo
      end if
      if (g_hi - g_lo <= 1.0e-12_real64 * g_hi .or. r == 0) exit
    end do
    call consistency_at(fr, st, g, r, y, okc)
    ok = okc

  end subroutine fallback_solve

  !> R_f(dgamma) with the hardening equation solved for y (pc at the floor if it wants to go below).
  pure recursive subroutine consistency_at(fr, st, gam, rf, y_sol, okc)
    type(frame_t), intent(in) :: fr
    type(step_t), intent(inout) :: st
    real(real64), intent(in) :: gam
    real(real64), intent(out) :: rf, y_sol
    logical, intent(out) :: okc
    real(real64) :: ylo, yhi, ym, y_new, dy_old
    type(local_eval_t) :: e
    integer :: kk
    okc = .false.
    rf = 0
    st%floor_active = .false.
    ylo = max(st%y_floor, -y_max)
    yhi = y_max
    e = local_eval(fr, st, gam, ylo)
    if (e%r_y >= 0) then
      y_sol = ylo
      st%floor_active = .true.
    else
      e = local_eval(fr, st, gam, yhi)
      if (e%r_y <= 0) return
      ! R_y(y) = 0 inside the bracket [ylo, yhi] (R_y < 0 at ylo, > 0 at yhi): Newton steps with
      ! dR_y/dy, a bisection whenever Newton would leave the bracket or shrinks it too slowly.
      ym = 0.5_real64 * (ylo + yhi)
      dy_old = yhi - ylo
      do kk = 1, 200
        e = local_eval(fr, st, gam, ym)
        if (e%r_y < 0) then
          ylo = ym
        else if (e%r_y > 0) then
          yhi = ym
        else
          exit
        end if
        if (yhi - ylo <= 1.0e-15_real64 * max(1.0_real64, abs(ym))) exit
        y_new = ym - e%r_y / e%j_yy
        if (.not. (y_new > ylo .and. y_new < yhi) .or. 2 * abs(y_new - ym) > dy_old) then
          y_new = 0.5_real64 * (ylo + yhi)
        end if
        dy_old = abs(y_new - ym)
        ym = y_new
        if (dy_old <= 1.0e-15_real64 * max(1.0_real64, abs(ym))) exit
      end do
      y_sol = ym
    end if
    e = local_eval(fr, st, gam, y_sol)
    rf = e%r_f
    okc = is_finite(rf)
  end subroutine consistency_at


end module ccix_frame
