#include "point_run.h"

#include "camclay9.h"

#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#define MAX_NEWTON 30
#define MAX_CUTBACKS 40


static double seconds_since(const struct timespec *t0) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (double)(t.tv_sec - t0->tv_sec) + 1e-9 * (double)(t.tv_nsec - t0->tv_nsec);
}

static double statev_or_zero(const UmatMaterial *mat, const UmatCall *c, int slot) {
  return slot < mat->nstatv ? c->statev[slot] : 0.0;
}

int make_directories(const char *path) {
  char buf[1024];
  snprintf(buf, sizeof buf, "%s", path);
  for (char *p = buf + 1; *p; p++)
    if (*p == '/') {
      *p = '\0';
      if (mkdir(buf, 0775) && errno != EEXIST) return 1;
      *p = '/';
    }
  return mkdir(buf, 0775) && errno != EEXIST;
}

/* Solve J x = r in place (n <= 6), partial pivoting. Returns 1 if singular. */
static int solve_small(int n, double J[6][6], double r[6]) {
  for (int k = 0; k < n; k++) {
    int p = k;
    for (int i = k + 1; i < n; i++)
      if (fabs(J[i][k]) > fabs(J[p][k])) p = i;
    if (J[p][k] == 0) return 1;
    if (p != k) {
      for (int j = 0; j < n; j++) {
        double t = J[k][j];
        J[k][j] = J[p][j], J[p][j] = t;
      }
      double t = r[k];
      r[k] = r[p], r[p] = t;
    }
    for (int i = k + 1; i < n; i++) {
      double m = J[i][k] / J[k][k];
      for (int j = k; j < n; j++) J[i][j] -= m * J[k][j];
      r[i] -= m * r[k];
    }
  }
  for (int i = n - 1; i >= 0; i--) {
    for (int j = i + 1; j < n; j++) r[i] -= J[i][j] * r[j];
    r[i] /= J[i][i];
  }
  return 0;
}

static double interp(const Segment *sg, int col, double t) {
  const double *tt = sg->table_time;
  int           n  = sg->table_rows;
  if (t <= tt[0]) return sg->table[col];
  if (t >= tt[n - 1]) return sg->table[(n - 1) * sg->table_cols + col];
  int lo = 0, hi = n - 1;
  while (hi - lo > 1) {
    int mid = (lo + hi) / 2;
    if (tt[mid] <= t) lo = mid;
    else hi = mid;
  }
  double w = (t - tt[lo]) / (tt[hi] - tt[lo]);
  return (1 - w) * sg->table[lo * sg->table_cols + col] + w * sg->table[hi * sg->table_cols + col];
}

/* The target of equation i at segment time t (lambda: fraction of the ramp done). */
static double target_of(const Segment *sg, int i, const double start[6], double lambda, double t) {
  const Equation *eq = &sg->eq[i];
  if (eq->table_column >= 0) return eq->table_factor * interp(sg, eq->table_column, t);
  if (eq->kind == EQ_LINEAR) return start[i];
  return start[i] + lambda * (eq->target - start[i]);
}

/* Residual of equation i for strain eps and stress sig. */
static double residual_of(const Equation *eq, int i, int n, const double eps[6], const double sig[6], double target) {
  switch (eq->kind) {
  case EQ_STRESS: return sig[i] - target;
  case EQ_STRAIN: return eps[i] - target;
  default: {
    double s = -target;
    for (int j = 0; j < n; j++) s += eq->a[j] * eps[j] + eq->b[j] * sig[j];
    return s;
  }
  }
}

typedef struct {
  int    newton;
  double control_error;
  double pnewdt;
  UmatCall failed_in, failed_out; /* the last call that asked for a smaller step */
  int    umat_failed;
} StepResult;

/* One step of length dt from the committed state 'cur' to equation targets 'target': Newton on the
 * strain increment. On success 'next' holds the converged call. */
