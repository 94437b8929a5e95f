/* Key declarations (keydecl.h): lookup by key path, typed reads, the unknown-key check, the reference's text. */
#include "keydecl.h"

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "text.h"

typedef struct {
  YdWatch         base; /* first: the root frees the whole struct */
  const KeyTable *t;
  unsigned        kind;
  char            undeclared[512]; /* the first key asked for without a declaration */
} Watch;

static void say(char *err, size_t errlen, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(err, errlen, fmt, ap);
  va_end(ap);
}

static Watch *watch_of(const YdNode *node) {
  const YdNode *root = yd_root(node);
  return root ? (Watch *)root->watch : NULL;
}

/* The canonical key path of map's key (key NULL: of map itself), the table's alias put for its lists' items. */
static const char *canonical(const Watch *w, const YdNode *map, const char *key, char *buf, size_t n) {
  char raw[512];
  yd_node_path(map, 1, raw, sizeof raw);
  const char *rest = raw, *head = "";
  for (int k = 0; w && k < 4 && w->t->alias_lists[k]; k++) {
    size_t l = strlen(w->t->alias_lists[k]);
    if (!strncmp(raw, w->t->alias_lists[k], l) && !strncmp(raw + l, "[]", 2) && (raw[l + 2] == '.' || !raw[l + 2])) {
      head = w->t->alias, rest = raw + l + 2;
      break;
    }
  }
  if (snprintf(buf, n, "%s%s%s%s", head, rest, key && (*head || *rest) ? "." : "", key ? key : "") < 0) buf[0] = '\0';
  return buf;
}

/* Whether declared path d matches canonical path c, segment by segment ("*" matches any one key). */
static int path_matches(const char *d, const char *c) {
  for (;;) {
    const char *de = strchr(d, '.'), *ce = strchr(c, '.');
    size_t      dl = de ? (size_t)(de - d) : strlen(d), cl = ce ? (size_t)(ce - c) : strlen(c);
    int         star = dl == 1 && d[0] == '*';
    if (!star && (dl != cl || strncmp(d, c, dl))) return 0;
    if (star && cl >= 2 && !strncmp(c + cl - 2, "[]", 2)) return 0;
    if (!de || !ce) return !de && !ce;
    d = de + 1, c = ce + 1;
  }
}

static const KeyDecl *lookup(const KeyTable *t, const char *path, unsigned kinds) {
  for (int k = 0; k < t->n; k++)
    if ((t->decl[k].kinds & kinds) && path_matches(t->decl[k].path, path)) return &t->decl[k];
  return NULL;
}

static void asked(YdWatch *base, const YdNode *map, const char *key) {
  Watch *w = (Watch *)base;
  char   path[512];
  if (w->undeclared[0]) return;
  canonical(w, map, key, path, sizeof path);
  if (!lookup(w->t, path, w->kind)) snprintf(w->undeclared, sizeof w->undeclared, "%s", path);
}

void keys_attach(YdDoc *doc, const KeyTable *t, unsigned kind) {
  if (!doc->root) return;
  Watch *w = (Watch *)doc->root->watch;
  if (!w) {
    w = calloc(1, sizeof *w);
    doc->root->watch = &w->base;
  }
  w->base.asked = asked, w->t = t, w->kind = kind;
}

const KeyDecl *keys_find(const YdNode *map, const char *key) {
  const Watch *w = watch_of(map);
  char         path[512];
  return w ? lookup(w->t, canonical(w, map, key, path, sizeof path), w->kind) : NULL;
}

int keys_apply(const YdNode *map, const char *key) { return keys_find(map, key) != NULL; }

static const char *full_path(const YdNode *map, const char *key, char *buf, size_t n) {
  char p[512];
  yd_node_path(map, 0, p, sizeof p);
  if (snprintf(buf, n, "%s%s%s", p, *p ? "." : "", key) < 0) buf[0] = '\0';
  return buf;
}

/* "a, b or c" from "a, b, c". */
static const char *choices_or(const char *choices, char *buf, size_t n) {
  const char *last = strrchr(choices, ',');
  if (!last) snprintf(buf, n, "%s", choices);
  else snprintf(buf, n, "%.*s or %s", (int)(last - choices), choices, last + 2);
  return buf;
}

