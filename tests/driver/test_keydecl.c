/* The key declarations (driver/src/io/keydecl.c, issue 35 item 1) on a table of their own, independently of the
 * scene's: a key read without a declaration is reported by keys_check_document; typed reads take their default,
 * range and choices from the declaration and say each mistake with file, line, key path and value; list items and
 * a table's alias ("stages"/"segments" -> "{stage}") and "*" keys are matched; an unknown key names the allowed
 * ones (and a misspelling), a key of another scene kind says whose it is, a declared key left unread says it does
 * not apply. Every message is compared whole. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "io/keydecl.h"

static int failures;

#define N NAN
static const KeyDecl decl[] = {
  {"a", 1 | 2, KEY_NUMBER, 0, 1, KEY_LO_OPEN | KEY_HI_OPEN, NULL, "0.5", NULL, "a number in (0, 1)"},
  {"n", 1, KEY_INTEGER, 1, N, KEY_TERSE, NULL, "3", NULL, "a count"},
  {"m", 1, KEY_INTEGER, 0, 8, 0, NULL, "2", NULL, "an integer in [0, 8]"},
  {"o", 1, KEY_INTEGER, N, N, 0, "1, 2", "1", NULL, "an order"},
  {"w", 1, KEY_WORD, N, N, 0, "red, green, blue", "green", NULL, "a colour"},
  {"b", 1, KEY_BOOL, N, N, 0, NULL, "true", NULL, "a switch"},
  {"r", 1, KEY_NUMBER, N, N, KEY_REQUIRED, NULL, NULL, NULL, "a required number"},
  {"p", 2, KEY_TEXT, N, N, 0, NULL, NULL, NULL, "a key of kind 2 only"},
  {"stages", 1, KEY_LIST, N, N, 0, NULL, NULL, NULL, "stages"},
  {"segments", 2, KEY_LIST, N, N, 0, NULL, NULL, NULL, "segments"},
  {"{stage}.duration", 1 | 2, KEY_NUMBER, 0, N, 0, NULL, NULL, "s", "a duration"},
  {"{stage}.loads", 1, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "loads by group"},
  {"{stage}.loads.*", 1, KEY_NUMBER, N, N, 0, NULL, NULL, NULL, "a group's load"},
};
static const KeyTable table = {.decl = decl, .n = (int)(sizeof decl / sizeof decl[0]), .kind_names = {"one", "two"},
                               .alias_lists = {"stages", "segments"}, .alias = "{stage}", .source = "the test's table"};

static void expect(const char *what, int rc, const char *err, int want_rc, const char *want) {
  if (rc != want_rc || (want && strcmp(err, want))) {
    printf("FAIL %s: returned %d (want %d)\n  got:  %s\n  want: %s\n", what, rc, want_rc, err, want ? want : "(any)");
    failures++;
  } else printf("ok   %s\n", what);
}

static int load(const char *text, YdDoc *doc, unsigned kind) {
  FILE *fp = fopen("keydecl_test.yaml", "w");
  char  err[512];
  fputs(text, fp);
  fclose(fp);
  if (yd_load("keydecl_test.yaml", doc, err, sizeof err)) {
    printf("FAIL load: %s\n", err);
    failures++;
    return 1;
  }
  keys_attach(doc, &table, kind);
  return 0;
}

int main(void) {
  YdDoc  doc;
  char   err[1024] = "";
  double a = -1;
  int    n = -1, m = -1, o = -1, w = -1, b = -1;

  /* defaults from the declarations, nothing given */
  if (load("r: 1\n", &doc, 1)) return 1;
  double r;
  int rc = keys_number(&doc, doc.root, "a", &a, NULL, err, sizeof err) || keys_integer(&doc, doc.root, "n", &n, NULL, err, sizeof err) ||
           keys_integer(&doc, doc.root, "m", &m, NULL, err, sizeof err) || keys_integer(&doc, doc.root, "o", &o, NULL, err, sizeof err) ||
           keys_word(&doc, doc.root, "w", NULL, &w, NULL, err, sizeof err) || keys_bool(&doc, doc.root, "b", &b, NULL, err, sizeof err) ||
           keys_number(&doc, doc.root, "r", &r, NULL, err, sizeof err);
  expect("defaults", rc || !(a == 0.5 && n == 3 && m == 2 && o == 1 && w == 1 && b == 1 && r == 1), err, 0, NULL);
  expect("nothing unread", keys_check_document(&doc, err, sizeof err), err, 0, NULL);
  /* a key asked for without a declaration */
  yd_get(doc.root, "colour");
  expect("undeclared read", keys_check_document(&doc, err, sizeof err), err, 1,
         "keydecl_test.yaml: key 'colour': read by the driver without a declaration in the test's table (a driver error)");
  expect("typed read of an undeclared key", keys_number(&doc, doc.root, "q", &a, NULL, err, sizeof err), err, 1,
         "keydecl_test.yaml: key 'q': read by the driver without a declaration in the test's table (a driver error)");
  yd_free(&doc);

  /* ranges, choices and types, each message whole */
  const struct {
    const char *text, *key, *want;
  } bad[] = {
    {"a: 1\n", "a", "keydecl_test.yaml:1: key 'a': expected 0 < a < 1, got 1"},
    {"a: x\n", "a", "keydecl_test.yaml:1: key 'a': expected a finite number, got 'x'"},
    {"n: 0\n", "n", "keydecl_test.yaml:1: key 'n': expected >= 1, got 0"},
    {"n: two\n", "n", "keydecl_test.yaml:1: key 'n': expected an integer, got 'two'"},
    {"n: 4294967297\n", "n", "keydecl_test.yaml:1: key 'n': expected an integer from -2147483648 to 2147483647, got '4294967297'"},
    {"m: 9\n", "m", "keydecl_test.yaml:1: key 'm': expected an integer from 0 to 8, got '9'"},
    {"o: 3\n", "o", "keydecl_test.yaml:1: key 'o': expected 1 or 2, got 3"},
    {"w: pink\n", "w", "keydecl_test.yaml:1: key 'w': expected red, green or blue, got 'pink'"},
    {"b: maybe\n", "b", "keydecl_test.yaml:1: key 'b': expected true or false, got 'maybe'"},
    {"x: 1\n", "r", "keydecl_test.yaml:1: key 'r' is missing: expected a number"},
  };
  for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
    if (load(bad[k].text, &doc, 1)) return 1;
    const char *key = bad[k].key;
    int         v;
    double      x;
    rc = key[0] == 'a' || key[0] == 'r' ? keys_number(&doc, doc.root, key, &x, NULL, err, sizeof err)
       : key[0] == 'w'                  ? keys_word(&doc, doc.root, key, NULL, &v, NULL, err, sizeof err)
       : key[0] == 'b'                  ? keys_bool(&doc, doc.root, key, &v, NULL, err, sizeof err)
                                        : keys_integer(&doc, doc.root, key, &v, NULL, err, sizeof err);
    expect(bad[k].want + strlen("keydecl_test.yaml:1: "), rc, err, 1, bad[k].want);
    yd_free(&doc);
  }

  /* list items under the alias, "*" keys; unknown keys, another kind's, a declared one left unread */
  if (load("stages:\n  - {duration: 2, loads: {top: 1, side: 3}}\n  - {loads: {}, durration: 1}\n", &doc, 1)) return 1;
  YdNode *st = yd_get(doc.root, "stages")->items[0], *loads = yd_get(st, "loads");
  double  d  = 0, top = 0;
  rc         = keys_number(&doc, st, "duration", &d, NULL, err, sizeof err) || keys_number(&doc, loads, "top", &top, NULL, err, sizeof err);
  expect("alias and *", rc || d != 2 || top != 1 || !keys_apply(loads, "any"), err, 0, NULL);
  yd_get(loads, "side");
  expect("the first stage read whole", keys_check_unused(&doc, st, NULL, err, sizeof err), err, 0, NULL);
  st = doc.root->items[0]->items[1];
  yd_get(st, "loads");
  expect("unknown key with its misspelling", keys_check_unused(&doc, st, NULL, err, sizeof err), err, 1,
         "keydecl_test.yaml:3: unknown key 'stages[1].durration' (misspelt 'duration'?): allowed keys here are duration, loads");
  yd_free(&doc);
  if (load("segments:\n  - {duration: 1, loads: {top: 1}}\np: x\n", &doc, 2)) return 1;
  st = yd_get(doc.root, "segments")->items[0];
  keys_number(&doc, st, "duration", &d, NULL, err, sizeof err);
  expect("a key of another kind", keys_check_unused(&doc, st, NULL, err, sizeof err), err, 1,
         "keydecl_test.yaml:2: key 'segments[0].loads' is a key of one scenes, not of two scenes (loads: loads by group): allowed keys "
         "here are duration");
  expect("a declared key not read", keys_check_unused(&doc, doc.root, "say why", err, sizeof err), err, 1,
         "keydecl_test.yaml:3: key 'p' does not apply here (say why) (p: a key of kind 2 only)");
  yd_free(&doc);
  remove("keydecl_test.yaml");
  printf("%d failure(s)\n", failures);
  return failures != 0;
}