static int mixed_step(const UmatMaterial *mat, const Segment *sg, const UmatCall *cur, const double target[6],
                      double dt, double deps[6], UmatCall *next, StepResult *res) {
  int n = mat->ntens;
  memset(res, 0, sizeof *res);
  res->pnewdt = DBL_MAX;
  /* Strain-controlled components are known exactly. */
  for (int i = 0; i < n; i++)
    if (sg->eq[i].kind == EQ_STRAIN) deps[i] = target[i] - cur->stran[i];
  double scale = 1;
  for (int i = 0; i < n; i++) scale = fmax(scale, fmax(fabs(cur->stress[i]), fabs(target[i])));
  for (int it = 0; it <= MAX_NEWTON; it++) {
    *next = *cur;
    memcpy(next->dstran, deps, sizeof(double) * n);
    next->dtime = dt;
    umat_invoke(mat, next);
    if (next->pnewdt < 1) {
      res->pnewdt      = next->pnewdt;
      res->umat_failed = 1;
      res->failed_in   = *cur;
      memcpy(res->failed_in.dstran, deps, sizeof(double) * n);
      res->failed_in.dtime = dt;
      res->failed_out      = *next;
      return 1;
    }
    res->pnewdt = next->pnewdt;
    double eps[6], r[6], err = 0;
    for (int i = 0; i < n; i++) eps[i] = cur->stran[i] + deps[i];
    for (int i = 0; i < n; i++) {
      r[i] = residual_of(&sg->eq[i], i, n, eps, next->stress, target[i]);
      double rel = sg->eq[i].kind == EQ_STRAIN ? fabs(r[i]) : fabs(r[i]) / scale;
      err        = fmax(err, rel);
    }
    res->newton        = it;
    res->control_error = err;
    if (err <= 1e-12) return 0;
    if (it == MAX_NEWTON) break;
    double J[6][6];
    for (int i = 0; i < n; i++)
      for (int j = 0; j < n; j++) {
        double dij = next->ddsdde[i + n * j];
        switch (sg->eq[i].kind) {
        case EQ_STRESS: J[i][j] = dij; break;
        case EQ_STRAIN: J[i][j] = i == j; break;
        default: {
          double s = sg->eq[i].a[j];
          for (int k = 0; k < n; k++) s += sg->eq[i].b[k] * next->ddsdde[k + n * j];
          J[i][j] = s;
        }
        }
      }
    if (solve_small(n, J, r)) return 1;
    for (int i = 0; i < n; i++) deps[i] -= r[i];
  }
  return 1;
}

/* Worst relative difference between DDSDDE and central differences of STRESS in DSTRAN. */
static double tangent_check(const UmatMaterial *mat, const UmatCall *cur, const UmatCall *next) {
  int    n = mat->ntens;
  double worst = 0, dmax = 0;
  for (int k = 0; k < n * n; k++) dmax = fmax(dmax, fabs(next->ddsdde[k]));
  for (int j = 0; j < n; j++) {
    double   h = 1e-7 * fmax(1e-3, fabs(next->dstran[j]));
    UmatCall p = *cur, m = *cur;
    memcpy(p.dstran, next->dstran, sizeof p.dstran);
    memcpy(m.dstran, next->dstran, sizeof m.dstran);
    p.dtime = m.dtime = next->dtime;
    p.dstran[j] += h;
    m.dstran[j] -= h;
    umat_invoke(mat, &p);
    umat_invoke(mat, &m);
    for (int i = 0; i < n; i++)
      worst = fmax(worst, fabs((p.stress[i] - m.stress[i]) / (2 * h) - next->ddsdde[i + n * j]) / dmax);
  }
  return worst;
}

static void invariants(const double s[6], int n, double *p, double *q) {
  double t[6] = {0};
  memcpy(t, s, sizeof(double) * n);
  *p         = -(t[0] + t[1] + t[2]) / 3;
  double d[3] = {t[0] + *p, t[1] + *p, t[2] + *p};
  *q = sqrt(1.5 * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] + 2 * (t[3] * t[3] + t[4] * t[4] + t[5] * t[5])));
}

static void write_header(FILE *fp) {
  static const char *c[6] = {"11", "22", "33", "12", "13", "23"};
  fprintf(fp, "time,step,segment,dt,newton_its,local_its,cutbacks");
  const char *groups[] = {"eps", "sig", "sig_hard", "sig_soft", "evp_hard", "evp_soft", "evp"};
  for (int g = 0; g < 7; g++)
    for (int i = 0; i < 6; i++) fprintf(fp, ",%s_%s", groups[g], c[i]);
  fprintf(fp, ",pc_hard,pc_soft,flags\n");
}

