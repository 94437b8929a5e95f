#include "semismooth.h"

#include "contact_estimate.h"

#include "contact_options.h"

#include "../fe/fe_pmg.h"
#include "../fe/fe_state.h"
#include "../io/log_events.h"

#include <math.h>
#include <petscksp.h>
#include <stdio.h>
#include <string.h>

/* Everything the Newton loop works on: the problem, the contact, the unknowns (u, u_r, lambda) with
 * their committed values and last converged increments (the predictor), residual parts and settings. */

/* Force control at zero load: no contact pressure anywhere, and the indenter rests on the surface (its
 * position is not an unknown then). */
PetscBool semismooth_released(const Semismooth *in) { return !in->depth_control && in->target == 0 ? PETSC_TRUE : PETSC_FALSE; }

/* Residual at the iterate (U, ur, lam): the element loop with the UMAT, the gaps, the contact forces;
 * returns the merit: the residual norm relative to the force scale (the active set does not enter). */
PetscErrorCode semismooth_evaluate(Semismooth *in, PetscReal *merit) {
  PetscFunctionBeginUser;
  PetscCall(fe_residual(NULL, in->U, in->Ru, in->p));
  PetscCall(PetscLogEventBegin(driver_event(EV_CONTACT), 0, 0, 0, 0));
  PetscCall(contact_update_gaps(&in->ct, in->U, in->ur));
  PetscCall(contact_residual(&in->ct, in->lam, in->ur, in->depth_control, in->target, in->Ru, &in->Rr, &in->ncp));
  PetscCall(PetscLogEventEnd(driver_event(EV_CONTACT), 0, 0, 0, 0));
  PetscCall(VecNorm(in->Ru, NORM_2, &in->ru));
  if (semismooth_released(in)) { /* released: the indenter rests on the surface (set after
                                                   the step), so only lambda = 0 is asked for */
    const PetscScalar *la;
    PetscReal          s = 0, all;
    PetscCall(VecGetArrayRead(in->lam, &la));
    for (PetscInt i = 0; i < in->ct.n; i++) s += PetscSqr(in->ct.w[i] * PetscRealPart(la[i]));
    PetscCall(VecRestoreArrayRead(in->lam, &la));
    PetscCall(MPIU_Allreduce(&s, &all, 1, MPIU_REAL, MPI_SUM, PetscObjectComm((PetscObject)in->U)));
    in->ncp = PetscSqrtReal(all);
  }
  *merit = PetscSqrtReal(in->ru * in->ru + in->ncp * in->ncp + in->Rr * in->Rr) / in->fref; /* R_r: a force (contact.h) */
  PetscFunctionReturn(0);
}

/* A signature of the active set (all ranks), to notice a set met again: cycling (met_again). */
static PetscErrorCode active_signature(Semismooth *in, unsigned long long *sig) {
  unsigned long long loc = 0;
  PetscFunctionBeginUser;
  for (PetscInt i = 0; i < in->ct.n; i++)
    if (in->ct.active[i]) {
      unsigned long long z = (unsigned long long)(in->ct.rstart + i + 1) * 0x9E3779B97F4A7C15ULL;
      z ^= z >> 31, z *= 0xBF58476D1CE4E5B9ULL, z ^= z >> 27;
      loc += z;
    }
  PetscCallMPI(MPI_Allreduce(&loc, sig, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, PetscObjectComm((PetscObject)in->U)));
  PetscFunctionReturn(0);
}

static const char *failure_reason[] = {"", "Newton did not converge", "the active set cycles", "the linear solver failed",
                                       "Newton stalled (the merit did not fall tenfold over -indent_stall_window iterations)"};

/* Why a step failed, with the residual Newton reached (relative to the load, as -indent_rtol). Stalled between rtol
   and its square root, far below what any output needs, it is round-off or, on fixed steps (no error estimate there
   to stop Newton earlier), the two-cycle of a few points switching branch (docs/contact.md, "The Newton loop"): the
   message says so, and which option ends such a step. */
const char *semismooth_failure(Semismooth *in, int status) {
  PetscReal r = in->history.n ? in->history.merit[in->history.n - 1] : -1;
  if (r < 0) return failure_reason[status];
  snprintf(in->why, sizeof in->why, "%s, at a residual of %.2g of the load against -indent_rtol %g%s", failure_reason[status], (double)r,
           (double)in->rtol,
           (status == STEP_STALLED || status == STEP_DIVERGED) && r < PetscSqrtReal(in->rtol)
             ? ": below the tolerance's square root, far below what an output needs, where round-off or, on fixed steps, a few "
               "points switching branch can hold Newton (docs/contact.md, \"The Newton loop\"); a larger -indent_rtol (e.g. 1e-6) "
               "ends such a step"
             : "");
  return in->why;
}

/* The residual (R_u, R_r, R_lambda) at (U, ur, lam) + e (du, dur, dlam), into (ru, rr, rl); the active set
   stays the one the tangent was built for. */
