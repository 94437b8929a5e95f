/* How a segment or stage is divided into steps: a fixed count (equal, or growing geometrically), or
 * adaptive steps that follow the UMAT's PNEWDT within bounds. Shared by the point and FE drivers. */
#ifndef STEP_CONTROL_H
#define STEP_CONTROL_H

#include "../io/yaml_doc.h"

typedef struct {
  int    adaptive, count;
  double ratio;                     /* fixed steps: dt_{k+1} = ratio dt_k (1: equal steps) */
  double first, min, max, growth;   /* adaptive steps */
} StepControl;

/* steps: {count: N, spacing: linear | geometric, ratio: r}  or  {adaptive: true, first, min, max, growth}.
 * node may be NULL (one step). Returns 0, or 1 with err naming file, line and key. */
int step_control_read(const YdDoc *doc, YdNode *node, const char *path, double duration, StepControl *sc, char *err,
                      size_t errlen);
/* The first step, and the k-th planned fixed step (k from 0), for a segment of this duration. */
double step_control_planned(const StepControl *sc, double duration, int k);
/* The step after an accepted one of length dt whose UMAT calls suggested pnewdt (adaptive steps). */
double step_control_next(const StepControl *sc, double dt, double pnewdt);

#endif
