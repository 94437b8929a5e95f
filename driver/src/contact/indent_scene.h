/* The indenter of a finite-element scene: its shape and place (top-level key 'indenter') and what it
 * does in each stage (key 'indenter' of a stage): a load (a number reached linearly at the stage's end,
 * {exp: {P0, k}} = P0 exp(k t) in the stage time, a measured history {table: {file, time, value,
 * time_factor, factor}} in the stage time, or 'hold'), or a depth (depth control: a number reached
 * linearly, or a table), and an optional end event {until: {depth: h}} or {until: {load: P}} on which the
 * stage's last step lands. */
#ifndef INDENT_SCENE_H
#define INDENT_SCENE_H

#include "../fe/fe_scene.h"
#include "indenter_shape.h"

typedef enum { IND_LOAD_RAMP, IND_LOAD_EXP, IND_LOAD_HOLD, IND_DEPTH_RAMP, IND_LOAD_TABLE, IND_DEPTH_TABLE } IndentLoadKind;

typedef struct {
  IndentLoadKind kind;
  TimeFn         fn;            /* the load (the model's: 1/copies of the whole indenter's) or the depth in the stage time
                                   (scene/time_function.h) */
  double         until_depth;   /* > 0: the stage ends when the depth reaches it */
  double         until_load;    /* > 0: ... when the load (the model's) reaches it (exp: at a time known in advance) */
} IndentStage;

typedef struct {
  IndenterShape shape;
  char          contact_group[64];
  char          file[512];      /* the scene file, for messages */
  double        c;              /* complementarity constant (eq. 13); 0: E / (contact-node spacing) */
  double        copies;         /* the whole indenter's load over the model's (key 'copies': 2 for a half model,
                                   6 for a 60-degree sector; 1 otherwise). The scene's loads and the history's
                                   are the whole indenter's; the stages' targets are stored as the model's. */
  IndentStage   stage[MAXSTAGES];
} IndentScene;

/* Read sc->indenter and every stage's indenter key. Returns 0, or 1 with err naming file, line, key. */
int indent_scene_read(YdDoc *doc, const FeScene *sc, IndentScene *is, char *err, size_t errlen);
/* The indenter's load (force control) or depth (depth control) at stage time ts; start: its value at the
 * stage's start; lambda: the fraction of the stage done. */
double indent_stage_value(const IndentStage *st, double start, double lambda, double ts);
/* Depth control (a depth ramp or table)? */
static inline int indent_stage_depth_control(const IndentStage *st) { return st->kind == IND_DEPTH_RAMP || st->kind == IND_DEPTH_TABLE; }
/* The stage time at which the stage's load first reaches P (exp, ramp from start, table), or -1 if never within
 * the stage's duration. */
double indent_stage_time_of_load(const IndentStage *st, double start, double duration, double P);

#endif
