/* The finite-element problem: a DMPlex mesh with a vector Lagrange field (P1 or P2 on simplices), the
 * UMAT at every quadrature point with its state (committed at converged steps, trial while iterating),
 * essential boundary conditions as section constraints, pressure loads, and the hand-written element
 * loop that assembles the residual and the consistent Jacobian (B^T DDSDDE B). */
#ifndef FE_PROBLEM_H
#define FE_PROBLEM_H

#include <petscdmplex.h>
#include <petscfe.h>
#include <petscsnes.h>

#include "../material/material_point.h"
#include "fe_constraint.h"

/* The state of a quadrature point: stress (6), total strain (6), then the UMAT's STATEV. */
enum { ST_STRESS = 0, ST_STRAN = 6, ST_STATEV = 12 };
/* The index of quadrature point q of local cell c among the points of this rank. */
#define SV(p, c, q) (((c) - (p)->space.cStart) * (p)->space.nq + (q))

#define FE_MAX_GROUPS 24 /* loads: pressures on groups, and traction components 'GROUP.x' etc. */

/* 3D (NTENS 6), plane strain (NTENS 4: 11 22 33 12, eps_33 = 0, per unit... thickness) or
 * axisymmetric (NTENS 4: rr zz thetatheta rz with x1 = r, x2 = z, as Abaqus; eps_33 = u_r / r). */
typedef enum { KIN_3D, KIN_PLANE_STRAIN, KIN_AXISYMMETRIC } Kinematics;

/* The space: the mesh, the vector field, quadrature and the geometry at the quadrature points; set up once by
 * fe_problem_setup, then read only (contact/ reads it through fe_problem_space). */
typedef struct {
  DM              dm;
  Kinematics      kin;
  PetscReal       thickness;         /* plane strain: forces and volumes per this thickness */
  PetscFE         fe;
  PetscQuadrature quad;
  PetscTabulation tab;
  PetscInt        dim, order, nq, nb, ns; /* nb: basis functions of the vector field on a cell, ns = nb / dim scalar ones */
  const PetscReal *qweights;
  PetscInt        cStart, cEnd;
  PetscInt        npoint;          /* quadrature points on this rank */
  PetscInt       *cell_dofs;       /* per cell: the local-vector index of each closure dof (nb) */
  PetscInt       *cell_rows;       /* per cell: global matrix index of each closure dof, < 0 if constrained */
  PetscReal      *grad, *shape_r;  /* per quadrature point: the scalar basis' physical gradients (ns x dim) and, in
                                      axisymmetry, its values over the radius (ns), for fe_kernel.h (fixed: small
                                      strain, and the geometry is computed once) */
  PetscReal      *wdetJ, *radius;  /* per quadrature point: weight x detJ (x thickness or 2 pi r), radius x1 */
  FeConstraint    con;             /* fixed components and mirror planes (nodal frames) */
} FeSpace;

/* The scene's weight of a point at radius r (its first coordinate) in an integral over the model: 2 pi r
   (axisymmetric), the thickness (plane strain), 1 (3D). */
static inline PetscReal fe_space_weight(const FeSpace *sp, PetscReal r) {
  return sp->kin == KIN_AXISYMMETRIC ? 2 * PETSC_PI * r : sp->kin == KIN_PLANE_STRAIN ? sp->thickness : 1;
}

/* The material at the quadrature points: its PROPS, phi per cell, the committed and trial states, the tangents of
 * the last residual, the last step's viscoplastic increments (fe_state.h). */
typedef struct {
  UmatMaterial    mat;
  PetscReal      *phi;          /* hard-frame fraction per local cell (PROPS(1) per cell) */
  PetscInt        nsv;          /* doubles per point: stress(6), strain(6), statev */
  PetscReal      *state, *trial, *ddsdde;
  PetscInt        ddsdde_valid; /* the tangent cache belongs to the last residual's U ... */
  Vec             ddsdde_u;     /* ... which is this one (fe_problem_evaluated_at) */
  PetscReal      *devp_prev;    /* per point: the viscoplastic strain increment of the last step */
  PetscBool       have_devp;
} FeQuadState;

