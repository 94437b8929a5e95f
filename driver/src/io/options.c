#include "options.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "text.h"

/* The names the blocks declared (main calls every block once before the run). */
#define MAX_DECLARED 96
static char declared[MAX_DECLARED][48];
static int  ndeclared;

static void remember(const char *name) {
  for (int k = 0; k < ndeclared; k++)
    if (!strcmp(declared[k], name)) return;
  if (ndeclared < MAX_DECLARED) snprintf(declared[ndeclared++], sizeof declared[0], "%s", name);
}

/* The options the driver set itself (options_default). */
static char defaulted[MAX_DECLARED][64];
static int  ndefaulted;

PetscErrorCode options_default(const char *name, const char *value) {
  PetscBool set;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasName(NULL, NULL, name, &set));
  if (!set) {
    PetscCall(PetscOptionsSetValue(NULL, name, value));
    if (ndefaulted < MAX_DECLARED && !options_set_by_driver(name)) snprintf(defaulted[ndefaulted++], sizeof defaulted[0], "%s", name);
  }
  PetscFunctionReturn(0);
}

int options_set_by_driver(const char *name) {
  const char *bare = name[0] == '-' ? name + 1 : name;
  for (int k = 0; k < ndefaulted; k++)
    if (!strcmp(defaulted[k] + 1, bare)) return 1;
  return 0;
}

/* help with the range appended: "help [range]" (into buf). */
static const char *with_range(const char *help, const char *range, char *buf, size_t n) {
  if (snprintf(buf, n, "%s [%s]", help, range) < 0) buf[0] = '\0';
  return buf;
}

/* The value given for name, or NULL (not given, or given without a value: *bare). */
static PetscErrorCode given_text(const char *name, char *buf, size_t n, PetscBool *given) {
  PetscFunctionBeginUser;
  buf[0] = '\0';
  PetscCall(PetscOptionsGetString(NULL, NULL, name, buf, n, given));
  PetscFunctionReturn(0);
}

PetscErrorCode options_int(PetscOptionItems *PetscOptionsObject, const char *name, const char *help, PetscInt def, PetscInt lo,
                           PetscInt hi, PetscInt *value, PetscBool *set) {
  char      text[256], want[96], range[64], full[1024];
  PetscBool given;
  int       v;
  PetscFunctionBeginUser;
  remember(name);
  PetscCall(given_text(name, text, sizeof text, &given));
  if (given && text_int(text, lo, hi, &v)) {
    text_int_expected(lo, hi, want, sizeof want);
    SETERRQ(PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "option %s %s: expected %s", name, text[0] ? text : "(no value)", want);
  }
  if (hi >= PETSC_MAX_INT) snprintf(range, sizeof range, ">= %lld", (long long)lo);
  else snprintf(range, sizeof range, "%lld to %lld", (long long)lo, (long long)hi);
  PetscCall(PetscOptionsRangeInt(name, with_range(help, range, full, sizeof full), NULL, def, value, set, lo, hi));
  PetscFunctionReturn(0);
}

/* "a number > 0 and < 1", "a number from 1.2 to 8", ">= 0" ... */
static const char *real_range(PetscReal lo, PetscReal hi, unsigned open, char *buf, size_t n) {
  const char *gl = open & OPTIONS_LO_OPEN ? ">" : ">=", *lh = open & OPTIONS_HI_OPEN ? "<" : "<=";
  if (!isnan(lo) && !isnan(hi) && !open) snprintf(buf, n, "a number from %g to %g", (double)lo, (double)hi);
  else if (!isnan(lo) && !isnan(hi)) snprintf(buf, n, "a number %s %g and %s %g", gl, (double)lo, lh, (double)hi);
  else if (!isnan(lo)) snprintf(buf, n, "a number %s %g", gl, (double)lo);
  else if (!isnan(hi)) snprintf(buf, n, "a number %s %g", lh, (double)hi);
  else snprintf(buf, n, "a finite number");
  return buf;
}

