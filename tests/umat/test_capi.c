/* The library from C, as the FE driver uses it: camclay9_check_props, camclay9_prop_name, camclay9_prop_info,
 * camclay9_statev_block and umat_ (issues #2, #24). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "camclay9.h"

static int failures = 0, checks = 0;
static void check(int ok, const char *what) {
  ++checks;
  if (!ok) { ++failures; printf("FAIL %s\n", what); }
}

int main(void) {
  double props[23] = {0.5, 2900, 18000, 13000, 4100, 6900, 1.46, 0.00013, 0.73, -0.20, 0.40, 2.0, 1.3e13,
                      4600, 3100, 1.46, 0.0026, 35.0, 1.3e10, 0.0, 0.0, 0.0, 1.0};
  char msg[256];
  int code;
  camclay9_check_props(props, 23, 32, 6, 3, &code, msg, sizeof msg);
  check(code == 0, "valid PROPS accepted");
  props[7] = -1.0;
  camclay9_check_props(props, 23, 32, 6, 3, &code, msg, sizeof msg);
  printf("C API message: %s\n", msg);
  check(code == 8 && strstr(msg, "PROPS(8)") != NULL, "lambda_p < 0 rejected, naming PROPS(8)");
  camclay9_check_props(props, 23, 32, 6, 3, &code, msg, 10);
  check(strlen(msg) == 9, "message truncated to the buffer");
  props[7] = 0.00013;

  /* The PROPS names (ccix_props' table, docs/umat.md): 0-based, NUL-terminated, truncated to the buffer. */
  char name[16];
  check(camclay9_prop_name(0, name, sizeof name) == 3 && !strcmp(name, "phi"), "PROPS name 0: phi");
  check(camclay9_prop_name(18, name, sizeof name) == 8 && !strcmp(name, "eta_soft"), "PROPS name 18: eta_soft");
  check(camclay9_prop_name(22, name, sizeof name) == 2 && !strcmp(name, "n3"), "PROPS name 22: n3");
  check(camclay9_prop_name(23, name, sizeof name) == 0 && name[0] == '\0', "no PROPS slot 23");
  check(camclay9_prop_name(-1, name, sizeof name) == 0, "no PROPS slot -1");
  check(camclay9_prop_name(1, name, 4) == 3 && !strcmp(name, "lam"), "name truncated to the buffer");

  /* The PROPS table (issue 24): each slot's name as camclay9_prop_name spells it, and its own bounds are exactly
   * what camclay9_check_props enforces: a value on a closed bound passes, on an open bound or one step (nextafter)
   * beyond either bound fails, naming that slot and the table's symbol. Every slot states a bound or a condition. */
  camclay9_prop_info_t info;
  const double woodford[23] = {0.5, 2900, 18000, 13000, 4100, 6900, 1.46, 0.00013, 0.73, -0.20, 0.40, 2.0, 1.3e13,
                               4600, 3100, 1.46, 0.0026, 35.0, 1.3e10, 0.0, 0.0, 0.0, 1.0};
  int np = 0, nbounded = 0;
  for (int k = 0; camclay9_prop_info(k, &info); k++, np++) {
    char what[96];
    camclay9_prop_name(k, name, sizeof name);
    snprintf(what, sizeof what, "PROPS slot %d (%s): name, bounds and their checks", k, name);
    int ok = !strcmp(info.name, name) && info.unit[0] && info.meaning[0] && info.symbol[0] &&
             (info.bounds & (CAMCLAY9_BOUND_LO | CAMCLAY9_BOUND_HI | CAMCLAY9_BOUND_COUPLED));
    const int lo = info.bounds & CAMCLAY9_BOUND_LO, hi = info.bounds & CAMCLAY9_BOUND_HI;
    ok = ok && (lo ? info.lo > -DBL_MAX : info.lo == -DBL_MAX) && (hi ? info.hi < DBL_MAX : info.hi == DBL_MAX);
    struct { double v; int valid; } probe[4] = {
      {info.lo, !!(info.bounds & CAMCLAY9_BOUND_LO_CLOSED)}, {nextafter(info.lo, -DBL_MAX), 0},
      {info.hi, !!(info.bounds & CAMCLAY9_BOUND_HI_CLOSED)}, {nextafter(info.hi, DBL_MAX), 0}};
    for (int j = 0; j < 4; j++) {
      if (!(j < 2 ? lo : hi)) continue;
      for (int i = 0; i < 23; i++) props[i] = woodford[i];
      props[k] = probe[j].v;
      camclay9_check_props(props, 23, 32, 6, 3, &code, msg, sizeof msg);
      ok = ok && (probe[j].valid ? code == 0 : code == k + 1 && strstr(msg, info.symbol) != NULL);
    }
    nbounded += lo || hi;
    check(ok, what);
  }
  /* The bounds again, from an independent source: the interface contract (docs/umat-interface.md, "Bad
   * properties", written by hand, not generated from ccix_props): M <= 0, lambda_p <= 0,
   * pc0 <= 0, eta < 0 and phi outside [0, 1] are invalid. Each bound value itself and one ulp beyond it, in
   * 1-based slots as the contract numbers them: a bound of the library's table that leaves the contract fails
   * here (the loop above only checks the table against itself). */
  const struct { int slot; double bound; int closed, below; } spec[] = {
    {1, 0, 1, 1}, {1, 1, 1, 0},             /* phi in [0, 1] */
    {7, 0, 0, 1}, {16, 0, 0, 1},            /* M > 0, hard and soft */
    {8, 0, 0, 1}, {17, 0, 0, 1},            /* lambda_p > 0 */
    {12, 0, 0, 1}, {18, 0, 0, 1},           /* pc0 > 0 */
    {13, 0, 1, 1}, {19, 0, 1, 1}};          /* eta >= 0 (0: rate independent) */
  for (size_t j = 0; j < sizeof spec / sizeof spec[0]; j++) {
    char what[96];
    const int k = spec[j].slot - 1;
    double beyond = nextafter(spec[j].bound, spec[j].below ? -DBL_MAX : DBL_MAX), inside = spec[j].bound +
                    (spec[j].below ? 1 : -1) * fmax(1e-3, 1e-3 * fabs(spec[j].bound));
    int ok = 1, c1, c2, c3;
    for (int i = 0; i < 23; i++) props[i] = woodford[i];
    props[k] = spec[j].bound, camclay9_check_props(props, 23, 32, 6, 3, &c1, msg, sizeof msg);
    props[k] = beyond, camclay9_check_props(props, 23, 32, 6, 3, &c2, msg, sizeof msg);
    props[k] = inside, camclay9_check_props(props, 23, 32, 6, 3, &c3, msg, sizeof msg);
    ok = (spec[j].closed ? c1 == 0 : c1 == k + 1) && c2 == k + 1 && c3 == 0;
    snprintf(what, sizeof what, "PROPS(%d) %s %g as docs/umat-interface.md states (codes %d %d %d)", spec[j].slot,
             spec[j].below ? (spec[j].closed ? ">=" : ">") : (spec[j].closed ? "<=" : "<"), spec[j].bound, c1, c2, c3);
    check(ok, what);
  }
  for (int i = 0; i < 23; i++) props[i] = woodford[i];
  check(np == CAMCLAY9_NPROPS_WITH_NORMAL && nbounded == 14, "23 PROPS slots, 14 with bounds of their own");
  check(!camclay9_prop_info(23, &info) && !info.name[0] && !camclay9_prop_info(-1, &info), "no PROPS slot 23 or -1");
  camclay9_prop_info(0, &info);
  check(info.lo == 0 && info.hi == 1 && info.bounds == (CAMCLAY9_BOUND_LO | CAMCLAY9_BOUND_LO_CLOSED | CAMCLAY9_BOUND_HI |
                                                        CAMCLAY9_BOUND_HI_CLOSED) && !strcmp(info.unit, "-"),
        "phi in [0, 1], no unit");
  camclay9_prop_info(12, &info);
  check(info.lo == 0 && info.bounds == (CAMCLAY9_BOUND_LO | CAMCLAY9_BOUND_LO_CLOSED) && !strcmp(info.unit, "MPa^3 s"),
        "eta_hard >= 0 in MPa^3 s");
  camclay9_prop_info(11, &info);
  check(info.lo == 0 && info.bounds == CAMCLAY9_BOUND_LO && !strcmp(info.unit, "MPa"), "pc0_hard > 0 in MPa");

  /* The STATEV blocks: the exported table and the header's constants name the same slots. */
  const struct { const char *name; int first, size; } blocks[] = {
    {"sig_hard", CAMCLAY9_SV_SIG_HARD, 6}, {"evp_hard", CAMCLAY9_SV_EVP_HARD, 6}, {"pc_hard", CAMCLAY9_SV_PC_HARD, 1},
    {"sig_soft", CAMCLAY9_SV_SIG_SOFT, 6}, {"evp_soft", CAMCLAY9_SV_EVP_SOFT, 6}, {"pc_soft", CAMCLAY9_SV_PC_SOFT, 1},
    {"evp", CAMCLAY9_SV_EVP, 6},           {"iterations", CAMCLAY9_SV_ITERATIONS, 1}, {"flags", CAMCLAY9_SV_FLAGS, 1},
    {"f_hard", 34, 1},                     {"f_soft", 35, 1}};
  int nb = 0, first, size;
  for (int k = 0; camclay9_statev_block(k, name, sizeof name, &first, &size); k++, nb++)
    check(k < 11 && !strcmp(name, blocks[k].name) && first == blocks[k].first && size == blocks[k].size, blocks[k].name);
  check(nb == 11 && first == -1 && size == 0, "11 STATEV blocks, then none");
  check(blocks[10].first + 1 == CAMCLAY9_NSTATV_DIAGNOSTICS && blocks[6].first + 6 == CAMCLAY9_NSTATV_MIN, "the blocks fill NSTATV");

  /* One elastic call (DTIME = 0): STRESS = C:DSTRAN from the stress-free state, DDSDDE = C. */
  double stress[6] = {0}, statev[32] = {0}, ddsdde[36], sse = 0, spd = 0, scd = 0, rpl, ddsddt[6], drplde[6],
         drpldt, stran[6] = {0}, dstran[6] = {0, 0, -1e-4, 0, 0, 0}, time[2] = {0, 0}, dtime = 0, temp = 0,
         dtemp = 0, predef[1] = {0}, dpred[1] = {0}, coords[3] = {0}, drot[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1},
         pnewdt = 1, celent = 1, dfgrd0[9] = {0}, dfgrd1[9] = {0};
  int ndi = 3, nshr = 3, ntens = 6, nstatv = 32, nprops = 23, noel = 1, npt = 1, layer = 1, kspt = 1,
      jstep[4] = {1, 1, 0, 0}, kinc = 1;
  char cmname[80];
  memset(cmname, ' ', sizeof cmname);
  memcpy(cmname, "CAMCLAY9", 8);
  umat_(stress, statev, ddsdde, &sse, &spd, &scd, &rpl, ddsddt, drplde, &drpldt, stran, dstran, time, &dtime,
        &temp, &dtemp, predef, dpred, cmname, &ndi, &nshr, &ntens, &nstatv, props, &nprops, coords, drot, &pnewdt,
        &celent, dfgrd0, dfgrd1, &noel, &npt, &layer, &kspt, jstep, &kinc, 80);
  /* Mixture C33 (theta = 0, phi = 0.5) = 0.5*34000 + 0.5*(4600 + 6200) = 22400 MPa; C13 = 0.5*7000 + 0.5*4600. */
  check(fabs(stress[2] - (-1e-4 * 22400.0)) < 1e-12, "sigma33 = C33 deps33");
  check(fabs(stress[0] - (-1e-4 * 5800.0)) < 1e-12, "sigma11 = C13 deps33");
  check(fabs(ddsdde[2 * 6 + 2] - 22400.0) < 1e-9, "DDSDDE(3,3) = C33");
  check(statev[12] == 2.0 && statev[25] == 35.0, "state initialised from PROPS: pc0 hard 2, soft 35");
  printf("test_capi: %d passed, %d failed\n", checks - failures, failures);
  return failures != 0;
}
