/* YAML document tree with line numbers, built on libyaml's event parser. */
#include "yaml_doc.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <yaml.h>

#include "text.h"

static void say(char *err, size_t errlen, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(err, errlen, fmt, ap);
  va_end(ap);
}

static YdNode *node_new(YdKind kind, int line) {
  YdNode *nd = calloc(1, sizeof *nd);
  nd->kind  = kind;
  nd->line  = line;
  nd->index = -1;
  return nd;
}

static void node_push(YdNode *parent, char *key, int key_line, YdNode *child) {
  parent->items = realloc(parent->items, (parent->n + 1) * sizeof *parent->items);
  parent->items[parent->n] = child;
  child->key                = key; /* owned by the parent's keys */
  child->parent             = parent;
  child->index              = parent->kind == YD_SEQUENCE ? (int)parent->n : -1;
  if (parent->kind == YD_MAPPING) {
    parent->keys      = realloc(parent->keys, (parent->n + 1) * sizeof *parent->keys);
    parent->key_lines = realloc(parent->key_lines, (parent->n + 1) * sizeof *parent->key_lines);
    parent->used      = realloc(parent->used, (parent->n + 1) * sizeof *parent->used);
    parent->keys[parent->n]      = key;
    parent->key_lines[parent->n] = key_line;
    parent->used[parent->n]      = 0;
  }
  parent->n++;
}

static void node_free(YdNode *nd) {
  if (!nd) return;
  for (size_t i = 0; i < nd->n; i++) {
    node_free(nd->items[i]);
    if (nd->keys) free(nd->keys[i]);
  }
  free(nd->items);
  free(nd->keys);
  free(nd->key_lines);
  free(nd->used);
  free(nd->text);
  free(nd->watch); /* the root's (io/keydecl.h allocates it) */
  free(nd);
}

/* Recursive descent over the event stream: parse one node starting with event ev. */
static int parse_node(yaml_parser_t *p, yaml_event_t *ev, YdNode **out, const char *file, char *err, size_t errlen);

static int next_event(yaml_parser_t *p, yaml_event_t *ev, const char *file, char *err, size_t errlen) {
  if (!yaml_parser_parse(p, ev)) {
    say(err, errlen, "%s:%zu: YAML syntax error: %s", file, p->problem_mark.line + 1,
        p->problem ? p->problem : "unknown");
    return 1;
  }
  return 0;
}

static int parse_node(yaml_parser_t *p, yaml_event_t *ev, YdNode **out, const char *file, char *err, size_t errlen) {
  int line = (int)ev->start_mark.line + 1;
  if (ev->type == YAML_SCALAR_EVENT) {
    YdNode *nd = node_new(YD_SCALAR, line);
    nd->text   = strndup((const char *)ev->data.scalar.value, ev->data.scalar.length);
    *out       = nd;
    return 0;
  }
  if (ev->type == YAML_ALIAS_EVENT) {
    say(err, errlen, "%s:%d: YAML aliases are not supported in scene files", file, line);
    return 1;
  }
  if (ev->type == YAML_SEQUENCE_START_EVENT || ev->type == YAML_MAPPING_START_EVENT) {
    int          mapping = ev->type == YAML_MAPPING_START_EVENT;
    YdNode      *nd      = node_new(mapping ? YD_MAPPING : YD_SEQUENCE, line);
    yaml_event_t e;
    *out = nd;
    for (;;) {
      if (next_event(p, &e, file, err, errlen)) return 1;
      if (e.type == YAML_SEQUENCE_END_EVENT || e.type == YAML_MAPPING_END_EVENT) {
        yaml_event_delete(&e);
        return 0;
      }
      char *key      = NULL;
      int   key_line = 0;
      if (mapping) {
        if (e.type != YAML_SCALAR_EVENT) {
          say(err, errlen, "%s:%zu: mapping keys must be plain scalars", file, e.start_mark.line + 1);
          yaml_event_delete(&e);
          return 1;
        }
        key      = strndup((const char *)e.data.scalar.value, e.data.scalar.length);
        key_line = (int)e.start_mark.line + 1;
        for (size_t i = 0; i < nd->n; i++)
          if (!strcmp(nd->keys[i], key)) {
            say(err, errlen, "%s:%d: key '%s' appears twice (first on line %d)", file, key_line, key,
                nd->key_lines[i]);
            free(key);
            yaml_event_delete(&e);
            return 1;
          }
        yaml_event_delete(&e);
        if (next_event(p, &e, file, err, errlen)) {
          free(key);
          return 1;
        }
      }
      YdNode *child = NULL;
      int     rc    = parse_node(p, &e, &child, file, err, errlen);
      yaml_event_delete(&e);
      if (rc) {
        free(key);
        node_free(child);
        return 1;
      }
      node_push(nd, key, key_line, child);
    }
  }
  say(err, errlen, "%s:%d: unexpected YAML event", file, line);
  return 1;
}