static PetscErrorCode residual_along(Semismooth *in, PetscReal e, Vec du, PetscReal dur, Vec dlam, Vec ru, PetscReal *rr, Vec rl) {
  PetscReal m;
  PetscFunctionBeginUser;
  PetscCall(VecAXPY(in->U, e, du));
  PetscCall(VecAXPY(in->lam, e, dlam));
  in->ur += e * dur;
  PetscCall(semismooth_evaluate(in, &m));
  PetscCall(contact_constraint_residual(&in->ct, in->lam, rl));
  PetscCall(VecCopy(in->Ru, ru));
  *rr = in->Rr;
  PetscCall(VecAXPY(in->U, -e, du));
  PetscCall(VecAXPY(in->lam, -e, dlam));
  in->ur -= e * dur;
  PetscFunctionReturn(0);
}

/* -indent_check_tangent: the whole linearised system of eq. 15 (the FE block with the UMAT's tangent, the
   contact blocks, the indenter row and the complementarity rows of the current active set) against central
   differences of the residual along a random direction; prints |J d - FD| / |J d|. */
static PetscErrorCode check_tangent(Semismooth *in, PetscReal *merit) {
  Vec       du, dl, ju, jl, rp, rm, lp, lm;
  PetscReal jr, rrp, rrm, nu, eps;
  PetscFunctionBeginUser;
  Vec *v[] = {&du, &ju, &rp, &rm, NULL}, *w[] = {&dl, &jl, &lp, &lm, NULL};
  for (int k = 0; v[k]; k++) PetscCall(VecDuplicate(in->U, v[k]));
  for (int k = 0; w[k]; k++) PetscCall(VecDuplicate(in->lam, w[k]));
  PetscCall(VecSetRandom(du, NULL));
  PetscCall(VecSetRandom(dl, NULL));
  { /* the multipliers of the active set only: the inactive ones sit on identity rows (eq. 14) */
    PetscScalar *a;
    PetscCall(VecGetArray(dl, &a));
    for (PetscInt i = 0; i < in->ct.n; i++)
      if (!in->ct.active[i]) a[i] = 0;
    PetscCall(VecRestoreArray(dl, &a));
  }
  PetscCall(VecNorm(in->U, NORM_INFINITY, &nu));
  PetscReal xmax = 0, xall;
  for (PetscInt i = 0; i < in->ct.n * in->ct.dim; i++) xmax = PetscMax(xmax, PetscAbsReal(in->ct.X[i]));
  PetscCall(MPIU_Allreduce(&xmax, &xall, 1, MPIU_REAL, MPI_MAX, PetscObjectComm((PetscObject)in->U)));
  PetscReal scale = PetscMax(PetscMax(nu, PetscAbsReal(in->ur)), 1e-3 * xall), dur = scale; /* of the solution's size */
  PetscCall(VecScale(du, scale));
  PetscCall(VecScale(dl, in->fref / PetscMax(in->ct.weight_sum, 1e-300)));
  /* -indent_check_tangent_part u | r | lambda (1, 2, 3): only that part of the direction */
  if (in->tangent_part && in->tangent_part != 1) PetscCall(VecZeroEntries(du));
  if (in->tangent_part && in->tangent_part != 2) dur = 0;
  if (in->tangent_part && in->tangent_part != 3) PetscCall(VecZeroEntries(dl));
  eps = 1e-6;
  PetscCall(indent_solver_apply(&in->sol, du, dur, dl, ju, &jr, jl));
  PetscCall(residual_along(in, eps, du, dur, dl, rp, &rrp, lp));
  PetscCall(residual_along(in, -eps, du, dur, dl, rm, &rrm, lm));
  PetscCall(VecAXPY(rp, -1.0, rm));
  PetscCall(VecScale(rp, 1 / (2 * eps))); /* FD of R_u */
  PetscCall(VecAXPY(lp, -1.0, lm));
  PetscCall(VecScale(lp, 1 / (2 * eps)));
  PetscReal fr = (rrp - rrm) / (2 * eps), nj[2], nd[2];
  PetscCall(VecNorm(ju, NORM_2, &nj[0]));
  PetscCall(VecNorm(jl, NORM_2, &nj[1]));
  PetscCall(VecAXPY(rp, -1.0, ju));
  PetscCall(VecAXPY(lp, -1.0, jl));
  PetscCall(VecNorm(rp, NORM_2, &nd[0]));
  PetscCall(VecNorm(lp, NORM_2, &nd[1]));
  PetscReal num = PetscSqrtReal(nd[0] * nd[0] + nd[1] * nd[1] + PetscSqr(fr - jr)), den = PetscSqrtReal(nj[0] * nj[0] + nj[1] * nj[1] + jr * jr);
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "    tangent check (eq. 15, whole system): |J d - FD| / |J d| = %.3e  (u rows %.2e, indenter row %.2e, "
                                          "multiplier rows %.2e)\n", (double)(num / den), (double)(nd[0] / den), (double)(PetscAbsReal(fr - jr) / den),
                        (double)(nd[1] / den)));
  for (int k = 0; v[k]; k++) PetscCall(VecDestroy(v[k]));
  for (int k = 0; w[k]; k++) PetscCall(VecDestroy(w[k]));
  PetscCall(semismooth_evaluate(in, merit)); /* back to the iterate */
  PetscCall(contact_constraint_residual(&in->ct, in->lam, in->Rlam));
  PetscFunctionReturn(0);
}

