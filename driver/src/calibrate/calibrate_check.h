/* Checks of the data against the first forward run that catch a wrong fit at the start. */
#ifndef CALIBRATE_CHECK_H
#define CALIBRATE_CHECK_H

#include "calibrate_run.h"

/* Checks that catch a wrong fit at the start (accept: the names of those accepted, CAL_ACCEPT_*). */
/* Every data row in a forward stage, every block with the rows of its kind (indentation data). */
int cal_check_rows(const CalRun *run, const char *dir, int accept, char *err, size_t errlen);
/* The data's scale against the first forward run's (a factor of 10 apart: a unit): models 0, the loads (from the
 * history, before the residuals); 1, the depths or values (the models at the data, after them). */
int cal_check_scale(const CalRun *run, const char *dir, int accept, int models, char *err, size_t errlen);

#endif
