/* The semismooth Newton method of Box 1 (Yin, Liu & Borja 2021) for one step of an indentation: the
 * finite-element problem plus one rigid indenter, the active set from the complementarity function inside
 * the Newton loop (eqs. 13-14), the linearised system of eq. 15 as a MatNest over (u, u_r, lambda) solved
 * directly or by a Schur-complement field split, a line search on the residual norm, a step accepted on a
 * small residual and an unchanged active set. The stepping (stages, step lengths, events) is the stage
 * runner's (stepping/indent_stepper). */
#ifndef SEMISMOOTH_H
#define SEMISMOOTH_H

#include "../fe/fe_problem.h"
#include "../io/binfile.h"
#include "contact.h"
#include "indent_scene.h"
#include "indent_solver.h"

/* A step's iterations: their active sets, by signature (a hash over all ranks), to notice one met again (a cycle),
 * and the merit at each iterate, for the contraction (error_small) and to notice a stall. */
typedef struct {
  unsigned long long *sig;   /* max_it + 1 */
  PetscReal          *merit; /* max_it + 1 */
  PetscInt            n;
} ActiveSetHistory;

/* Everything the Newton loop works on: the problem, the contact, the unknowns (u, u_r, lambda) with their
 * committed values and last converged increments (the predictor), residual parts and settings. */
typedef struct {
  FeProblem   *p;
  Contact      ct;
  IndentSolver sol;
  Mat          K, Kmf;                           /* the FE tangent, assembled and matrix-free */
  Vec          U, lam, Ru, Rlam, du, dlam;       /* iterate, residual parts, Newton direction */
  Vec          Uk, lamk;                         /* the iterate before a line search */
  Vec          U0, lam0, rateU, ratelam;         /* committed; last converged increment */
  PetscReal    ur, ur0, rateur, dt_prev;
  PetscBool    have_rate, predictor, monitor, line_search, fd_check, newton_estimate, ksp_ew;
  PetscReal    eta;                              /* the last forcing term (-indent_ksp_ew; 0: none yet this step) */
  PetscReal    rtol, fref;
  PetscInt     max_it, tangent_part;              /* tangent_part: -indent_check_tangent_part (contact_options.h) */
  PetscInt     stall_window;                      /* -indent_stall_window (stalled in semismooth.c); 0: off */
  PetscInt     stall_retry;                       /* 1: the last attempt stalled; 2: this one, its retry, runs to max_it */
  /* the step being solved */
  PetscBool    depth_control;
  PetscReal    target;                           /* load or depth at the step's end */
  PetscReal    committed;                        /* the load at the step's start (force control: the last target) */
  PetscReal    etol;                             /* > 0: also stop on the estimated remaining error (see
                                                    semismooth_step); 0: on the residual only */
  PetscReal    Rr, ncp, ru;                      /* residual parts at the last evaluation */
  PetscReal    du_norm, dur_last, alpha;         /* the last correction: |alpha du|_inf, alpha dur, and its alpha */
  PetscInt     nactive, changes;                 /* active nodes; changes over the step's iterations */
  PetscInt     its_total, cycles;
  ActiveSetHistory history;
  char             why[640]; /* a failed step's reason, with its residual (semismooth_failure) */
} Semismooth;

enum { STEP_OK = 0, STEP_DIVERGED, STEP_CYCLING, STEP_LINEAR, STEP_STALLED };
/* Why the last step failed (status of semismooth_step, not STEP_OK), with the residual Newton reached. */
const char *semismooth_failure(Semismooth *in, int status);

/* Contact nodes, vectors, the eq. 15 solver and the options (-indent_*), the initial state (the UMAT's
 * zero increment), the complementarity constant and the indenter-row shift. */
PetscErrorCode semismooth_create(FeProblem *p, const IndentScene *is, const char *msh, Semismooth *in, char *err, size_t errlen, int *bad);
PetscErrorCode semismooth_destroy(Semismooth *in);
/* Force control at zero load: no contact pressure anywhere, and the indenter rests on the surface. */
PetscBool semismooth_released(const Semismooth *in);
/* Residual at the iterate; merit: its norm relative to the force scale. */
PetscErrorCode semismooth_evaluate(Semismooth *in, PetscReal *merit);
/* One step of length h to in->target (load or depth): status STEP_OK or why not; its: Newton iterations. */
PetscErrorCode semismooth_step(Semismooth *in, PetscReal h, int *status, PetscInt *its_out);
/* After a converged step at zero load with nothing in contact: the indenter down onto the surface. */
PetscErrorCode semismooth_rest_on_surface(Semismooth *in);
/* A stage's control (force or depth); new_stage: the last increment no longer predicts the next step. */
void semismooth_set_stage(Semismooth *in, PetscBool depth_control, PetscBool new_stage);
/* The next step's target (load or depth at its end), the committed load (the last step's target under force control),
   the largest load so far (the residual test's force scale) and Newton's error tolerance (etol, see semismooth_step). */
void semismooth_set_target(Semismooth *in, PetscReal target, PetscReal committed, PetscReal load_max, PetscReal etol);
/* The state a restart needs that every rank holds alike (the depth, its last increment, the counters, the number
   of active nodes): written or read (write 0) in one order. Returns nonzero when f failed. */
int semismooth_state_io(Semismooth *in, BinFile *f, int write);
/* Commit the converged step; same_stage: its increments predict the next step. */
PetscErrorCode semismooth_commit(Semismooth *in, PetscReal h, PetscBool same_stage);

#endif