static void write_row(FILE *fp, const UmatMaterial *mat, const UmatCall *c, double t, int step, int seg, double dt,
                      int newton, int cutbacks) {
  int n = mat->ntens;
  fprintf(fp, "%.17g,%d,%d,%.17g,%d,%d,%d", t, step, seg, dt, newton, (int)statev_or_zero(mat, c, CAMCLAY9_SV_ITERATIONS),
          cutbacks);
  for (int i = 0; i < 6; i++) fprintf(fp, ",%.12g", i < n ? c->stran[i] : 0.0);
  for (int i = 0; i < 6; i++) fprintf(fp, ",%.12g", i < n ? c->stress[i] : 0.0);
  const int base[5] = {CAMCLAY9_SV_SIG_HARD, CAMCLAY9_SV_SIG_SOFT, CAMCLAY9_SV_EVP_HARD, CAMCLAY9_SV_EVP_SOFT, CAMCLAY9_SV_EVP};
  for (int g = 0; g < 5; g++)
    for (int i = 0; i < 6; i++) fprintf(fp, ",%.12g", statev_or_zero(mat, c, base[g] + i));
  fprintf(fp, ",%.12g,%.12g,%d\n", statev_or_zero(mat, c, CAMCLAY9_SV_PC_HARD), statev_or_zero(mat, c, CAMCLAY9_SV_PC_SOFT),
          (int)statev_or_zero(mat, c, CAMCLAY9_SV_FLAGS));
}

static void write_json(const PointScene *sc, const double *t_start, const double *t_end) {
  char path[1100];
  snprintf(path, sizeof path, "%s/scene.json", sc->outdir);
  FILE *fp = fopen(path, "w");
  if (!fp) return;
  fprintf(fp, "{\"name\": \"%s\", \"ntens\": %d, \"props\": [", sc->name, sc->mat.ntens);
  double props[23] = {0};
  memcpy(props, sc->mat.props, sizeof(double) * (sc->mat.nprops < 23 ? sc->mat.nprops : 23));
  if (sc->mat.nprops < 23) props[22] = 1;
  for (int i = 0; i < 23; i++) fprintf(fp, "%s%.17g", i ? ", " : "", props[i]);
  double nn = sqrt(props[20] * props[20] + props[21] * props[21] + props[22] * props[22]);
  fprintf(fp, "], \"normal\": [%.17g, %.17g, %.17g], \"units\": {\"stress\": \"MPa\", \"time\": \"s\"}, \"segments\": [",
          props[20] / nn, props[21] / nn, props[22] / nn);
  for (int s = 0; s < sc->nseg; s++)
    fprintf(fp, "%s{\"name\": \"%s\", \"t_start\": %.17g, \"t_end\": %.17g, \"creep\": %s, \"axis\": %d}", s ? ", " : "",
            sc->seg[s].name, t_start[s], t_end[s], sc->seg[s].creep ? "true" : "false", sc->seg[s].axis);
  fprintf(fp, "]}\n");
  fclose(fp);
}