static const char *leaf(const char *path) {
  const char *dot = strrchr(path, '.');
  return dot ? dot + 1 : path;
}

static const char *range_text(const KeyDecl *d, int terse, char *buf, size_t n) {
  int lo = !isnan(d->lo), hi = !isnan(d->hi), lo_open = d->flags & KEY_LO_OPEN, hi_open = d->flags & KEY_HI_OPEN;
  buf[0] = '\0';
  if (d->choices && (d->type == KEY_WORD || d->type == KEY_INTEGER)) return choices_or(d->choices, buf, n);
  if (d->type == KEY_INTEGER && !terse && (lo || hi)) {
    text_int_expected(lo ? (long long)d->lo : INT_MIN, hi ? (long long)d->hi : INT_MAX, buf, n);
    return buf;
  }
  if (lo && hi && !lo_open && !hi_open) snprintf(buf, n, "a number from %g to %g", d->lo, d->hi);
  else if (lo && hi) snprintf(buf, n, "%g %s %s %s %g", d->lo, lo_open ? "<" : "<=", leaf(d->path), hi_open ? "<" : "<=", d->hi);
  else if (lo) snprintf(buf, n, "%s %g", lo_open ? ">" : ">=", d->lo);
  else if (hi) snprintf(buf, n, "%s %g", hi_open ? "<" : "<=", d->hi);
  return buf;
}

const char *keys_range_text(const KeyDecl *d, char *buf, size_t n) { return range_text(d, 0, buf, n); }

static int in_range(const KeyDecl *d, double v) {
  if (!isnan(d->lo) && ((d->flags & KEY_LO_OPEN) ? !(v > d->lo) : !(v >= d->lo))) return 0;
  if (!isnan(d->hi) && ((d->flags & KEY_HI_OPEN) ? !(v < d->hi) : !(v <= d->hi))) return 0;
  return 1;
}

static const char *type_name(KeyType t) {
  static const char *names[] = {"a mapping", "a list", "a number", "an integer", "true or false", "a word", "a text", "a file",
                                "a list of numbers", "a value"};
  return names[t];
}

/* The declaration every typed read needs: with a table, a read of an undeclared key is the driver's error. */
static int declared(const YdDoc *doc, YdNode *map, const char *key, const KeyDecl **d, char *err, size_t errlen) {
  const Watch *w = watch_of(map);
  char         path[512];
  *d = NULL;
  if (!w) return 0;
  *d = lookup(w->t, canonical(w, map, key, path, sizeof path), w->kind);
  if (*d) return 0;
  say(err, errlen, "%s: key '%s': read by the driver without a declaration in %s (a driver error)", doc->file, path, w->t->source);
  return 1;
}

/* An absent key: an error if it is required (its default is the caller's to set). */
static int absent(const YdDoc *doc, YdNode *map, const KeyDecl *d, const char *key, char *err, size_t errlen) {
  char path[512];
  if (!d || !(d->flags & KEY_REQUIRED)) return 0;
  say(err, errlen, "%s:%d: key '%s' is missing: expected %s", doc->file, map ? map->line : 0, full_path(map, key, path, sizeof path),
      type_name(d->type));
  return 1;
}

/* Every typed read begins so: the declaration (*d), the value's node (*nd, also into *node_out) and its key path.
   -1: an error (err filled); 0: absent (the caller applies the default, then absent()); 1: present. */
static int fetch(const YdDoc *doc, YdNode *map, const char *key, const KeyDecl **d, YdNode **nd, YdNode **node_out, char *path,
                 size_t n, char *err, size_t errlen) {
  if (declared(doc, map, key, d, err, errlen)) return -1;
  *nd = yd_get(map, key);
  if (node_out) *node_out = *nd;
  full_path(map, key, path, n);
  return *nd != NULL;
}

/* The place of word s in the choices ("a, b, c"), or -1. */
static int word_index(const char *choices, const char *s) {
  int k = 0;
  for (const char *c = choices; c && *c; k++) {
    size_t l = strcspn(c, ",");
    if (l == strlen(s) && !strncmp(c, s, l)) return k;
    c += l;
    while (*c == ',' || *c == ' ') c++;
  }
  return -1;
}

