/* The keys of the scenes: one declaration each (io/keydecl.h), in scene_keys.c. The readers of FE, indentation and
 * point scenes (fe/fe_scene.c, contact/indent_scene.c, point/point_scene.c, scene/stage.c, scene/time_function.c,
 * material/material_input.c) read their keys through it; -help and docs/driver.md's key reference are written
 * from it (driver -key_reference; tests/driver/test_scene_keys.py --write). */
#ifndef SCENE_KEYS_H
#define SCENE_KEYS_H

#include "../io/keydecl.h"

enum {
  SCENE_FE    = 1, /* scene: fe (with an indenter: indentation) */
  SCENE_POINT = 2, /* scene: point */
  SCENE_SWEEP = 4  /* scene: sweep (its material block; its other keys: app/sweep.c) */
};

extern const KeyTable scene_keys;

/* Attach the table to a scene of kind (a SCENE_ bit). */
void scene_keys_attach(YdDoc *doc, unsigned kind);

#endif