/* The loads: unit-pressure force vectors per group, the pressures at the step's end (fe_problem_set_pressures),
 * and the external force from them. */
typedef struct {
  PetscInt        npressure;
  char            pressure_group[FE_MAX_GROUPS][64];
  Vec             unit_force[FE_MAX_GROUPS];
  PetscReal       pressure[FE_MAX_GROUPS];
  Vec             fext;
} FeLoads;

/* What the evaluations report (read by stepping/ through fe_problem_diag). */
typedef struct {
  PetscReal          min_pnewdt;        /* smallest PNEWDT of the last residual evaluation (all ranks) */
  PetscReal          reaction_local[3]; /* the supports' force from this rank's cells at the last residual */
  PetscReal          reaction[3];       /* ... summed over the ranks by fe_problem_reactions */
  PetscInt           umat_calls, tangent_recomputes;
  double             assembly_seconds;
  MaterialFailedCall failed;            /* the first UMAT call of the last residual that asked for a shorter step */
} FeDiag;

/* The error indicator per local cell (fe_estimate.h): of the last field output, and its largest over the outputs. */
typedef struct FeProblem FeProblem;
typedef struct {
  PetscReal *eta, *eta_max;
  PetscReal *surf;     /* per local cell: a boundary's share of eta^2 at this output (fe_estimate_add_surface) */
  PetscInt   nupdates; /* report times folded into eta_max */
  DM         dmv;      /* the mesh with 7 values per vertex (a stress and a weight), for the recovery */
  /* a boundary term's source (the contact surface's, contact_mortar.h), called at each output before the fields'
     recovery; NULL: none */
  PetscErrorCode (*surface)(void *ctx, FeProblem *p);
  void *surface_ctx;
} FeEstimate;

struct FeProblem {
  FeSpace     space;
  FeQuadState pts;
  FeLoads     loads;
  FeDiag      diag;
  FeEstimate  est;
  /* the evaluation: the step being solved and the UMAT's step control (fe_problem_set_step, _set_umat_control) */
  PetscReal   time, dt;     /* end of the step being solved, its length */
  UmatControl umat;         /* the UMAT's own step control for this evaluation (umat_call.h) */
  /* the Jacobian's COO assembly (fe_jacobian_coo_setup, fe_jacobian_coo_release) */
  Mat          coo_mat;     /* the Jacobian assembled by COO, not owned */
  PetscScalar *coo_v;       /* its element matrices, cell by cell */
};

/* Mesh from a gmsh .msh file (physical groups become labels of the same name), distributed. */
PetscErrorCode fe_mesh_create(MPI_Comm comm, const char *msh, PetscInt dim, DM *dm);
/* Field, boundary conditions, quadrature, state. fixed: essential conditions (zero values): fixed components
 * and mirror planes (fe_constraint.h). */
PetscErrorCode fe_problem_setup(FeProblem *p, DM dm, Kinematics kin, PetscReal thickness, PetscInt order,
                                const UmatMaterial *mat, const FeFixed *fixed,
                                PetscInt nfixed, const char pressure_groups[][64], PetscInt npressure);
PetscErrorCode fe_problem_destroy(FeProblem *p);
/* Read access for the other folders (contact/, stepping/, app/): they change the problem only through the
 * functions below. */