int keys_number(const YdDoc *doc, YdNode *map, const char *key, double *v, YdNode **node_out, char *err, size_t errlen) {
  const KeyDecl *d;
  YdNode        *nd;
  char           path[512], range[160];
  int            got = fetch(doc, map, key, &d, &nd, node_out, path, sizeof path, err, errlen);
  if (got <= 0) {
    if (!got && d && d->def) text_real(d->def, v); /* a default in words leaves *v as the reader set it */
    return got < 0 || absent(doc, map, d, key, err, errlen);
  }
  if (yd_double(doc, nd, path, v, err, errlen)) return 1;
  if (d && !in_range(d, *v)) {
    say(err, errlen, "%s:%d: key '%s': expected %s, got %g", doc->file, nd->line, path, keys_range_text(d, range, sizeof range), *v);
    return 1;
  }
  return 0;
}

static int int_choice(const char *choices, int v) {
  char want[16];
  snprintf(want, sizeof want, "%d", v);
  return word_index(choices, want) >= 0;
}

int keys_integer(const YdDoc *doc, YdNode *map, const char *key, int *v, YdNode **node_out, char *err, size_t errlen) {
  const KeyDecl *d;
  YdNode        *nd;
  char           path[512], range[160];
  int            got = fetch(doc, map, key, &d, &nd, node_out, path, sizeof path, err, errlen);
  if (got <= 0) {
    if (!got && d && d->def) text_int(d->def, INT_MIN, INT_MAX, v);
    return got < 0 || absent(doc, map, d, key, err, errlen);
  }
  if (yd_expect(doc, nd, YD_SCALAR, path, err, errlen)) return 1;
  int       ranged = d && !d->choices && (!isnan(d->lo) || !isnan(d->hi)), terse = d && (d->flags & KEY_TERSE);
  long long lo = ranged && !isnan(d->lo) ? (long long)d->lo : INT_MIN, hi = ranged && !isnan(d->hi) ? (long long)d->hi : INT_MAX;
  int       why = text_int(nd->text, INT_MIN, INT_MAX, v);
  if (why == TEXT_NOT_A_NUMBER) {
    say(err, errlen, "%s:%d: key '%s': expected an integer, got '%s'", doc->file, nd->line, path, nd->text);
    return 1;
  }
  if (why || (ranged && (*v < lo || *v > hi))) {
    if (why && (!ranged || terse)) text_int_expected(INT_MIN, INT_MAX, range, sizeof range);
    else if (terse) range_text(d, 1, range, sizeof range);
    else text_int_expected(lo, hi, range, sizeof range);
    if (!why && terse) say(err, errlen, "%s:%d: key '%s': expected %s, got %d", doc->file, nd->line, path, range, *v);
    else say(err, errlen, "%s:%d: key '%s': expected %s, got '%s'", doc->file, nd->line, path, range, nd->text);
    return 1;
  }
  if (d && d->choices && !int_choice(d->choices, *v)) { /* an integer, but not one of the choices */
    say(err, errlen, "%s:%d: key '%s': expected %s, got %d", doc->file, nd->line, path, keys_range_text(d, range, sizeof range), *v);
    return 1;
  }
  return 0;
}

int keys_bool(const YdDoc *doc, YdNode *map, const char *key, int *v, YdNode **node_out, char *err, size_t errlen) {
  const KeyDecl *d;
  YdNode        *nd;
  char           path[512];
  int            got = fetch(doc, map, key, &d, &nd, node_out, path, sizeof path, err, errlen);
  if (got <= 0) {
    if (!got && d && d->def) *v = !strcmp(d->def, "true");
    return got < 0 || absent(doc, map, d, key, err, errlen);
  }
  return yd_bool(doc, nd, path, v, err, errlen);
}

int keys_word(const YdDoc *doc, YdNode *map, const char *key, const char **v, int *index, YdNode **node_out, char *err,
              size_t errlen) {
  const KeyDecl *d;
  YdNode        *nd;
  char           path[512], range[256];
  const char    *s;
  int            got = fetch(doc, map, key, &d, &nd, node_out, path, sizeof path, err, errlen);
  if (got <= 0) {
    if (!got && d && d->def && d->choices && word_index(d->choices, d->def) >= 0) {
      if (v) *v = d->def;
      if (index) *index = word_index(d->choices, d->def);
    }
    return got < 0 || absent(doc, map, d, key, err, errlen);
  }
  if (yd_string(doc, nd, path, &s, err, errlen)) return 1;
  int k = d && d->choices ? word_index(d->choices, s) : 0;
  if (k < 0) {
    say(err, errlen, "%s:%d: key '%s': expected %s, got '%s'", doc->file, nd->line, path, keys_range_text(d, range, sizeof range), s);
    return 1;
  }
  if (v) *v = s;
  if (index) *index = k;
  return 0;
}

