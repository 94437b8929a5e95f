/* driver: runs one scene file.   driver -input input/<scene>.yaml [PETSc options]
 *
 * The scene's 'scene:' key says what it is: 'point' (one material point under mixed stress/strain
 * control), 'replay' (one recorded UMAT call), or, with the FE driver (issue #4), a finite-element scene. */
#include <petscsys.h>
#include <string.h>

#include "../io/yaml_doc.h"
#include "../point/point_run.h"
#include "../point/replay.h"
#include "../point/sweep.h"
#include "../fe/fe_run.h"

static const char help[] =
  "driver -input SCENE.yaml: runs a scene of the Cam-Clay IX project.\n"
  "Finite-element scenes (scene: fe; mpiexec -n N driver ...):\n"
  "  mesh: {geometry: X.geo | file: X.msh, parameters: {NAME: value}, order: 1 | 2,\n"
  "         kinematics: 3d | plane_strain | axisymmetric, thickness}\n"
  "  material: (as below)   phi: {mean, std, min, max, seed}\n"
  "  initial: {stress: [6 values, both frames], pressure: {GROUP: p}}\n"
  "  boundary: {fixed: [{group: G, components: [x, y, z]}], pressure: [G, ...]}\n"
  "  stages: - {name, duration, load: linear | instant, pressure: {G: p}, steps: {...}, until: {evp_rate_below}, creep}\n"
  "  output: {directory, fields_every: N}\n"
  "  options: -checkpoint_every N, -restart, -max_steps N, any PETSc SNES/KSP/PC option\n"
  "Scene keys (material point, scene: point):\n"
  "  scene: point | replay       name: text      ntens: 6 | 4     units: {stress: MPa, time: s}\n"
  "  material: {umat: camclay9, name, props: woodford | [list], set: {phi: .., eta_soft: .., tol: ..},\n"
  "             bedding_angle: deg | normal: [n1, n2, n3], nstatv}\n"
  "  initial: {stress: [6 values, both frames], statev: [list]}\n"
  "  output: {directory: out/point/NAME, progress_every: N}     check_tangent: true|false\n"
  "  segments: - {name, duration, load: linear | instant,\n"
  "               control: {11: {stress: v} | {strain: v} | {strain: {column: c, factor: f}}, ..., others: {...}},\n"
  "               constraints: [{replaces: 22, strain: {11: 1, 22: 1, 33: 1}, stress: {...}, value: v}],\n"
  "               steps: {count: N, spacing: linear | geometric, ratio: r} | {adaptive: true, first, min, max, growth},\n"
  "               until: {evp_rate_below: v | q_above: v | q_below: v | p_above: v}, creep: bool, axis: 33,\n"
  "               table: {file: data.csv, time: column, time_factor: f}}\n"
  "Extremes sweep (scene: sweep): material, matrix: {dt, eta, strain_increment, bedding_angle, phi},\n"
  "  reference_steps, output: {directory}\n"
  "Replay (scene: replay): call: {ntens, nstatv, props, stress, statev, stran, dstran, time, dtime},\n"
  "  expected: {pnewdt, stress, statev, ddsdde} (checked bit for bit)\n";

int main(int argc, char **argv) {
  char      input[PETSC_MAX_PATH_LEN] = "";
  PetscBool given = PETSC_FALSE, check = PETSC_FALSE, help_asked = PETSC_FALSE;
  char      err[2048], outdir[PETSC_MAX_PATH_LEN] = "";
  PetscInt  replay_step = 0;

  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-help", &help_asked));
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Scene driver", NULL);
  PetscCall(PetscOptionsString("-input", "scene file (YAML)", NULL, input, input, sizeof input, &given));
  PetscCall(PetscOptionsBool("-check_tangent", "compare DDSDDE with central differences at every step", NULL, check,
                             &check, NULL));
  PetscCall(PetscOptionsString("-output_dir", "write the output here instead of the scene's output.directory", NULL,
                               outdir, outdir, sizeof outdir, NULL));
  PetscCall(PetscOptionsInt("-write_replay_at_step", "write a replay scene of the UMAT call of this step", NULL,
                            replay_step, &replay_step, NULL));
  PetscOptionsEnd();
  if (!given) {
    if (!help_asked) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "driver: give a scene: driver -input input/<scene>.yaml (-help lists the keys)\n"));
    PetscCall(PetscFinalize());
    return help_asked ? 0 : 2;
  }
  YdDoc doc;
  int   rc = 0;
  if (yd_load(input, &doc, err, sizeof err)) {
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "driver: %s\n", err));
    PetscCall(PetscFinalize());
    return 2;
  }
  const char *kind = NULL;
  if (yd_string(&doc, yd_get(doc.root, "scene"), "scene", &kind, err, sizeof err)) {
    rc = 2;
  } else if (!strcmp(kind, "point")) {
    PointScene   sc;
    PointSummary sum;
    if (point_scene_read(&doc, &sc, err, sizeof err)) rc = 2;
    else {
      if (check) sc.check_tangent = 1;
      if (outdir[0]) snprintf(sc.outdir, sizeof sc.outdir, "%s", outdir);
      sc.replay_step = (int)replay_step;
      rc = point_run(&sc, &sum, err, sizeof err);
      PetscCall(PetscPrintf(PETSC_COMM_WORLD,
                            "point scene %s: %d steps, %d cutbacks, worst control residual %.2e (relative), %.4f s%s -> %s/history.csv\n",
                            sc.name, sum.steps, sum.cutbacks, sum.worst_control_error, sum.wall, rc ? ", FAILED" : "",
                            sc.outdir));
      if (sc.check_tangent)
        PetscCall(PetscPrintf(PETSC_COMM_WORLD, "tangent check: worst |DDSDDE - central differences| / |DDSDDE| = %.3e\n",
                              sum.worst_tangent_error));
      point_scene_free(&sc);
    }
  } else if (!strcmp(kind, "fe")) {
    rc = fe_run(&doc, outdir, err, sizeof err);
  } else if (!strcmp(kind, "sweep")) {
    rc = sweep_run(&doc, outdir, err, sizeof err);
  } else if (!strcmp(kind, "replay")) {
    rc = replay_run(&doc, err, sizeof err);
  } else {
    snprintf(err, sizeof err, "%s:%d: key 'scene': expected fe, point, replay or sweep, got '%s'",
             doc.file, yd_key_line(doc.root, "scene"), kind);
    rc = 2;
  }
  if (rc) PetscCall(PetscPrintf(PETSC_COMM_WORLD, "driver: %s\n", err));
  yd_free(&doc);
  PetscCall(PetscFinalize());
  return rc;
}