/* A NUL byte (a binary or damaged file) stops libyaml with an unhelpful message: find its line. */
static int nul_line(FILE *fp) {
  int c, line = 1;
  while ((c = getc(fp)) != EOF) {
    if (c == '\0') return line;
    if (c == '\n') line++;
  }
  return 0;
}

int yd_load(const char *file, YdDoc *doc, char *err, size_t errlen) {
  struct stat st;
  memset(doc, 0, sizeof *doc);
  if (!stat(file, &st) && S_ISDIR(st.st_mode)) {
    say(err, errlen, "%s: -input is a directory: expected a scene file (YAML)", file);
    return 1;
  }
  FILE *fp = fopen(file, "rb");
  if (!fp) {
    say(err, errlen, "%s: cannot open the scene file: %s", file, strerror(errno));
    return 1;
  }
  int nul = nul_line(fp);
  if (nul) {
    say(err, errlen, "%s:%d: a NUL byte: a scene file is text (is it binary or damaged?)", file, nul);
    fclose(fp);
    return 1;
  }
  rewind(fp);
  yaml_parser_t p;
  yaml_event_t  ev;
  yaml_parser_initialize(&p);
  yaml_parser_set_input_file(&p, fp);
  int rc = 0;
  doc->file = strdup(file);
  /* stream start, document start, root node */
  for (;;) {
    if (next_event(&p, &ev, file, err, errlen)) {
      rc = 1;
      break;
    }
    if (ev.type == YAML_STREAM_START_EVENT || ev.type == YAML_DOCUMENT_START_EVENT) {
      yaml_event_delete(&ev);
      continue;
    }
    if (ev.type == YAML_STREAM_END_EVENT) {
      yaml_event_delete(&ev);
      say(err, errlen, "%s: the scene file is empty", file);
      rc = 1;
      break;
    }
    rc = parse_node(&p, &ev, &doc->root, file, err, errlen);
    yaml_event_delete(&ev);
    break;
  }
  yaml_parser_delete(&p);
  fclose(fp);
  if (!rc && doc->root->kind != YD_MAPPING) {
    say(err, errlen, "%s:%d: a scene file is a mapping of keys (scene:, material:, ...)", file, doc->root->line);
    rc = 1;
  }
  if (rc) yd_free(doc);
  return rc;
}

void yd_free(YdDoc *doc) {
  node_free(doc->root);
  free(doc->file);
  memset(doc, 0, sizeof *doc);
}

const YdNode *yd_root(const YdNode *node) {
  while (node && node->parent) node = node->parent;
  return node;
}

const char *yd_node_path(const YdNode *node, int canonical, char *buf, size_t n) {
  const YdNode *chain[64];
  int           depth = 0;
  size_t        len   = 0;
  buf[0]              = '\0';
  for (const YdNode *x = node; x && x->parent && depth < 64; x = x->parent) chain[depth++] = x;
  while (depth-- > 0 && len < n) {
    const YdNode *x = chain[depth];
    if (x->key) len += (size_t)snprintf(buf + len, n - len, "%s%s", len ? "." : "", x->key);
    else if (canonical) len += (size_t)snprintf(buf + len, n - len, "[]");
    else len += (size_t)snprintf(buf + len, n - len, "[%d]", x->index);
  }
  return buf;
}

YdNode *yd_get(YdNode *map, const char *key) {
  if (!map || map->kind != YD_MAPPING) return NULL;
  const YdNode *root = yd_root(map);
  if (root->watch) root->watch->asked(root->watch, map, key);
  for (size_t i = 0; i < map->n; i++)
    if (!strcmp(map->keys[i], key)) {
      map->used[i] = 1;
      return map->items[i];
    }
  return NULL;
}

int yd_key_line(const YdNode *map, const char *key) {
  if (!map) return 0;
  if (map->kind == YD_MAPPING)
    for (size_t i = 0; i < map->n; i++)
      if (!strcmp(map->keys[i], key)) return map->key_lines[i];
  return map->line;
}

static const char *kind_name(YdKind k) {
  return k == YD_SCALAR ? "a value" : k == YD_SEQUENCE ? "a list" : "a mapping";
}

YdNode *yd_require(const YdDoc *doc, YdNode *map, const char *key, YdKind kind, const char *path, char *err,
                   size_t errlen) {
  YdNode *nd = yd_get(map, key);
  if (nd) return yd_expect(doc, nd, kind, path, err, errlen) ? NULL : nd;
  if (map && map->kind == YD_MAPPING)
    for (size_t i = 0; i < map->n; i++)
      if (!map->used[i] && text_distance(map->keys[i], key) <= 2) {
        say(err, errlen, "%s:%d: unknown key '%s' (misspelt '%s'?): key '%s' is missing: expected %s", doc->file,
            map->key_lines[i], map->keys[i], key, path, kind_name(kind));
        return NULL;
      }
  say(err, errlen, "%s:%d: key '%s' is missing: expected %s", doc->file, map ? map->line : 0, path, kind_name(kind));
  return NULL;
}