/* The Newton stopping rule of implicit ODE solvers (Hairer & Wanner, Solving ODEs II, §IV.8): with the
 * contraction theta of the iteration, the error left in the iterate is about theta/(1 - theta) times the last
 * correction; stop once that is below etol (a fraction of the time-step tolerance) times the step's increment,
 * in the displacements and in the indenter's position. theta is the residual's contraction (for Newton with
 * exact solves, the corrections contract as the residuals do). The residual must also be below
 * sqrt(rtol) of the force scale, so that a slow first iterate cannot stop the step. */
static PetscErrorCode error_small(Semismooth *in, PetscReal merit, PetscReal merit_prev, PetscBool *small) {
  PetscReal dU, theta = merit / merit_prev, eta = theta / (1 - theta);
  PetscFunctionBeginUser;
  *small = PETSC_FALSE;
  if (!in->newton_estimate || in->etol <= 0 || !(theta < 0.5) || merit > PetscSqrtReal(in->rtol)) PetscFunctionReturn(0);
  PetscCall(VecWAXPY(in->Uk, -1.0, in->U0, in->U)); /* the step's increment (Uk is free between iterations) */
  PetscCall(VecNorm(in->Uk, NORM_INFINITY, &dU));
  *small = eta * in->du_norm <= in->etol * dU && eta * PetscAbsReal(in->dur_last) <= in->etol * PetscAbsReal(in->ur - in->ur0) ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* Force control with nothing in contact: no state carries the load until the indenter touches, so it is moved
 * down to the first touch of the multipliers' gaps (their mean gaps on P2) instead of by the indenter-row shift's
 * steps of R_r / k_n. Needed on P2: there the tip vertex's mean gap is positive while the tip touches, and
 * the shift's steps took more than the iteration limit to close it. No move when a gap is already closed (P1 with
 * the tip on the surface). */
static PetscErrorCode approach(Semismooth *in, PetscReal *merit) {
  PetscReal all;
  PetscFunctionBeginUser;
  PetscCall(contact_first_touch(&in->ct, PETSC_FALSE, &all)); /* the multipliers' gaps */
  if (all > 0 && all < PETSC_MAX_REAL) {
    in->ur += all;
    PetscCall(semismooth_evaluate(in, merit));
  }
  PetscFunctionReturn(0);
}

/* The predictor's scale of the last converged increment: the ratio of the step lengths (h / h_prev) or, under force
 * control, the ratio of this step's load increment to the last one's when that is the smaller. This step's is exact
 * (its target less the committed one); the last one's is the multipliers' (eq. 19), so that a restart needs nothing
 * its checkpoint lacks. In a hold (this step's increment zero), and after a last increment below 1e-8 of the force
 * scale, the step ratio. The smaller of the two because a rising indentation stiffens as its contact grows (depth
 * about proportional to sqrt(P) for a pointed tip): where the steps are steady the load ratio (e^{k h} of an exp
 * load) overshoots, and after a load that jumps (exp's P0, a table) the step ratio does, by several times. Measured
 * on the kerogen sector's fixed steps (bench/contact_solver_bench.py's ladder with its hold in 10 s steps, one rank):
 * 82 -> 77 Newton iterations at 5.9 k unknowns, 93 -> 89 at 24 k. Exact for a linear response under shrinking load
 * increments (test_contact_2d). Never negative: a load that turns within a stage starts from the committed state. */
static PetscErrorCode predictor_ratio(Semismooth *in, PetscReal h, PetscReal *r) {
  PetscReal dP, unused[2], step = in->target - in->committed;
  PetscFunctionBeginUser;
  *r = h / in->dt_prev;
  if (in->depth_control || step == 0) PetscFunctionReturn(0);
  PetscCall(contact_summary(&in->ct, in->ratelam, &dP, &unused[0], &unused[1]));
  if (PetscAbsReal(dP) > 1e-8 * in->fref) *r = PetscMin(*r, PetscMax(0, step / dP));
  PetscFunctionReturn(0);
}

/* Predict: the step's first iterate, the last converged state or its extrapolation along the last converged
 * increments, scaled by predictor_ratio (the multipliers kept non-negative). */
