/* One declaration per key of a YAML input (as deal.II's declare_parameters or MOOSE's validParams): its key path,
 * the kinds of scene that read it, its type, its range or choices, its default, its unit and a line of help. The
 * table of declarations (the scene's: scene/scene_keys.c) drives
 *   - the readers' typed reads (keys_number, keys_integer, keys_word, keys_bool): the value's type, its range or
 *     choices and, when the key is absent, its default, with one message for each kind of mistake
 *     ("FILE:LINE: key 'PATH': expected RANGE, got VALUE");
 *   - the unknown-key check (keys_check_unused, keys_check_document): a key no reader asked for is refused,
 *     naming the keys declared there, or the kind of scene it belongs to;
 *   - the text of -help and the key reference of docs/driver.md (keys_write: the same lines);
 *   - the check that every key a reader asks for is declared: once a table is attached to a document
 *     (keys_attach), yd_get reports every key asked for, and keys_check_document refuses one without a
 *     declaration (a driver bug, caught by any scene that reaches that reader).
 *
 * Key paths: "mesh.order"; a list's items as "[]" ("boundary.fixed[].group"); "*" for a key of the user's
 * choosing ("mesh.parameters.*", "stages[].pressure.*"). A table may give several root lists one name: the items
 * of "stages" (FE scenes) and of "segments" (point scenes) are both "{stage}". */
#ifndef IO_KEYDECL_H
#define IO_KEYDECL_H

#include <stddef.h>
#include <stdio.h>

#include "yaml_doc.h"

typedef enum {
  KEY_MAPPING,  /* a mapping of the keys declared below it */
  KEY_LIST,     /* a list (of the items declared as PATH[]..., or of what its help says) */
  KEY_NUMBER,   /* a finite number, within [lo, hi] */
  KEY_INTEGER,  /* an integer, within [lo, hi] or one of choices */
  KEY_BOOL,     /* true or false */
  KEY_WORD,     /* one of choices */
  KEY_TEXT,     /* any text (a name, a column, a group) */
  KEY_FILE,     /* a path, relative to the scene file's folder */
  KEY_NUMBERS,  /* a list of numbers (how many: the help) */
  KEY_FORMS     /* one of several forms, listed in choices ("a number | hold | {exp: ...}") */
} KeyType;

enum {
  KEY_LO_OPEN  = 1, /* > lo (else >= lo) */
  KEY_HI_OPEN  = 2, /* < hi (else <= hi) */
  KEY_REQUIRED = 4, /* must be given (where its mapping is) */
  KEY_TERSE    = 8  /* an integer's range said as a number's ("expected >= 1, got 0") */
};

typedef struct {
  const char *path;    /* the key path (above) */
  unsigned    kinds;   /* the scene kinds that read it (bits of KeyTable.kind_names) */
  KeyType     type;
  double      lo, hi;  /* the range; NAN: none on that side */
  unsigned    flags;   /* KEY_LO_OPEN, KEY_HI_OPEN, KEY_REQUIRED */
  const char *choices; /* KEY_WORD, KEY_INTEGER, KEY_FORMS: "a, b, c" ("|" between forms); else NULL */
  const char *def;     /* the default as one would write it ("1.5"; a computed one in words); NULL: none */
  const char *unit;    /* "MPa", "s", "deg", "1/s", "length", "force" ...; NULL: none */
  const char *help;    /* one line */
} KeyDecl;

typedef struct {
  const KeyDecl *decl;
  int            n;
  const char    *kind_names[4];   /* the name of kind bit k: "fe", "point" */
  const char    *alias_lists[4];  /* root lists whose items are declared under alias */
  const char    *alias;           /* "{stage}" */
  const char    *source;          /* where the table is written, for the message about an undeclared key */
} KeyTable;

/* From now on the document's keys are read against table t as a scene of kind (one bit): yd_get tells it every
 * key asked for. */
void keys_attach(YdDoc *doc, const KeyTable *t, unsigned kind);

/* The declaration of key of mapping map for the document's kind; NULL if none (or no table attached). */
const KeyDecl *keys_find(const YdNode *map, const char *key);
/* Whether map's key is declared for the document's kind (a reader asks before it reads a key some kinds lack). */
int keys_apply(const YdNode *map, const char *key);

/* Typed reads of map's key by its declaration. Absent: the declared default (when it is a number or a word; else
 * *v is left as the reader set it), or, for a required key, "key 'PATH' is missing". Present: its type, then its
 * range or choices, each mistake with file, line, key path and value. 0, or 1 with err filled. *node_out (may be
 * NULL): the value's node, NULL if absent. */
int keys_number(const YdDoc *doc, YdNode *map, const char *key, double *v, YdNode **node_out, char *err, size_t errlen);
int keys_integer(const YdDoc *doc, YdNode *map, const char *key, int *v, YdNode **node_out, char *err, size_t errlen);
int keys_bool(const YdDoc *doc, YdNode *map, const char *key, int *v, YdNode **node_out, char *err, size_t errlen);
/* *v: the word; *index: its place in the declared choices (either may be NULL). */
int keys_word(const YdDoc *doc, YdNode *map, const char *key, const char **v, int *index, YdNode **node_out, char *err,
              size_t errlen);

/* The range of a declaration as a message says it ("> 0", "a number from 1.2 to 8", "0 < tol < 1", "1 or 2"); "" if
 * it has none. */
const char *keys_range_text(const KeyDecl *d, char *buf, size_t n);

/* After a reader has read mapping map: a key it never asked for is an error: "unknown key 'PATH' (misspelt
 * 'X'?): allowed keys here are ..." (the declared ones), "key 'PATH' is one of KIND scenes, not of this one", or,
 * for a declared key the reader did not need, "key 'PATH' does not apply here" with why (may be NULL) and its help.
 * 0, or 1 with err filled. Without a table: "unknown key 'PATH'". */
int keys_check_unused(const YdDoc *doc, const YdNode *map, const char *why, char *err, size_t errlen);
/* After the whole scene is read: keys_check_unused over every mapping, and the first key a reader asked for without
 * a declaration (a driver error, naming the table's source). 0, or 1 with err filled. */
int keys_check_document(const YdDoc *doc, char *err, size_t errlen);

/* The table as text (one key a line: path, scene kinds, type and range or choices, default, unit, help; for
 * -help) or as a Markdown table (docs/driver.md, "Key reference"). */
void keys_write(const KeyTable *t, int markdown, FILE *fp);
/* The same text into buf (for -help, before PETSc starts); returns the length it needed. */
size_t keys_text(const KeyTable *t, char *buf, size_t n);

#endif
