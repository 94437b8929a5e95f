/* A material-point scene (one integration point, mixed stress/strain control): its segments, how each
 * component is controlled, how steps are taken, and when a segment ends. Read from YAML. */
#ifndef POINT_SCENE_H
#define POINT_SCENE_H

#include "../io/yaml_doc.h"
#include "../material/umat_call.h"
#include "../scene/stage.h"

typedef enum { EQ_STRESS, EQ_STRAIN, EQ_LINEAR } EquationKind;

/* One of the six equations that fix the strain increment of a step (component order 11 22 33 12 13 23;
 * strains engineering). EQ_LINEAR: a.eps + b.sigma = value (value NAN: keep the segment-start value). */
typedef struct {
  EquationKind kind;
  double       target;      /* stress or strain at the end of the segment (or table-driven) */
  double       a[6], b[6], value;
  int          table_column; /* >= 0: target from the segment's table, that column */
  double       table_factor;
} Equation;

/* A segment: the stage of every scene kind (name, duration, instant, steps, until, creep: scene/stage.h) and how
 * the point's six components are controlled in it. */
typedef struct {
  Stage     stage;
  Equation  eq[6];
  int       axis;            /* for the plots: the loading axis (0, 1, 2) of a creep segment */
  /* table-driven targets (lab data): time and columns */
  int       table_rows, table_cols;
  double   *table_time, *table;  /* table[row * table_cols + col] */
} Segment;

typedef struct {
  char         name[128];
  char         outdir[512];
  UmatMaterial mat;
  double       stress0[6];
  double       statev0[UMAT_MAX_STATEV];
  int          nseg;
  Segment     *seg;
  int          check_tangent;  /* compare DDSDDE with central differences at every step */
  int          progress_every;
  int          replay_step;    /* > 0: write a replay scene of the UMAT call that ended this step */
} PointScene;

int  point_scene_read(YdDoc *doc, PointScene *sc, char *err, size_t errlen);
void point_scene_free(PointScene *sc);
int  point_component(const char *key); /* "11" ... "23" -> 0..5, else -1 */

#endif
