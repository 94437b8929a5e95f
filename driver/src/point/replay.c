#include "replay.h"

#include <stdio.h>
#include <string.h>

#include "../material/umat_call.h"

static int same_bits(const double *a, const double *b, int n, const char *what, char *err, size_t errlen) {
  for (int i = 0; i < n; i++)
    if (memcmp(&a[i], &b[i], sizeof(double))) {
      snprintf(err, errlen, "replay differs from the recorded call: %s[%d] = %.17g, recorded %.17g", what, i, a[i],
               b[i]);
      return 1;
    }
  return 0;
}

int replay_run(YdDoc *doc, char *err, size_t errlen) {
  YdNode *root = doc->root, *call = yd_get(root, "call"), *x;
  if (yd_expect(doc, call, YD_MAPPING, "call", err, errlen)) return 1;
  UmatMaterial mat;
  UmatCall     c;
  memset(&mat, 0, sizeof mat);
  memset(&c, 0, sizeof c);
  const char *name = "CAMCLAY9";
  if ((x = yd_get(call, "cmname")) && yd_string(doc, x, "call.cmname", &name, err, errlen)) return 1;
  umat_material_set_name(&mat, name);
  c.noel = c.npt = c.kstep = c.kinc = 1;
  if ((x = yd_get(call, "element")) && yd_int(doc, x, "call.element", &c.noel, err, errlen)) return 1;
  if ((x = yd_get(call, "point")) && yd_int(doc, x, "call.point", &c.npt, err, errlen)) return 1;
  if (yd_int(doc, yd_get(call, "ntens"), "call.ntens", &mat.ntens, err, errlen)) return 1;
  if (mat.ntens != 4 && mat.ntens != 6) {
    snprintf(err, errlen, "%s: key 'call.ntens': expected 4 or 6, got %d", doc->file, mat.ntens);
    return 1;
  }
  if (yd_int(doc, yd_get(call, "nstatv"), "call.nstatv", &mat.nstatv, err, errlen)) return 1;
  if (mat.nstatv < 0 || mat.nstatv > UMAT_MAX_STATEV) {
    snprintf(err, errlen, "%s: key 'call.nstatv': expected 0 to %d", doc->file, UMAT_MAX_STATEV);
    return 1;
  }
  if (yd_doubles(doc, yd_get(call, "props"), "call.props", mat.props, -UMAT_MAX_PROPS, &mat.nprops, err, errlen) ||
      yd_doubles(doc, yd_get(call, "stress"), "call.stress", c.stress, mat.ntens, NULL, err, errlen) ||
      yd_doubles(doc, yd_get(call, "statev"), "call.statev", c.statev, mat.nstatv, NULL, err, errlen) ||
      yd_doubles(doc, yd_get(call, "stran"), "call.stran", c.stran, mat.ntens, NULL, err, errlen) ||
      yd_doubles(doc, yd_get(call, "dstran"), "call.dstran", c.dstran, mat.ntens, NULL, err, errlen) ||
      yd_doubles(doc, yd_get(call, "time"), "call.time", c.time, 2, NULL, err, errlen) ||
      yd_double(doc, yd_get(call, "dtime"), "call.dtime", &c.dtime, err, errlen))
    return 1;
  if (yd_check_unused(doc, call, "call", "cmname, element, point, ntens, nstatv, props, stress, statev, stran, dstran, time, dtime", err, errlen)) return 1;

  umat_invoke(&mat, &c);
  printf("replay: element %d, point %d: PNEWDT = %.17g\n  STRESS =", c.noel, c.npt, c.pnewdt);
  for (int i = 0; i < mat.ntens; i++) printf(" %.17g", c.stress[i]);
  printf("\n");

  YdNode *exp = yd_get(root, "expected");
  yd_get(root, "name"); /* free text */
  if (exp) {
    UmatCall e;
    memset(&e, 0, sizeof e);
    if (yd_double(doc, yd_get(exp, "pnewdt"), "expected.pnewdt", &e.pnewdt, err, errlen) ||
        yd_doubles(doc, yd_get(exp, "stress"), "expected.stress", e.stress, mat.ntens, NULL, err, errlen) ||
        yd_doubles(doc, yd_get(exp, "statev"), "expected.statev", e.statev, mat.nstatv, NULL, err, errlen) ||
        yd_doubles(doc, yd_get(exp, "ddsdde"), "expected.ddsdde", e.ddsdde, mat.ntens * mat.ntens, NULL, err, errlen))
      return 1;
    if (yd_check_unused(doc, exp, "expected", "pnewdt, stress, statev, ddsdde", err, errlen)) return 1;
    if (same_bits(&c.pnewdt, &e.pnewdt, 1, "PNEWDT", err, errlen) ||
        same_bits(c.stress, e.stress, mat.ntens, "STRESS", err, errlen) ||
        same_bits(c.statev, e.statev, mat.nstatv, "STATEV", err, errlen) ||
        same_bits(c.ddsdde, e.ddsdde, mat.ntens * mat.ntens, "DDSDDE", err, errlen))
      return 1;
    printf("replay: identical to the recorded call, bit for bit (PNEWDT, STRESS, STATEV, DDSDDE)\n");
  }
  return yd_check_unused(doc, root, "", "scene, name, call, expected", err, errlen);
}