/* The keys declared in map for kind, "a, b, c", into buf. */
static const char *children(const Watch *w, const YdNode *map, char *buf, size_t n) {
  char   base[512];
  size_t len = 0, lb;
  canonical(w, map, NULL, base, sizeof base);
  lb     = strlen(base);
  buf[0] = '\0';
  for (int k = 0; k < w->t->n; k++) {
    const KeyDecl *d = &w->t->decl[k];
    const char    *p = d->path, *name;
    char           seen[80];
    if (!(d->kinds & w->kind)) continue;
    if (lb) {
      /* d's parent must match base: compare all but its last segment */
      const char *dot = strrchr(p, '.');
      if (!dot) continue;
      char parent[512];
      snprintf(parent, sizeof parent, "%.*s", (int)(dot - p), p);
      if (!path_matches(parent, base)) continue;
      name = dot + 1;
    } else {
      if (strchr(p, '.')) continue;
      name = p;
    }
    snprintf(seen, sizeof seen, "%.*s", (int)strcspn(name, "["), name);
    if (!strcmp(seen, "*")) continue;
    /* once each (a key declared for several kinds appears once per kind in the table) */
    int dup = 0;
    for (const char *c = buf; *c && !dup;) {
      size_t l = strcspn(c, ",");
      dup      = l == strlen(seen) && !strncmp(c, seen, l);
      c += l;
      while (*c == ',' || *c == ' ') c++;
    }
    if (!dup && len < n) len += (size_t)snprintf(buf + len, n - len, "%s%s", len ? ", " : "", seen);
  }
  return buf;
}

int keys_check_unused(const YdDoc *doc, const YdNode *map, const char *why, char *err, size_t errlen) {
  const Watch *w = watch_of(map);
  char         path[512], list[1024], cpath[512];
  if (!map || map->kind != YD_MAPPING) return 0;
  for (size_t i = 0; i < map->n; i++) {
    if (map->used[i]) continue;
    full_path(map, map->keys[i], path, sizeof path);
    if (!w) {
      say(err, errlen, "%s:%d: unknown key '%s'", doc->file, map->key_lines[i], path);
      return 1;
    }
    canonical(w, map, map->keys[i], cpath, sizeof cpath);
    const KeyDecl *d = lookup(w->t, cpath, w->kind);
    if (d) {
      say(err, errlen, "%s:%d: key '%s' does not apply here%s%s%s (%s: %s)", doc->file, map->key_lines[i], path, why ? " (" : "",
          why ? why : "", why ? ")" : "", map->keys[i], d->help);
      return 1;
    }
    children(w, map, list, sizeof list);
    const KeyDecl *other = lookup(w->t, cpath, ~w->kind);
    if (other) {
      char kinds[64] = "";
      for (int k = 0; k < 4; k++)
        if ((other->kinds >> k & 1) && w->t->kind_names[k])
          snprintf(kinds + strlen(kinds), sizeof kinds - strlen(kinds), "%s%s", kinds[0] ? " and " : "", w->t->kind_names[k]);
      const char *mine = "";
      for (int k = 0; k < 4; k++)
        if ((w->kind >> k & 1) && w->t->kind_names[k]) mine = w->t->kind_names[k];
      say(err, errlen, "%s:%d: key '%s' is a key of %s scenes, not of %s scenes (%s: %s): allowed keys here are %s", doc->file,
          map->key_lines[i], path, kinds, mine, map->keys[i], other->help, list);
      return 1;
    }
    /* a misspelling of a declared key the mapping does not hold */
    char hint[96] = "";
    for (const char *c = list; *c;) {
      size_t l = strcspn(c, ",");
      char   name[80];
      snprintf(name, sizeof name, "%.*s", (int)l, c);
      int held = 0;
      for (size_t j = 0; j < map->n; j++) held |= !strcmp(map->keys[j], name);
      if (!held && !hint[0] && text_distance(map->keys[i], name) <= 2) snprintf(hint, sizeof hint, " (misspelt '%s'?)", name);
      c += l;
      while (*c == ',' || *c == ' ') c++;
    }
    say(err, errlen, "%s:%d: unknown key '%s'%s: allowed keys here are %s", doc->file, map->key_lines[i], path, hint, list);
    return 1;
  }
  return 0;
}

