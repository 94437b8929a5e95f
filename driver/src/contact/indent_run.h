/* The time stepper of an indentation scene: the finite-element problem plus one rigid indenter, solved at
 * each step by the semismooth Newton method of Box 1 (Yin, Liu & Borja 2021): the active set from the
 * complementarity function inside the Newton loop, the linearised system of eq. 15 as a MatNest over
 * (u, u_r, lambda) solved directly (converted, MUMPS) or by a Schur-complement field split, a line
 * search on the residual norm, a step accepted on a small residual and an unchanged active set. */
#ifndef INDENT_RUN_H
#define INDENT_RUN_H

#include "../fe/fe_problem.h"
#include "../fe/fe_scene.h"
#include "indent_scene.h"

/* Run the stages of sc with the indenter of is on the set-up problem p. Returns 0, or 1 with err. */
int indent_run(FeScene *sc, IndentScene *is, FeProblem *p, char *err, size_t errlen);

#endif