static PetscErrorCode predict(Semismooth *in, PetscReal h) {
  PetscFunctionBeginUser;
  PetscCall(VecCopy(in->U0, in->U));
  PetscCall(VecCopy(in->lam0, in->lam));
  in->ur = in->ur0;
  if (in->predictor && in->have_rate && in->dt_prev > 0) {
    PetscReal    r;
    PetscScalar *la;
    PetscCall(predictor_ratio(in, h, &r));
    PetscCall(VecAXPY(in->U, r, in->rateU));
    PetscCall(VecAXPY(in->lam, r, in->ratelam));
    in->ur += r * in->rateur;
    PetscCall(VecGetArray(in->lam, &la));
    for (PetscInt i = 0; i < in->ct.n; i++) la[i] = PetscMax(0, PetscRealPart(la[i]));
    PetscCall(VecRestoreArray(in->lam, &la));
  }
  PetscFunctionReturn(0);
}

/* Update the active set (eq. 14) at the iterate, and record its signature in the step's history. Released (force
 * control at zero load): no contact pressure anywhere. */
static PetscErrorCode update_active_set(Semismooth *in, PetscInt *changes) {
  PetscFunctionBeginUser;
  if (semismooth_released(in)) {
    PetscInt loc = 0;
    for (PetscInt i = 0; i < in->ct.n; i++) loc += in->ct.active[i], in->ct.active[i] = PETSC_FALSE;
    PetscCall(MPIU_Allreduce(&loc, changes, 1, MPIU_INT, MPI_SUM, PetscObjectComm((PetscObject)in->U)));
    in->nactive = 0;
  } else PetscCall(contact_update_active(&in->ct, in->lam, in->fref / in->ct.weight_sum, changes, &in->nactive));
  in->changes += *changes;
  PetscFunctionReturn(0);
}

/* Whether the set of iteration k (just recorded) was met two or more iterations before: cycling. */
static PetscBool met_again(const ActiveSetHistory *h) {
  for (PetscInt j = 0; j + 2 < h->n; j++)
    if (h->sig[j] == h->sig[h->n - 1]) return PETSC_TRUE;
  return PETSC_FALSE;
}

/* Stalled: the active set unchanged over the last stall_window iterations (each signature that of the iteration
 * before) and the merit not below a tenth of its value stall_window iterations before. Newton on a settled set contracts the merit at every step (the line search
 * sees to it), so such a step is mostly one the iteration limit ends anyway. Measured with a window of 8
 * (docs/performance.md, "2D contact solve"): the 11 steps of loading_rate_a1 that failed at 30 iterations stop at
 * iteration 8 to 11; of the converged steps of loading_rate_a1 and bedding_theta45 (at most 12 iterations) one
 * is given up, and redone shorter. The stepper cuts a stalled step back as it does at the limit; the attempt after
 * it runs to the limit (stall_retry), so that a step which needs more than the window's iterations is not cut back
 * for good: the 3D half model at tol 5e-3 needs 10 at t = 149.75 s of its load stage and, cut back at every 8th,
 * failed at dt = 2.7e-9 s (docs/contact.md, "The Newton loop"). */
static PetscBool stalled(const Semismooth *in) {
  const ActiveSetHistory *h = &in->history;
  const PetscInt          w = in->stall_window, k = h->n - 1;
  if (w <= 0 || k < w || in->stall_retry == 2) return PETSC_FALSE;
  for (PetscInt j = k - w + 1; j <= k; j++)
    if (h->sig[j] != h->sig[j - 1]) return PETSC_FALSE;
  return h->merit[k] > 0.1 * h->merit[k - w] ? PETSC_TRUE : PETSC_FALSE;
}

/* Converged: the set did not change and the residual is small (every part below rtol of the force scale), or,
 * under an error measure, the estimated remaining error is (error_small). */
static PetscErrorCode converged(Semismooth *in, PetscInt k, PetscInt changes, PetscReal merit, PetscBool *done) {
  const PetscReal f = in->rtol * in->fref;
  PetscBool       small = in->ru <= f && in->ncp <= f && PetscAbsReal(in->Rr) <= f;
  PetscFunctionBeginUser;
  if (!small && k > 0 && changes == 0) PetscCall(error_small(in, merit, in->history.merit[k - 1], &small));
  if (in->monitor)
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "    newton %2d  |R_u| %.3e  |R_r| %.3e  |ncp| %.3e  active %d (%d changes)  u_r %.10g  merit %.17g\n",
                          (int)k, (double)in->ru, (double)PetscAbsReal(in->Rr), (double)in->ncp, (int)in->nactive, (int)changes,
                          (double)in->ur, (double)merit));
  *done = small && changes == 0 ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

