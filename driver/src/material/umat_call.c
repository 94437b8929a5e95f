/* Calling an Abaqus UMAT from C, and writing a replay of one call. */
#include "umat_call.h"

#include <float.h>
#include <string.h>

/* The standard Abaqus UMAT argument list (gfortran: trailing underscore, hidden CMNAME length last). */
extern void umat_(double *stress, double *statev, double *ddsdde, double *sse, double *spd, double *scd, double *rpl,
                  double *ddsddt, double *drplde, double *drpldt, const double *stran, const double *dstran,
                  const double *time, const double *dtime, const double *temp, const double *dtemp,
                  const double *predef, const double *dpred, const char *cmname, const int *ndi, const int *nshr,
                  const int *ntens, const int *nstatv, const double *props, const int *nprops, const double *coords,
                  const double *drot, double *pnewdt, const double *celent, const double *dfgrd0,
                  const double *dfgrd1, const int *noel, const int *npt, const int *layer, const int *kspt,
                  const int *jstep, const int *kinc, unsigned long cmname_len);

void umat_material_set_name(UmatMaterial *mat, const char *name) {
  memset(mat->cmname, ' ', sizeof mat->cmname);
  size_t n = strlen(name);
  memcpy(mat->cmname, name, n < sizeof mat->cmname ? n : sizeof mat->cmname);
}

void umat_invoke(const UmatMaterial *mat, UmatCall *c) { umat_invoke_props(mat, mat->props, c); }

void umat_invoke_props(const UmatMaterial *mat, const double *props, UmatCall *c) {
  static const double drot[9]   = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  static const double coords[3] = {0, 0, 0}, f[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  double              rpl, ddsddt[6], drplde[6], drpldt, temp = 0, dtemp = 0, predef = 0, dpred = 0, celent = 1;
  int                 ndi = 3, nshr = mat->ntens - 3, layer = 1, kspt = 1;
  int                 jstep[4] = {c->kstep, 1, 0, 0};
  c->pnewdt                    = DBL_MAX; /* Abaqus sets PNEWDT large before each call */
  umat_(c->stress, c->statev, c->ddsdde, &c->sse, &c->spd, &c->scd, &rpl, ddsddt, drplde, &drpldt, c->stran,
        c->dstran, c->time, &c->dtime, &temp, &dtemp, &predef, &dpred, mat->cmname, &ndi, &nshr, &mat->ntens,
        &mat->nstatv, props, &mat->nprops, coords, drot, &c->pnewdt, &celent, f, f, &c->noel, &c->npt, &layer,
        &kspt, jstep, &c->kinc, sizeof mat->cmname);
}

static void list(FILE *fp, const char *key, const double *v, int n) {
  fprintf(fp, "  %s: [", key);
  for (int i = 0; i < n; i++) fprintf(fp, "%s%.17g", i ? ", " : "", v[i]);
  fprintf(fp, "]\n");
}

int umat_write_replay(const char *path, const UmatMaterial *mat, const UmatCall *in, const UmatCall *out,
                      const char *why) {
  FILE *fp = fopen(path, "w");
  if (!fp) return 1;
  char name[81];
  memcpy(name, mat->cmname, 80);
  name[80] = '\0';
  for (int i = 79; i >= 0 && name[i] == ' '; i--) name[i] = '\0';
  fprintf(fp, "# Replays one UMAT call exactly (%%.17g round-trips every double): driver -input %s\n", path);
  fprintf(fp, "# Why it was written: %s\n", why);
  fprintf(fp, "scene: replay\nname: replay\ncall:\n");
  fprintf(fp, "  cmname: \"%s\"\n  element: %d\n  point: %d\n  ntens: %d\n  nstatv: %d\n", name, in->noel, in->npt,
          mat->ntens, mat->nstatv);
  list(fp, "props", mat->props, mat->nprops);
  list(fp, "stress", in->stress, mat->ntens);
  list(fp, "statev", in->statev, mat->nstatv);
  list(fp, "stran", in->stran, mat->ntens);
  list(fp, "dstran", in->dstran, mat->ntens);
  list(fp, "time", in->time, 2);
  fprintf(fp, "  dtime: %.17g\n", in->dtime);
  fprintf(fp, "expected:\n  pnewdt: %.17g\n", out->pnewdt);
  list(fp, "stress", out->stress, mat->ntens);
  list(fp, "statev", out->statev, mat->nstatv);
  list(fp, "ddsdde", out->ddsdde, mat->ntens * mat->ntens);
  return fclose(fp) != 0;
}