const char *yd_path(const YdNode *node, const char *path, char *buf, size_t n) {
  size_t lp = strlen(path);
  if (node && node->key) {
    size_t lk = strlen(node->key);
    if ((lp == lk || (lp > lk && path[lp - lk - 1] == '.')) && !strcmp(path + lp - lk, node->key)) return path;
    snprintf(buf, n, "%s%s%s", path, lp ? "." : "", node->key);
    return buf;
  }
  if (node && node->index >= 0 && !(lp && path[lp - 1] == ']')) {
    snprintf(buf, n, "%s[%d]", path, node->index);
    return buf;
  }
  return path;
}

int yd_expect(const YdDoc *doc, const YdNode *node, YdKind kind, const char *path, char *err, size_t errlen) {
  char full[512];
  if (!node) {
    say(err, errlen, "%s: key '%s' is missing: expected %s", doc->file, path, kind_name(kind));
    return 1;
  }
  if (node->kind != kind) {
    say(err, errlen, "%s:%d: key '%s': expected %s, got %s", doc->file, node->line, yd_path(node, path, full, sizeof full),
        kind_name(kind), kind_name(node->kind));
    return 1;
  }
  return 0;
}

int yd_double(const YdDoc *doc, const YdNode *node, const char *path, double *value, char *err, size_t errlen) {
  char full[512];
  if (yd_expect(doc, node, YD_SCALAR, path, err, errlen)) return 1;
  if (text_real(node->text, value)) {
    say(err, errlen, "%s:%d: key '%s': expected a finite number, got '%s'", doc->file, node->line,
        yd_path(node, path, full, sizeof full), node->text);
    return 1;
  }
  return 0;
}

int yd_int_range(const YdDoc *doc, const YdNode *node, const char *path, long long lo, long long hi, int *value, char *err,
                 size_t errlen) {
  char full[512], want[96];
  if (yd_expect(doc, node, YD_SCALAR, path, err, errlen)) return 1;
  int why = text_int(node->text, lo, hi, value);
  if (why) {
    if (why == TEXT_NOT_A_NUMBER && lo <= INT_MIN && hi >= INT_MAX) snprintf(want, sizeof want, "an integer");
    else text_int_expected(lo, hi, want, sizeof want);
    say(err, errlen, "%s:%d: key '%s': expected %s, got '%s'", doc->file, node->line, yd_path(node, path, full, sizeof full),
        want, node->text);
    return 1;
  }
  return 0;
}

int yd_int(const YdDoc *doc, const YdNode *node, const char *path, int *value, char *err, size_t errlen) {
  return yd_int_range(doc, node, path, INT_MIN, INT_MAX, value, err, errlen);
}

int yd_bool(const YdDoc *doc, const YdNode *node, const char *path, int *value, char *err, size_t errlen) {
  char full[512];
  if (yd_expect(doc, node, YD_SCALAR, path, err, errlen)) return 1;
  if (!strcasecmp(node->text, "true") || !strcasecmp(node->text, "yes")) *value = 1;
  else if (!strcasecmp(node->text, "false") || !strcasecmp(node->text, "no")) *value = 0;
  else {
    say(err, errlen, "%s:%d: key '%s': expected true or false, got '%s'", doc->file, node->line,
        yd_path(node, path, full, sizeof full), node->text);
    return 1;
  }
  return 0;
}

int yd_string(const YdDoc *doc, const YdNode *node, const char *path, const char **value, char *err, size_t errlen) {
  if (yd_expect(doc, node, YD_SCALAR, path, err, errlen)) return 1;
  *value = node->text;
  return 0;
}

int yd_doubles(const YdDoc *doc, const YdNode *node, const char *path, double *values, int n, int *got, char *err,
               size_t errlen) {
  if (yd_expect(doc, node, YD_SEQUENCE, path, err, errlen)) return 1;
  int cap = n < 0 ? -n : n;
  char full[512];
  path = yd_path(node, path, full, sizeof full);
  if ((n >= 0 && (int)node->n != n) || (n < 0 && (int)node->n > cap)) {
    say(err, errlen, "%s:%d: key '%s': expected a list of %s%d numbers, got %zu", doc->file, node->line, path,
        n < 0 ? "at most " : "", cap, node->n);
    return 1;
  }
  char item[256];
  for (size_t i = 0; i < node->n; i++) {
    snprintf(item, sizeof item, "%s[%zu]", path, i);
    if (yd_double(doc, node->items[i], item, &values[i], err, errlen)) return 1;
  }
  if (got) *got = (int)node->n;
  return 0;
}

int yd_check_unused(const YdDoc *doc, const YdNode *map, const char *path, const char *allowed, char *err,
                    size_t errlen) {
  if (!map || map->kind != YD_MAPPING) return 0;
  for (size_t i = 0; i < map->n; i++)
    if (!map->used[i]) {
      say(err, errlen, "%s:%d: unknown key '%s%s%s': allowed keys here are %s", doc->file, map->key_lines[i], path,
          *path ? "." : "", map->keys[i], allowed);
      return 1;
    }
  return 0;
}
