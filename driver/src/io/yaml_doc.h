/* A YAML document as a small tree that remembers where each node came from, so that every error
 * about a scene can name the file, the line and the key (libyaml does the parsing). */
#ifndef YAML_DOC_H
#define YAML_DOC_H

#include <stddef.h>

typedef enum { YD_SCALAR, YD_SEQUENCE, YD_MAPPING } YdKind;

typedef struct YdNode YdNode;

/* Whoever declared a document's keys (io/keydecl.h) watches it: yd_get tells it every key a reader asks for, so
 * that a key read without a declaration is found. */
typedef struct YdWatch YdWatch;
struct YdWatch {
  void (*asked)(YdWatch *w, const YdNode *map, const char *key);
};

struct YdNode {
  YdKind   kind;
  int      line;      /* 1-based line in the file */
  const char *key;    /* the key it is the value of (in its mapping), or NULL */
  int      index;     /* its index in its sequence, or -1 */
  char    *text;      /* scalar text (YD_SCALAR) */
  size_t   n;         /* children: sequence items, or mapping pairs */
  YdNode **items;     /* sequence items, or mapping values */
  char   **keys;      /* mapping keys (YD_MAPPING) */
  int     *key_lines; /* line of each key */
  int     *used;      /* mapping: set when a reader asked for the key (unknown-key check) */
  YdNode  *parent;    /* the mapping or sequence it is in; NULL: the root */
  YdWatch *watch;     /* the root's: the declarations its keys are read against (io/keydecl.h), or NULL */
};

typedef struct {
  char   *file;
  YdNode *root;
} YdDoc;

/* Parse a file. Returns 0 on success; else fills err (file:line: message) and returns 1. */
int  yd_load(const char *file, YdDoc *doc, char *err, size_t errlen);
void yd_free(YdDoc *doc);

/* The key path of node from the root: "stages[2].steps" (canonical: "stages[].steps", every index as []). */
const char *yd_node_path(const YdNode *node, int canonical, char *buf, size_t n);
/* The document's root of node. */
const YdNode *yd_root(const YdNode *node);

/* Mapping lookup; NULL if absent. Marks the key as used (and tells the root's watch, if any). */
YdNode *yd_get(YdNode *map, const char *key);
/* Line of key in map (or of map if absent). */
int yd_key_line(const YdNode *map, const char *key);

/* Typed reads; each returns 0 on success, else writes "file:line: key 'path': expected ..., got ..."
 * into err and returns 1. 'path' is the dotted key path used in messages; when it names the node's parent
 * (stages[0].steps for the node of count), the node's own key or index is added, so a message always
 * names the key whose value is wrong. */
int yd_double(const YdDoc *doc, const YdNode *node, const char *path, double *value, char *err, size_t errlen);
int yd_int(const YdDoc *doc, const YdNode *node, const char *path, int *value, char *err, size_t errlen);
/* An integer in [lo, hi] (io/text.h: the one integer check of every reader). */
int yd_int_range(const YdDoc *doc, const YdNode *node, const char *path, long long lo, long long hi, int *value, char *err,
                 size_t errlen);
int yd_bool(const YdDoc *doc, const YdNode *node, const char *path, int *value, char *err, size_t errlen);
int yd_string(const YdDoc *doc, const YdNode *node, const char *path, const char **value, char *err, size_t errlen);
/* A sequence of exactly n numbers (n < 0: any length up to -n; count returned in *got). */
int yd_doubles(const YdDoc *doc, const YdNode *node, const char *path, double *values, int n, int *got, char *err,
               size_t errlen);
/* The value of a required key of a kind; NULL with err filled when it is missing (naming a misspelt
 * key of the mapping, e.g. 'segmnets' for 'segments') or of another kind. */
YdNode *yd_require(const YdDoc *doc, YdNode *map, const char *key, YdKind kind, const char *path, char *err,
                   size_t errlen);
/* Expect a node of a kind. */
int yd_expect(const YdDoc *doc, const YdNode *node, YdKind kind, const char *path, char *err, size_t errlen);
/* After reading a mapping: any key never asked for is an error naming it and the allowed keys. */
/* The key path of node: path, with the node's key or index added unless path ends with it. */
const char *yd_path(const YdNode *node, const char *path, char *buf, size_t n);
int yd_check_unused(const YdDoc *doc, const YdNode *map, const char *path, const char *allowed, char *err,
                    size_t errlen);

#endif