PetscErrorCode options_real(PetscOptionItems *PetscOptionsObject, const char *name, const char *help, PetscReal def, PetscReal lo,
                            PetscReal hi, unsigned open, PetscReal *value, PetscBool *set) {
  char      text[256], range[96], full[1024];
  PetscBool given;
  double    v = 0;
  PetscFunctionBeginUser;
  remember(name);
  PetscCall(given_text(name, text, sizeof text, &given));
  PetscCheck(!given || !text_real(text, &v), PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "option %s %s: expected a finite number", name,
             text[0] ? text : "(no value)");
  real_range(lo, hi, open, range, sizeof range);
  int below = !isnan(lo) && ((open & OPTIONS_LO_OPEN) ? !(v > lo) : !(v >= lo));
  int above = !isnan(hi) && ((open & OPTIONS_HI_OPEN) ? !(v < hi) : !(v <= hi));
  PetscCheck(!given || !(below || above), PETSC_COMM_WORLD, PETSC_ERR_ARG_OUTOFRANGE, "option %s %s: expected %s", name, text, range);
  const char *shown = !strncmp(range, "a number from ", 14) ? range + 14 : !strncmp(range, "a number ", 9) ? range + 9 : range;
  PetscCall(PetscOptionsReal(name, with_range(help, shown, full, sizeof full), NULL, def, value, set));
  PetscFunctionReturn(0);
}

PetscErrorCode options_bool(PetscOptionItems *PetscOptionsObject, const char *name, const char *help, PetscBool def,
                            PetscBool *value, PetscBool *set) {
  char      text[256];
  PetscBool given, ok = PETSC_TRUE;
  PetscFunctionBeginUser;
  remember(name);
  PetscCall(given_text(name, text, sizeof text, &given));
  if (given && text[0]) {
    const char *words[] = {"true", "false", "yes", "no", "1", "0", "on", "off"};
    ok = PETSC_FALSE;
    for (int k = 0; k < 8; k++) ok = ok || !strcasecmp(text, words[k]) ? PETSC_TRUE : PETSC_FALSE;
  }
  PetscCheck(ok, PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "option %s %s: expected true or false (or nothing: true)", name, text);
  PetscCall(PetscOptionsBool(name, help, NULL, def, value, set));
  PetscFunctionReturn(0);
}

PetscErrorCode options_string(PetscOptionItems *PetscOptionsObject, const char *name, const char *help, const char *def,
                              char *value, size_t len, PetscBool *set) {
  PetscFunctionBeginUser;
  remember(name);
  PetscCall(PetscOptionsString(name, help, NULL, def, value, len, set));
  PetscFunctionReturn(0);
}

PetscErrorCode options_elist(PetscOptionItems *PetscOptionsObject, const char *name, const char *help, const char *const *list,
                             PetscInt n, PetscInt def, PetscInt *value, PetscBool *set) {
  char      text[256], all[256] = "";
  PetscBool given, ok = PETSC_FALSE;
  PetscFunctionBeginUser;
  remember(name);
  PetscCall(given_text(name, text, sizeof text, &given));
  for (PetscInt k = 0; k < n; k++) {
    ok = ok || !strcmp(text, list[k]) ? PETSC_TRUE : PETSC_FALSE;
    size_t l = strlen(all);
    PetscCall(PetscSNPrintf(all + l, sizeof all - l, "%s%s", k ? ", " : "", list[k]));
  }
  PetscCheck(!given || ok, PETSC_COMM_WORLD, PETSC_ERR_ARG_WRONG, "option %s %s: expected one of %s", name, text[0] ? text : "(no value)", all);
  PetscCall(PetscOptionsEList(name, help, NULL, list, n, list[def], value, set));
  PetscFunctionReturn(0);
}

static char petsc_prefix[4][32];
static int  npetsc_prefix;