/* The inexact Newton forcing term (-indent_ksp_ew), GMRES' relative tolerance at this iterate of a settled set: choice 2
 * of Eisenstat & Walker (SIAM J. Sci. Comput. 17, 1996, 16-32), eta = gamma (m_k / m_{k-1})^2 with gamma = 0.9, with
 * Kelley's safeguards (Iterative Methods for Linear and Nonlinear Equations, SIAM 1995, §6.3): not below gamma
 * eta_{k-1}^2 while that exceeds 0.1 (no sudden tightening), at most eta_max = 0.1, and not below 0.5 rtol / m_k (a
 * direction more exact than -indent_rtol needs is wasted). m is the merit (eq. 15's residual relative to the load),
 * the ratio that of the last two iterates whether or not the set changed between them. Solved tight instead
 * (-indent_ksp_rtol_tight): a step's first iterate, which has no ratio, so that a response linear within the step
 * still converges in one iteration (with eta_max there, an elastic cone's 24 Newton iterations became 51); and after a
 * damped step (the line search's alpha < 1), whose small fall of the merit says nothing of the direction's accuracy:
 * read as slow progress it loosened the next solve to eta_max, which again fell by half (the Cam-Clay IX cone of
 * test_contact_solver: 20 to 27 Newton iterations per step where tight solves took 3 to 5). Never below
 * -indent_ksp_rtol_tight. */
static PetscReal forcing(Semismooth *in, PetscReal merit) {
  const PetscReal gamma = 0.9, eta_max = 0.1;
  const PetscInt  n     = in->history.n;
  PetscReal       eta   = 0;
  if (n >= 2 && in->history.merit[n - 2] > 0 && in->alpha == 1) {
    PetscReal safe = gamma * in->eta * in->eta;
    eta            = gamma * PetscSqr(merit / in->history.merit[n - 2]);
    if (safe > 0.1) eta = PetscMax(eta, safe);
    eta = PetscMin(eta_max, PetscMax(eta, 0.5 * in->rtol / merit));
  }
  return PetscMax(eta, in->sol.rtol_tight);
}

/* Solve: eq. 15 for the current set, with a stiffness shift on the indenter row when no node is in contact (force
 * control: the row would be empty); the direction into (du, dur, dlam). The linear solve may be loose only on a settled
 * set: while the error estimate stops Newton (indent_solver.h), or by the forcing term (-indent_ksp_ew); while the set
 * changes it is tight, since an inexact direction could flip a node onto another branch of a non-unique contact
 * solution (indent_solver.h). */
static PetscErrorCode solve(Semismooth *in, PetscInt changes, PetscBool shift, PetscReal *merit, PetscReal *dur, PetscBool *ok) {
  PetscBool tight = changes > 0 || !in->newton_estimate || in->etol <= 0 ? PETSC_TRUE : PETSC_FALSE;
  PetscReal eta   = in->ksp_ew && changes == 0 ? forcing(in, *merit) : 0;
  PetscFunctionBeginUser;
  if (in->ksp_ew) in->eta = eta > 0 ? eta : in->sol.rtol_tight; /* the last direction's tolerance, for the safeguard */
  PetscCall(PetscLogEventBegin(driver_event(EV_CONTACT), 0, 0, 0, 0));
  PetscCall(contact_jacobian(&in->ct, in->depth_control, shift));
  PetscCall(PetscLogEventEnd(driver_event(EV_CONTACT), 0, 0, 0, 0));
  PetscCall(contact_constraint_residual(&in->ct, in->lam, in->Rlam));
  if (in->fd_check && !shift) PetscCall(check_tangent(in, merit)); /* the shift is in the tangent only */
  PetscCall(indent_solver_solve(&in->sol, &in->ct, in->Ru, in->Rr, in->Rlam, tight, eta, in->du, dur, in->dlam, ok));
  PetscFunctionReturn(0);
}

/* Line search: while the active set settles the full semismooth step is taken (it identifies the set in finitely
 * many steps); with the set unchanged, the step is halved while the merit does not fall (Armijo, at most 5
 * halvings); a damped step (alpha = 1/2) after a cycle. The iterate moves; *merit becomes the new one. */
static PetscErrorCode line_search(Semismooth *in, PetscReal dur, PetscBool search, PetscBool damped, PetscReal *merit) {
  PetscReal urk = in->ur, alpha = damped ? 0.5 : 1.0, trial;
  PetscFunctionBeginUser;
  PetscCall(VecCopy(in->U, in->Uk));
  PetscCall(VecCopy(in->lam, in->lamk));
  for (int ls = 0;; ls++) {
    PetscCall(VecWAXPY(in->U, alpha, in->du, in->Uk));
    PetscCall(VecWAXPY(in->lam, alpha, in->dlam, in->lamk));
    in->ur = urk + alpha * dur;
    PetscCall(semismooth_evaluate(in, &trial));
    if (!search || trial <= (1 - 1e-4 * alpha) * *merit || ls == 5 || trial < in->rtol) break;
    alpha *= 0.5;
  }
  *merit = trial;
  PetscCall(VecNorm(in->du, NORM_INFINITY, &in->du_norm));
  in->du_norm *= alpha, in->dur_last = alpha * dur, in->alpha = alpha;
  PetscFunctionReturn(0);
}