int point_run(const PointScene *sc, PointSummary *sum, char *err, size_t errlen) {
  const UmatMaterial *mat = &sc->mat;
  int                 n   = mat->ntens;
  memset(sum, 0, sizeof *sum);
  /* No output directory: run without files (the extremes sweep runs thousands of points). */
  FILE *csv = fopen("/dev/null", "w");
  if (sc->outdir[0]) {
    fclose(csv);
    if (make_directories(sc->outdir)) {
      snprintf(err, errlen, "output directory '%s': cannot create: %s", sc->outdir, strerror(errno));
      return 1;
    }
    char path[1100];
    snprintf(path, sizeof path, "%s/history.csv", sc->outdir);
    csv = fopen(path, "w");
    if (!csv) {
      snprintf(err, errlen, "%s: cannot write: %s", path, strerror(errno));
      return 1;
    }
    write_header(csv);
  }

  UmatCall cur;
  memset(&cur, 0, sizeof cur);
  memcpy(cur.stress, sc->stress0, sizeof cur.stress);
  memcpy(cur.statev, sc->statev0, sizeof cur.statev);
  cur.noel = cur.npt = cur.kstep = cur.kinc = 1;
  /* A zero increment (DSTRAN = 0, DTIME = 0) first: the UMAT initialises its state from STRESS if it
   * needs to (Cam-Clay IX's uninitialised-state rule), so that row 0 shows the real initial state. */
  umat_invoke(mat, &cur);
  if (cur.pnewdt < 1) {
    snprintf(err, errlen, "the UMAT rejected the initial state (a zero increment returned PNEWDT = %g)", cur.pnewdt);
    fclose(csv);
    return 1;
  }
  double  t = 0, last_deps[6] = {0}, last_dt = 0;
  double *t_start = calloc(sc->nseg, sizeof(double)), *t_end = calloc(sc->nseg, sizeof(double));
  write_row(csv, mat, &cur, t, 0, 0, 0, 0, 0);
  struct timespec wall0;
  clock_gettime(CLOCK_MONOTONIC, &wall0);
  int     rc    = 0;

  for (int s = 0; s < sc->nseg && !rc; s++) {
    const Segment *sg = &sc->seg[s];
    double         start[6];
    /* Values at the segment start: ramps begin there; linear constraints keep their value. */
    for (int i = 0; i < n; i++) {
      const Equation *eq = &sg->eq[i];
      if (eq->kind == EQ_STRESS) start[i] = cur.stress[i];
      else if (eq->kind == EQ_STRAIN) start[i] = cur.stran[i];
      else if (!isnan(eq->value)) start[i] = eq->value;
      else {
        double v = 0;
        for (int j = 0; j < n; j++) v += eq->a[j] * cur.stran[j] + eq->b[j] * cur.stress[j];
        start[i] = v;
      }
    }
    t_start[s]      = t;
    double t_seg    = 0, dt;
    const StepControl *stc = &sg->steps;
    int    k_planned = 0, planned = stc->adaptive ? -1 : stc->count;
    dt = step_control_planned(stc, sg->duration, 0);
    int instant_pending = sg->instant;
    int cut_in_step = 0;
    while (!rc) {
      double dt_step;
      if (instant_pending) dt_step = 0; /* the jump: a zero-time, elastic step (DTIME = 0) */
      else {
        if (t_seg >= sg->duration * (1 - 1e-12) || (planned >= 0 && k_planned >= planned && !cut_in_step)) break;
        dt_step = fmin(dt, sg->duration - t_seg);
      }
      double lambda = sg->instant || sg->duration == 0 ? 1 : (t_seg + dt_step) / sg->duration;
      double target[6], deps[6];
      for (int i = 0; i < n; i++) target[i] = target_of(sg, i, start, lambda, t_seg + dt_step);
      for (int i = 0; i < n; i++) deps[i] = last_dt > 0 && dt_step > 0 ? last_deps[i] * dt_step / last_dt : 0;
      UmatCall   next;
      StepResult res;
      cur.time[0] = t_seg, cur.time[1] = t;
      if (mixed_step(mat, sg, &cur, target, dt_step, deps, &next, &res)) {
        /* Cut back: the UMAT's PNEWDT, or half the step when the control Newton did not converge. */
        sum->cutbacks++;
        double factor = res.umat_failed ? fmax(fmin(res.pnewdt, 0.5), 0.1) : 0.5;
        if (dt_step == 0 || ++cut_in_step > MAX_CUTBACKS || dt_step * factor < (stc->adaptive ? stc->min : 0)) {
          sum->failed = 1;
          snprintf(err, errlen,
                   "segment '%s': step failed for good at time %.6g s (segment time %.6g s, dt %.3g s): %s, "
                   "control residual %.3g",
                   sg->name, t, t_seg, dt_step, res.umat_failed ? "the UMAT asked for a smaller step" :
                   "the mixed-control Newton did not converge", res.control_error);
          if (res.umat_failed) {
            char rp[1100];
            snprintf(rp, sizeof rp, "%s/failed_call.yaml", sc->outdir);
            if (!umat_write_replay(rp, mat, &res.failed_in, &res.failed_out, err)) {
              size_t len = strlen(err);
              snprintf(err + len, errlen - len, "; the failing UMAT call is replayed by: driver -input %s", rp);
            }
          }
          rc = 1;
          break;
        }
        dt = dt_step * factor;
        continue;
      }
      if (sc->check_tangent && dt_step > 0) sum->worst_tangent_error = fmax(sum->worst_tangent_error, tangent_check(mat, &cur, &next));
      sum->worst_control_error = fmax(sum->worst_control_error, res.control_error);
      if (sc->replay_step > 0 && sum->steps + 1 == sc->replay_step) {
        UmatCall in = cur;
        memcpy(in.dstran, next.dstran, sizeof in.dstran);
        in.dtime = dt_step;
        char rp[1100];
        snprintf(rp, sizeof rp, "%s/replay_step_%d.yaml", sc->outdir, sc->replay_step);
        if (umat_write_replay(rp, mat, &in, &next, "requested with -write_replay_at_step"))
          fprintf(stderr, "driver: could not write %s\n", rp);
      }
      /* Commit. */
      double evp_old[6];
      for (int i = 0; i < 6; i++) evp_old[i] = statev_or_zero(mat, &cur, CAMCLAY9_SV_EVP + i);
      memcpy(last_deps, next.dstran, sizeof last_deps);
      last_dt = dt_step;
      for (int i = 0; i < n; i++) next.stran[i] = cur.stran[i] + next.dstran[i];
      cur = next;
      cur.kinc++;
      t += dt_step;
      t_seg += dt_step;
      sum->steps++;
      write_row(csv, mat, &cur, t, sum->steps, s, dt_step, res.newton, cut_in_step);
      if (sc->progress_every > 0 && sum->steps % sc->progress_every == 0)
        printf("step %6d  segment %-12s t = %-11.5g dt = %-10.4g newton %d  local %d  cutbacks %d  wall %.2f s\n",
               sum->steps, sg->name, t, dt_step, res.newton, (int)statev_or_zero(mat, &cur, CAMCLAY9_SV_ITERATIONS),
               sum->cutbacks, seconds_since(&wall0));
      if (instant_pending) {
        instant_pending = 0;
        continue;
      }
      /* Next step size. */
      if (stc->adaptive) dt = step_control_next(stc, dt_step, res.pnewdt);
      else if (cut_in_step) {
        /* finish the planned step with the reduced size, then resume the plan */
        double planned_end = 0;
        for (int k = 0; k <= k_planned; k++) planned_end += step_control_planned(stc, sg->duration, k);
        if (t_seg >= planned_end * (1 - 1e-12)) {
          k_planned++;
          cut_in_step = 0;
          dt          = step_control_planned(stc, sg->duration, k_planned);
        } else dt = fmin(2 * dt_step, planned_end - t_seg);
      } else {
        k_planned++;
        dt = step_control_planned(stc, sg->duration, k_planned);
      }
      if (stc->adaptive) cut_in_step = 0;
      /* End conditions. */
      if (sg->until != UNTIL_NONE) {
        double p, q, rate = 0;
        invariants(cur.stress, n, &p, &q);
        for (int i = 0; i < 6; i++) {
          double d = statev_or_zero(mat, &cur, CAMCLAY9_SV_EVP + i) - evp_old[i];
          rate += d * d;
        }
        rate = dt_step > 0 ? sqrt(rate) / dt_step : INFINITY;
        int done = (sg->until == UNTIL_EVP_RATE_BELOW && rate < sg->until_value) ||
                   (sg->until == UNTIL_Q_ABOVE && q > sg->until_value) ||
                   (sg->until == UNTIL_Q_BELOW && q < sg->until_value) || (sg->until == UNTIL_P_ABOVE && p > sg->until_value);
        if (done) break;
      }
    }
    t_end[s] = t;
  }
  fclose(csv);
  memcpy(sum->final_stress, cur.stress, sizeof sum->final_stress);
  sum->wall = seconds_since(&wall0);
  sum->finite = 1;
  for (int i = 0; i < n; i++) sum->finite &= isfinite(cur.stress[i]);
  for (int i = 0; i < mat->nstatv; i++) sum->finite &= isfinite(cur.statev[i]);
  if (sc->outdir[0]) write_json(sc, t_start, t_end);
  free(t_start);
  free(t_end);
  return rc;
}
