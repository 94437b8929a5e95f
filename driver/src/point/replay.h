/* A replay scene: one UMAT call with its exact arguments (written by the drivers when a call fails for
 * good), run again; with an 'expected' block the results must match it bit for bit. */
#ifndef REPLAY_H
#define REPLAY_H

#include "../io/yaml_doc.h"

/* Returns 0 when the call ran (and matched 'expected', if given); 1 with err filled otherwise. */
int replay_run(YdDoc *doc, char *err, size_t errlen);

#endif
