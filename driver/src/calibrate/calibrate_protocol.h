/* The data's own protocol (its stages) and the forward scene that follows it (drive: data). */
#ifndef CALIBRATE_PROTOCOL_H
#define CALIBRATE_PROTOCOL_H

#include "../io/yaml_doc.h"
#include "calibrate_run.h"

/* The data's own stages (from data.columns.stage, or from the load curve: loading,
 * hold at the peak, unloading), and the forward scene made to follow them (drive: data). */
int  cal_protocol_find(const YdDoc *doc, CalRun *run, char *err, size_t errlen);
/* One line per stage into buf (the log). */
void cal_protocol_describe(const CalRun *run, char *buf, size_t n);
/* Write the forward scene (and reference) driven by the data's history into dir: run->driven(_reference). */
int  cal_protocol_write(CalRun *run, const char *dir, char *err, size_t errlen);

#endif