void options_petsc_prefix(const char *prefix) {
  for (int k = 0; k < npetsc_prefix; k++)
    if (!strcmp(petsc_prefix[k], prefix)) return;
  if (npetsc_prefix < 4) snprintf(petsc_prefix[npetsc_prefix++], sizeof petsc_prefix[0], "%s", prefix);
}

/* Whether name is an option of a PETSc object under a registered prefix. */
static int petsc_object_option(const char *name) {
  static const char *objects[] = {"ksp_", "pc_", "mat_", "fieldsplit_"};
  for (int k = 0; k < npetsc_prefix; k++) {
    size_t l = strlen(petsc_prefix[k]);
    if (name[0] != '-' || strncmp(name + 1, petsc_prefix[k], l)) continue;
    for (int j = 0; j < 4; j++)
      if (!strncmp(name + 1 + l, objects[j], strlen(objects[j]))) return 1;
  }
  return 0;
}

/* Whether name begins like a declared option (its text up to the first '_' after the dash, or all of it) or
   like one of the extra prefixes. */
static int driver_like(const char *name, const char *const *extra) {
  for (int k = 0; k < ndeclared; k++) {
    const char *u = strchr(declared[k] + 1, '_');
    size_t      l = u ? (size_t)(u - declared[k] + 1) : strlen(declared[k]);
    if (!strncmp(name, declared[k], l) && (u || !name[l])) return 1;
  }
  for (int k = 0; extra && extra[k]; k++)
    if (!strncmp(name, extra[k], strlen(extra[k]))) return 1;
  return 0;
}

static int is_declared(const char *name) {
  for (int k = 0; k < ndeclared; k++)
    if (!strcmp(declared[k], name)) return 1;
  return 0;
}

PetscErrorCode options_check_unknown(const char *const *names, int n, const char *const *extra_prefixes, const char *source, char *err,
                                     size_t errlen, PetscBool *bad) {
  PetscInt nleft = 0;
  char   **left = NULL, **values = NULL;
  PetscFunctionBeginUser;
  *bad = PETSC_FALSE;
  if (!names) {
    PetscCall(PetscOptionsLeftGet(NULL, &nleft, &left, &values));
    names = (const char *const *)left, n = (int)nleft;
  }
  for (int k = 0; k < n && !*bad; k++) {
    char name[256];
    snprintf(name, sizeof name, "%s%s", names[k][0] == '-' ? "" : "-", names[k]);
    if (is_declared(name) || petsc_object_option(name) || !driver_like(name, extra_prefixes)) continue;
    int best = 9, which = -1;
    for (int j = 0; j < ndeclared; j++) {
      int d = text_distance(name, declared[j]);
      if (d < best) best = d, which = j;
    }
    char hint[96] = "";
    if (which >= 0 && best <= 3) snprintf(hint, sizeof hint, " (misspelt %s?)", declared[which]);
    snprintf(err, errlen, "%s%soption %s: not an option of the driver%s; nothing was run (driver -help lists the options)",
             source ? source : "", source ? ": " : "", name, hint);
    *bad = PETSC_TRUE;
  }
  if (left) PetscCall(PetscOptionsLeftRestore(NULL, &nleft, &left, &values));
  PetscFunctionReturn(0);
}

PetscErrorCode options_forget_reads(void) {
  PetscFunctionBeginUser;
  for (int k = 0; k < ndeclared; k++) {
    char      value[1024];
    PetscBool set;
    PetscCall(PetscOptionsHasName(NULL, NULL, declared[k], &set));
    if (!set) continue;
    PetscCall(PetscOptionsGetString(NULL, NULL, declared[k], value, sizeof value, &set));
    PetscCall(PetscOptionsClearValue(NULL, declared[k]));
    PetscCall(PetscOptionsSetValue(NULL, declared[k], value[0] ? value : NULL));
  }
  PetscFunctionReturn(0);
}