static int check_tree(const YdDoc *doc, const YdNode *nd, char *err, size_t errlen) {
  if (!nd) return 0;
  if (nd->kind == YD_MAPPING && keys_check_unused(doc, nd, NULL, err, errlen)) return 1;
  for (size_t i = 0; i < nd->n; i++)
    if ((nd->kind != YD_MAPPING || nd->used[i]) && check_tree(doc, nd->items[i], err, errlen)) return 1;
  return 0;
}

int keys_check_document(const YdDoc *doc, char *err, size_t errlen) {
  const Watch *w = watch_of(doc->root);
  if (w && w->undeclared[0]) {
    say(err, errlen, "%s: key '%s': read by the driver without a declaration in %s (a driver error)", doc->file, w->undeclared,
        w->t->source);
    return 1;
  }
  return check_tree(doc, doc->root, err, errlen);
}

/* One declaration's columns: kinds, type with range or choices. */
static void columns(const KeyTable *t, const KeyDecl *d, char *kinds, size_t nk, char *type, size_t nt) {
  char range[200];
  kinds[0] = '\0';
  for (int k = 0; k < 4; k++)
    if ((d->kinds >> k & 1) && t->kind_names[k])
      snprintf(kinds + strlen(kinds), nk - strlen(kinds), "%s%s", kinds[0] ? ", " : "", t->kind_names[k]);
  keys_range_text(d, range, sizeof range);
  if (d->type == KEY_FORMS) snprintf(type, nt, "%s", d->choices ? d->choices : "a value");
  else if (d->choices && (d->type == KEY_WORD || d->type == KEY_INTEGER)) snprintf(type, nt, "one of %s", d->choices);
  else if (range[0] && d->type == KEY_INTEGER) snprintf(type, nt, "%s", range);
  else if (!strncmp(range, "a number", 8)) snprintf(type, nt, "%s", range);
  else if (range[0]) snprintf(type, nt, "%s%s%s", type_name(d->type), range[0] == '>' || range[0] == '<' ? " " : ", ", range);
  else snprintf(type, nt, "%s", type_name(d->type));
}

static void write_one(const KeyTable *t, const KeyDecl *d, int markdown, FILE *fp) {
  char kinds[64], type[300];
  columns(t, d, kinds, sizeof kinds, type, sizeof type);
  const char *def = d->flags & KEY_REQUIRED ? "required" : d->def ? d->def : "";
  if (markdown) {
    fprintf(fp, "| `%s` | %s | ", d->path, kinds);
    for (const char *c = type; *c; c++) fputs(*c == '|' ? "\\|" : (char[]){*c, 0}, fp);
    fprintf(fp, " | %s | %s | ", def, d->unit ? d->unit : "");
    for (const char *c = d->help; *c; c++) fputs(*c == '|' ? "\\|" : (char[]){*c, 0}, fp);
    fputs(" |\n", fp);
  } else {
    char head[160];
    snprintf(head, sizeof head, "%s [%s]", d->path, kinds);
    fprintf(fp, "  %-44s %s", head, type);
    if (def[0]) fprintf(fp, "; %s%s", d->flags & KEY_REQUIRED ? "" : "default: ", def);
    if (d->unit) fprintf(fp, "; unit: %s", d->unit);
    fprintf(fp, ". %s\n", d->help);
  }
}

void keys_write(const KeyTable *t, int markdown, FILE *fp) {
  if (markdown) fputs("| key | scenes | type, range or choices | default | unit | meaning |\n|---|---|---|---|---|---|\n", fp);
  for (int k = 0; k < t->n; k++) write_one(t, &t->decl[k], markdown, fp);
}

size_t keys_text(const KeyTable *t, char *buf, size_t n) {
  FILE *fp = fmemopen(buf, n, "w");
  if (!fp) return 0;
  keys_write(t, 0, fp);
  long len = ftell(fp);
  fclose(fp);
  return (size_t)len;
}