/* One step by the semismooth Newton method of Box 1, in the phases of deal.II's step-42: predict, then per
 * iteration update the active set (eq. 14), test convergence, solve eq. 15 for the set, line search. A set met
 * again two iterations or more later is a cycle: the next step is damped, and after the third the stepper cuts
 * the step back. */
PetscErrorCode semismooth_step(Semismooth *in, PetscReal h, int *status, PetscInt *its_out) {
  PetscReal merit;
  PetscInt  k, changes, damp = 0;
  PetscFunctionBeginUser;
  *status = STEP_DIVERGED, in->changes = 0, in->history.n = 0, in->eta = 0;
  PetscCall(predict(in, h));
  in->stall_retry = in->stall_retry == 1 ? 2 : 0; /* the attempt after a stalled one: the stall test off */
  PetscCall(semismooth_evaluate(in, &merit));
  for (k = 0; k <= in->max_it; k++) {
    PetscBool done = PETSC_FALSE, ok, shift;
    PetscReal dur;
    PetscCall(update_active_set(in, &changes));
    if (!in->depth_control && !semismooth_released(in) && in->nactive == 0 && in->target > 0) PetscCall(approach(in, &merit));
    in->history.merit[in->history.n] = merit;
    PetscCall(active_signature(in, &in->history.sig[in->history.n++]));
    PetscCall(converged(in, k, changes, merit, &done));
    if (done) {
      *status = STEP_OK;
      break;
    }
    if (k == in->max_it) break;
    if (stalled(in)) {
      *status = STEP_STALLED, in->stall_retry = 1;
      break;
    }
    if (changes > 0 && met_again(&in->history)) {
      in->cycles++;
      if (++damp > 2) { /* damped twice and still cycling: let the stepper cut the step back */
        *status = STEP_CYCLING;
        break;
      }
    }
    shift = !in->depth_control && in->nactive == 0;
    PetscCall(solve(in, changes, shift, &merit, &dur, &ok));
    if (!ok) {
      *status = STEP_LINEAR;
      break;
    }
    PetscCall(line_search(in, dur, in->line_search && changes == 0 && !shift, damp > 0, &merit));
  }
  *its_out = k, in->its_total += k;
  PetscFunctionReturn(0);
}

/* After a converged step at zero load with nothing in contact, the indenter rests on the surface: move
 * it down to the first touch (the depth then read is the residual depth). */
