#include "step_control.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

double step_control_planned(const StepControl *sc, double duration, int k) {
  if (sc->adaptive) return sc->first;
  double first = sc->ratio == 1 ? duration / sc->count : duration * (sc->ratio - 1) / (pow(sc->ratio, sc->count) - 1);
  return first * pow(sc->ratio, k);
}

/* A relative measure is first order in dt (the estimate is O(dt^2), the increment O(dt)): the elementary
 * controller scales dt with 1/ratio. With the previous accepted step's ratio too, a PI controller (Gustafsson,
 * ACM TOMS 17, 1991, 533-554; Soderlind, Numer. Algorithms 31, 2002, 281-310): dt' = dt S ratio^-alpha
 * ratio_prev^beta, whose proportional part (beta) damps the cycle the elementary controller falls into when the
 * estimate lags the step (grow, grow, reject). worst_point follows the UMAT's PNEWDT, which already holds its own
 * safety factor. */
double step_control_next(const StepControl *sc, const StepGains *g, double dt, double pnewdt, double ratio, double ratio_prev) {
  double f = sc->growth;
  if (sc->measure == MEASURE_WORST_POINT || ratio < 0) f = fmin(f, pnewdt);
  else {
    double r = fmax(ratio, 1e-300), c = ratio_prev > 0 ? STEP_SAFETY * pow(r, -g->alpha) * pow(ratio_prev, g->beta) : STEP_SAFETY / r;
    f = fmin(fmin(f, pnewdt), fmax(c, 0.2));
  }
  return fmin(fmax(dt * f, sc->min), sc->max);
}

double step_control_cut(const StepControl *sc, double dt, int diverged, double pnewdt, double ratio) {
  if (diverged) return dt * STEP_CUT_DIVERGED;
  if (pnewdt < 1) return dt * fmax(fmin(pnewdt, 0.5), 0.1);
  return fmax(dt * fmax(fmin(STEP_SAFETY / ratio, 0.5), 0.1), sc->min);
}

