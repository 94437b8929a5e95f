/* The functions on a calibrate run alone (calibrate_run.h). */
#include "calibrate_run.h"

#include <stdlib.h>

static const char *kind_names[] = {"loading", "hold", "unloading", "series"};
const char        *cal_kind_name(CalKind k) { return kind_names[k]; }

const char *cal_run_scene(const CalRun *run, int reference) {
  if (reference) return run->drive ? run->driven_reference : run->reference;
  return run->drive ? run->driven : run->scene;
}

void cal_run_free(CalRun *run) {
  free(run->data), free(run->row_stage), free(run->knot_t), free(run->knot_p);
  for (int c = 0; c < run->ncurve; c++) {
    free(run->curve[c].x), free(run->curve[c].y), free(run->curve[c].t), free(run->curve[c].model);
  }
}