PetscErrorCode semismooth_rest_on_surface(Semismooth *in) {
  PetscReal all;
  PetscFunctionBeginUser;
  PetscCall(contact_first_touch(&in->ct, PETSC_TRUE, &all)); /* P1: at the nodes; P2: at the facets' Gauss points */
  if (all < PETSC_MAX_REAL) { /* down onto the surface, or up out of it */
    in->ur += all;
    PetscCall(contact_update_gaps(&in->ct, in->U, in->ur));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode semismooth_commit(Semismooth *in, PetscReal h, PetscBool same_stage) {
  PetscFunctionBeginUser;
  PetscCall(VecWAXPY(in->rateU, -1.0, in->U0, in->U));
  PetscCall(VecWAXPY(in->ratelam, -1.0, in->lam0, in->lam));
  in->rateur    = in->ur - in->ur0;
  in->dt_prev   = h;
  in->have_rate = same_stage;
  PetscCall(VecCopy(in->U, in->U0));
  PetscCall(VecCopy(in->lam, in->lam0));
  in->ur0 = in->ur;
  PetscCall(fe_state_commit(in->p, h));
  PetscFunctionReturn(0);
}


/* K at the iterate, for the solver when it factors or preconditions (indent_solver.h). */
static PetscErrorCode assemble_tangent(void *ctx) {
  Semismooth *in = ctx;
  PetscFunctionBeginUser;
  PetscCall(fe_jacobian(NULL, in->U, in->K, in->K, in->p));
  PetscFunctionReturn(0);
}

/* The p-multigrid's coarse level for the field split on P2 (fe_pmg.h). */
static PetscErrorCode coarse_space(void *ctx, Mat *P, MatNullSpace *rbm) {
  Semismooth *in = ctx;
  PetscFunctionBeginUser;
  PetscCall(fe_p1_prolongation(fe_problem_space(in->p), P, rbm));
  PetscFunctionReturn(0);
}

/* The error indicator's contact term at a field output (fe_estimate.h's est.surface): the committed multipliers. */
static PetscErrorCode surface_term(void *ctx, FeProblem *p) {
  Semismooth *in = (Semismooth *)ctx;
  PetscFunctionBeginUser;
  PetscCall(contact_estimate(&in->ct, in->lam, p));
  PetscFunctionReturn(0);
}

/* indenter.copies > 1: the model is one of copies mirror images of the body, a cut through the indenter's axis; a whole
   body under copies > 1 would carry the load of a part (a load copies times too large): *bad 2 with the message. */
static PetscErrorCode check_copies(Contact *ct, const IndentScene *is, const char *msh, char *err, size_t errlen, int *bad) {
  PetscFunctionBeginUser;
  if (is->copies > 1) {
    PetscReal span, most = ct->dim == 2 ? 0 : 360 / is->copies;
    PetscCall(contact_azimuth_span(ct, is->shape.tip, &span));
    if (span > most + 1) {
      if (ct->dim == 2)
        snprintf(err, errlen, "%s: key 'indenter.copies': %g copies of the model make the body, so the model must be the half on one "
                 "side of the indenter's axis (x = %g), but its contact surface '%s' lies on both sides (mesh %s): a whole body has "
                 "copies 1", is->file, is->copies, is->shape.tip[0], is->contact_group, msh);
      else
        snprintf(err, errlen, "%s: key 'indenter.copies': %g copies of the model make the body, so the model must be a cut through the "
                 "indenter's axis spanning at most %g degrees about it, but its contact surface '%s' spans %.1f (mesh %s): a whole "
                 "body has copies 1", is->file, is->copies, (double)most, is->contact_group, (double)span, msh);
      *bad = 2;
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode semismooth_create(FeProblem *p, const IndentScene *is, const char *msh, Semismooth *in, char *err, size_t errlen, int *bad) {
  const FeSpace *sp = fe_problem_space(p);
  MPI_Comm comm = PetscObjectComm((PetscObject)sp->dm);
  PetscFunctionBeginUser;
  *bad = 0;
  PetscCall(PetscMemzero(in, sizeof *in));
  in->p = p;
  {
    PetscBool has;
    PetscCall(DMHasLabel(sp->dm, is->contact_group, &has));
    if (!has) {
      snprintf(err, errlen, "%s: key 'indenter.contact': '%s' is not a physical group of the mesh %s", is->file, is->contact_group, msh);
      *bad = 2;
      PetscFunctionReturn(0);
    }
  }
  PetscCall(contact_create(p, is->contact_group, &is->shape, &in->ct));
  PetscCall(check_copies(&in->ct, is, msh, err, errlen, bad));
  if (*bad) PetscFunctionReturn(0);
  p->est.surface = surface_term, p->est.surface_ctx = in;
  PetscCall(DMCreateGlobalVector(sp->dm, &in->U));
  { /* K: AIJ in the displacement layout, its pattern from the cells by COO (fe_jacobian_coo_setup below; DMCreateMatrix's
       own preallocation was a fifth of a run's set-up), with the rigid-body modes for GAMG on the displacement block */
    PetscInt     n, N;
    MatNullSpace rbm;
    PetscCall(VecGetLocalSize(in->U, &n));
    PetscCall(VecGetSize(in->U, &N));
    PetscCall(MatCreate(comm, &in->K));
    PetscCall(MatSetSizes(in->K, n, n, N, N));
    PetscCall(MatSetType(in->K, MATAIJ));
    PetscCall(DMPlexCreateRigidBody(sp->dm, 0, &rbm));
    PetscCall(MatSetNearNullSpace(in->K, rbm));
    PetscCall(MatNullSpaceDestroy(&rbm));
  }
  Vec *uv[] = {&in->Ru, &in->du, &in->Uk, &in->U0, &in->rateU, NULL};
  for (int k = 0; uv[k]; k++) PetscCall(VecDuplicate(in->U, uv[k]));
  PetscCall(VecCreateMPI(comm, in->ct.n, in->ct.N, &in->lam));
  Vec *lv[] = {&in->Rlam, &in->dlam, &in->lamk, &in->lam0, &in->ratelam, NULL};
  for (int k = 0; lv[k]; k++) PetscCall(VecDuplicate(in->lam, lv[k]));
  Vec *all[] = {&in->U, &in->Ru, &in->du, &in->Uk, &in->U0, &in->rateU, &in->lam, &in->Rlam, &in->dlam, &in->lamk, &in->lam0, &in->ratelam, NULL};
  for (int k = 0; all[k]; k++) PetscCall(VecZeroEntries(*all[k]));
  IndentOptions o; /* -indent_*: contact_options.c */
  PetscCall(indent_options(comm, &o));
  in->rtol = o.rtol, in->max_it = o.max_it, in->predictor = o.predictor, in->monitor = o.monitor, in->line_search = o.line_search;
  in->newton_estimate = o.newton_estimate, in->fd_check = o.check_tangent, in->tangent_part = o.tangent_part, in->ksp_ew = o.ksp_ew;
  in->stall_window = o.stall_window, in->stall_retry = 0;
  PetscCall(PetscMalloc2(in->max_it + 1, &in->history.sig, in->max_it + 1, &in->history.merit));
  PetscCall(fe_jacobian_coo_setup(p, in->K));
  PetscCall(fe_tangent_operator(p, in->K, &in->Kmf));
  PetscCall(indent_solver_create(&in->ct, in->K, in->Kmf, assemble_tangent, sp->order == 2 ? coarse_space : NULL, in, &o, &in->sol));
  /* The initial state: the UMAT initialises its state on a zero increment; its elastic tangent sets the
     indenter row's shift (one contact node's stiffness) and the complementarity constant. */
  fe_problem_set_step(p, 0, 0), fe_problem_set_umat_control(p, umat_control(UMAT_CONTROL_OFF, 0));
  PetscCall(fe_residual(NULL, in->U, in->Ru, p));
  PetscCall(fe_problem_commit(p));
  PetscCall(fe_jacobian(NULL, in->U, in->K, in->K, p));
  PetscCall(contact_node_stiffness(&in->ct, in->K));
  {
    PetscReal E = fe_problem_stiffness_scale(p), Eall, ell = 0, lall;
    for (PetscInt i = 0; i < in->ct.n; i++) { /* a contact-node spacing from the weights */
      PetscReal w = in->ct.w[i], r = in->ct.X[i * in->ct.dim];
      ell = PetscMax(ell, sp->dim == 3 ? PetscSqrtReal(w) : sp->kin == KIN_AXISYMMETRIC ? (r > 0 ? w / (2 * PETSC_PI * r) : 0) : w / sp->thickness);
    }
    PetscCall(MPIU_Allreduce(&E, &Eall, 1, MPIU_REAL, MPI_MAX, comm));
    PetscCall(MPIU_Allreduce(&ell, &lall, 1, MPIU_REAL, MPI_MAX, comm));
    in->ct.c = is->c > 0 ? is->c : Eall / lall;
  }
  PetscCall(contact_update_gaps(&in->ct, in->U, in->ur));
  { /* the indenter starts on or above the surface: a node already inside it is a scene error */
    PetscReal gmin = PETSC_MAX_REAL, all, scale = 0, sall;
    for (PetscInt i = 0; i < in->ct.n; i++) gmin = PetscMin(gmin, in->ct.g[i]);
    for (PetscInt i = 0; i < in->ct.n * in->ct.dim; i++) scale = PetscMax(scale, PetscAbsReal(in->ct.X[i]));
    PetscCall(MPIU_Allreduce(&gmin, &all, 1, MPIU_REAL, MPI_MIN, comm));
    PetscCall(MPIU_Allreduce(&scale, &sall, 1, MPIU_REAL, MPI_MAX, comm));
    if (all < -1e-9 * PetscMax(sall, 1e-300)) {
      snprintf(err, errlen, "%s: key 'indenter.tip': the indenter starts %g below the surface of the contact group '%s' (a gap of %g): "
                            "place its tip on or above the surface", is->file, (double)-all, is->contact_group, (double)all);
      *bad = 2;
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode semismooth_destroy(Semismooth *in) {
  PetscFunctionBeginUser;
  PetscCall(indent_solver_destroy(&in->sol));
  if (in->p && in->p->est.surface_ctx == in) in->p->est.surface = NULL, in->p->est.surface_ctx = NULL;
  PetscCall(contact_destroy(&in->ct));
  Vec *all[] = {&in->U, &in->Ru, &in->du, &in->Uk, &in->U0, &in->rateU, &in->lam, &in->Rlam, &in->dlam, &in->lamk, &in->lam0, &in->ratelam, NULL};
  for (int k = 0; all[k]; k++) PetscCall(VecDestroy(all[k]));
  PetscCall(MatDestroy(&in->K));
  PetscCall(MatDestroy(&in->Kmf));
  PetscCall(PetscFree2(in->history.sig, in->history.merit));
  PetscFunctionReturn(0);
}

void semismooth_set_stage(Semismooth *in, PetscBool depth_control, PetscBool new_stage) {
  in->depth_control = depth_control;
  if (new_stage) in->have_rate = PETSC_FALSE; /* the last stage's increment predicts nothing in this one */
}

/* The force scale of the residual test: the largest load so far or this target (force control), or the depth row's
   force k_n |target| (depth control; contact.h). */
void semismooth_set_target(Semismooth *in, PetscReal target, PetscReal committed, PetscReal load_max, PetscReal etol) {
  in->target = target, in->committed = committed, in->etol = etol;
  in->fref   = PetscMax(PetscMax(load_max, in->depth_control ? in->ct.kn * PetscAbsReal(target) : target), 1e-300);
}

int semismooth_state_io(Semismooth *in, BinFile *f, int write) {
  PetscReal r[3] = {in->ur0, in->rateur, in->dt_prev};
  PetscInt  n[4] = {in->have_rate, in->its_total, in->cycles, in->nactive};
  if (write) binfile_write(f, r, sizeof r[0], 3), binfile_write(f, n, sizeof n[0], 4);
  else {
    binfile_read(f, r, sizeof r[0], 3), binfile_read(f, n, sizeof n[0], 4);
    in->ur0 = in->ur = r[0], in->rateur = r[1], in->dt_prev = r[2];
    in->have_rate = n[0] ? PETSC_TRUE : PETSC_FALSE, in->its_total = n[1], in->cycles = n[2], in->nactive = n[3];
  }
  return !f->ok;
}