static inline const FeSpace      *fe_problem_space(const FeProblem *p) { return &p->space; }
static inline DM                  fe_problem_dm(const FeProblem *p) { return p->space.dm; }
static inline const FeDiag       *fe_problem_diag(const FeProblem *p) { return &p->diag; }
static inline const UmatMaterial *fe_problem_material(const FeProblem *p) { return &p->pts.mat; }
/* Doubles of state per quadrature point (stress, strain, STATEV). */
static inline PetscInt  fe_problem_point_size(const FeProblem *p) { return p->pts.nsv; }
static inline Vec       fe_problem_unit_force(const FeProblem *p, PetscInt g) { return p->loads.unit_force[g]; }
static inline PetscReal fe_problem_pressure(const FeProblem *p, PetscInt g) { return p->loads.pressure[g]; }
/* Whether the last residual was evaluated at U, so that the tangents it cached are U's. */
PetscErrorCode fe_problem_evaluated_at(FeProblem *p, Vec U, PetscBool *same);
/* The UMAT's own step control for the following evaluations (off while Newton iterates). */
static inline void fe_problem_set_umat_control(FeProblem *p, UmatControl c) { p->umat = c; }
/* The step the following evaluations solve: its end time and length (0: the initial state). */
static inline void fe_problem_set_step(FeProblem *p, PetscReal time, PetscReal dt) { p->time = time, p->dt = dt; }
/* The boundary pressures of the pressure groups 0..n-1 at the step's end, and the load vector from them. */
PetscErrorCode fe_problem_set_pressures(FeProblem *p, PetscInt n, const PetscReal pressure[]);
/* The largest D_1111 of this rank's points' last tangents (DDSDDE), a stiffness scale of the material. */
PetscReal fe_problem_stiffness_scale(const FeProblem *p);
/* The first UMAT call of the last residual that asked for a shorter step (for a replay scene), NULL if none. */
static inline const MaterialFailedCall *fe_problem_failed_call(const FeProblem *p) { return p->diag.failed.have ? &p->diag.failed : NULL; }
/* The COO Jacobian set up by fe_jacobian_coo_setup is being destroyed: assemble by MatSetValues again. */
static inline void fe_jacobian_coo_release(FeProblem *p) { p->coo_mat = NULL; }
/* Initial state: both frames at stress0 at every point (the UMAT's uninitialised-state rule). */
PetscErrorCode fe_problem_set_initial_stress(FeProblem *p, const PetscReal stress0[6]);
/* phi per cell: seeded normal (mean, std) kept within [lo, hi], a function of the cell centroids and the
 * seed only, so the same on any number of ranks; correlation > 0: spatially correlated over that length.
 * std = 0: uniform mean. */
PetscErrorCode fe_problem_set_phi(FeProblem *p, PetscReal mean, PetscReal std, PetscReal lo, PetscReal hi,
                                  PetscInt seed, PetscReal correlation);
/* SNES callbacks. */
PetscErrorCode fe_residual(SNES snes, Vec U, Vec F, void *ctx);
PetscErrorCode fe_jacobian(SNES snes, Vec U, Mat J, Mat P, void *ctx);
/* Assemble the Jacobian J by COO from now on (the other matrices by MatSetValues). */
PetscErrorCode fe_jacobian_coo_setup(FeProblem *p, Mat J);
/* The Jacobian as a matrix-free operator (a MatShell of the layout of 'like'): the tangents of the last residual
 * applied cell by cell, the same operator as fe_jacobian's matrix to roundoff, at a tenth of an assembly's cost. */
PetscErrorCode fe_tangent_operator(FeProblem *p, Mat like, Mat *A);
/* Consistent nodal forces (a global vector) of a unit pressure on the boundary faces of a group, or of a
 * unit traction along an axis for load 'GROUP.x' ('.y', '.z'), with the kinematics' weight (thickness,
 * 2 pi r): the traction along an axis gives each node int N_i dGamma. */
PetscErrorCode fe_problem_unit_load(FeProblem *p, const char *load, Vec *f);
/* Update the external force for the current pressures. */
PetscErrorCode fe_problem_update_loads(FeProblem *p);
/* The supports' reaction of the last residual, summed over the ranks (collective). */
PetscErrorCode fe_problem_reactions(FeProblem *p);
/* Commit the trial state (call after a converged step, with the residual evaluated at the solution). */
PetscErrorCode fe_problem_commit(FeProblem *p);

/* Scalars over the quadrature points of all ranks, for the history. */
typedef struct {
  PetscReal volume, strain_mean[6], stress_mean[6];
  PetscReal strain_spread;            /* max over points and components of |eps - volume mean| */
  PetscReal evp_rate;                 /* volume-mean |d eps_vp| / dt of the last step */
  PetscReal frame_evp[2][6];          /* axial vp strain of each frame over the points: mean, min, q1,
                                         median, q3, max (Yin et al. 2021 Fig. 18) */
} FeStats;
PetscErrorCode fe_problem_stats(FeProblem *p, PetscInt axis, FeStats *s, PetscBool trial, PetscBool quantiles);

#endif
