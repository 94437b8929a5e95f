/* driver: runs one scene file.   driver -input input/<scene>.yaml [PETSc options]
 *
 * The scene's 'scene:' key says what it is: 'point' (one material point under mixed stress/strain
 * control), 'replay' (one recorded UMAT call), or, with the FE driver (issue #4), a finite-element scene. */
#include <petscsys.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "../calibrate/calibrate.h"
#include "../contact/contact_options.h"
#include "../io/options.h"
#include "../io/keydecl.h"
#include "../io/yaml_doc.h"
#include "../material/material_input.h"
#include "../scene/scene_keys.h"
#include "../stepping/fe_stepper.h"
#include "../stepping/point_stepper.h"
#include "blas_check.h"
#include "fe_adapt.h"
#include "fe_app.h"
#include "fe_run.h"
#include "run_summary.h"
#include "../point/replay.h"
#include "sweep.h"

/* -help: what the driver runs, every key of the FE, indentation and point scenes from their declarations
 * (scene/scene_keys.c), the other kinds' keys, then (PETSc) every option with its range and default. */
static const char help_head[] =
  "driver -input SCENE.yaml: runs a scene of the Cam-Clay IX project; the 'scene:' key says which kind.\n"
  "Keys of FE (scene: fe; with an indenter: indentation; mpiexec -n N driver ...) and point scenes (scene: point), one a\n"
  "line: its path ({stage}: an item of 'stages' (fe) or of 'segments' (point); []: a list's item; *: a name of your\n"
  "choosing) [the scenes that read it], its type with its range or choices; its default; its unit. What it is.\n"
  "Input paths are relative to the scene file's folder, outputs to the working directory (docs/driver.md, Paths; its\n"
  "Key reference is this list).\n";
static const char help_tail[] =
  "Extremes sweep (scene: sweep): material (above), matrix: {dt, eta, strain_increment, bedding_angle, phi},\n"
  "  reference_steps, output: {directory}\n"
  "Calibration (scene: calibrate; docs/calibrate.md): parameters: - {name: PROPS name, start, min, max, scale: log},\n"
  "  runs: - {name, scene: forward.yaml, drive: data | scene, reference: full.yaml | none, set: {NAME: v},\n"
  "          options: '-...', data: {file, columns: {time, load, depth, value, stage}, factors: {...}, time_from},\n"
  "          residuals: - {kind: loading | hold | unloading | series, stage, weight, model: column, relative}}\n"
  "  refine: auto | yes | no, accept: [rows, scale, bound], output: {directory}\n"
  "  TAO options -tao_type (pounders), -tao_max_funcs, -tao_pounders_delta, ...; -calibrate_dry_run\n"
  "Replay (scene: replay): call: {ntens, nstatv, props, stress, statev, stran, dstran, time, dtime},\n"
  "  expected: {pnewdt, stress, statev, ddsdde} (checked bit for bit)\n"
  "Options: each with its range or choices in [brackets] and its default as <now : formerly>.\n";
static char help[65536];

static void make_help(void) {
  size_t n = (size_t)snprintf(help, sizeof help, "%s", help_head);
  n += keys_text(&scene_keys, help + n, sizeof help - n);
  if (n < sizeof help) snprintf(help + n, sizeof help - n, "%s", help_tail);
}

/* The driver's own options, besides the modules' below. */
typedef struct {
  char      input[PETSC_MAX_PATH_LEN], outdir[PETSC_MAX_PATH_LEN];
  PetscBool given, check;
  PetscInt  replay_step, key_reference;
} MainOptions;

static PetscErrorCode main_options(MainOptions *m) {
  PetscBool          traceback = PETSC_FALSE, dry = PETSC_FALSE; /* dry, load_draws: read by calibrate.c */
  PetscInt           load_draws = CAL_LOAD_DRAWS;
  const char *const  forms[]   = {"none", "text", "markdown"};
  PetscFunctionBeginUser;
  PetscCall(PetscMemzero(m, sizeof *m));
  PetscOptionsBegin(PETSC_COMM_WORLD, NULL, "Scene driver", NULL);
  PetscCall(options_string(PetscOptionsObject, "-input", "scene file (YAML)", m->input, m->input, sizeof m->input, &m->given));
  PetscCall(options_bool(PetscOptionsObject, "-check_tangent", "point scenes: compare DDSDDE with central differences at every step",
                         m->check, &m->check, NULL));
  PetscCall(options_string(PetscOptionsObject, "-output_dir", "write the output here instead of the scene's output.directory", m->outdir,
                           m->outdir, sizeof m->outdir, NULL));
  PetscCall(options_int(PetscOptionsObject, "-write_replay_at_step", "point scenes: write a replay scene of the UMAT call of this step (0: none)",
                        0, 0, PETSC_MAX_INT, &m->replay_step, NULL));
  PetscCall(options_bool(PetscOptionsObject, "-error_traceback", "print PETSc's traceback of an error (else only its message)", traceback,
                         &traceback, NULL));
  PetscCall(options_bool(PetscOptionsObject, "-calibrate_dry_run",
                         "calibrate scenes: write the forward scenes that follow the data, say the stages found, run nothing", dry, &dry,
                         NULL));
  PetscCall(options_int(PetscOptionsObject, "-calibrate_load_draws",
                        "calibrate scenes: forward runs at the fit for a fitted load history's share of the standard errors (0: none)",
                        CAL_LOAD_DRAWS, 0, CAL_LOAD_DRAWS_MAX, &load_draws, NULL));
  PetscCall(options_elist(PetscOptionsObject, "-key_reference",
                          "print every scene key's declaration (markdown: docs/driver.md's Key reference) and run nothing", forms, 3, 0,
                          &m->key_reference, NULL));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

/* Every module's options block, once before anything is read or run: -help lists them all, a value that does
 * not parse (an integer out of its range, a word for a number) stops here, and every option of the driver is
 * known, so that a misspelt one is refused now rather than warned about at the end of a long run. */
static PetscErrorCode declare_options(MainOptions *m) {
  RunnerOptions   run;
  FeSolverOptions fe;
  IndentOptions   indent;
  char            set[2048];
  PetscBool       given;
  PetscFunctionBeginUser;
  PetscCall(main_options(m));
  PetscCall(app_runner_options(&run));
  PetscCall(fe_solver_options(PETSC_COMM_WORLD, &fe));
  PetscCall(indent_options(PETSC_COMM_WORLD, &indent));
  PetscCall(material_options(set, sizeof set, &given));
  PetscInt  levels = 0;
  PetscReal growth = 2;
  PetscCall(fe_adapt_declare(&levels, &growth, &given, &given));
  PetscFunctionReturn(0);
}

/* Prefixes the driver keeps for its modules beyond those of the options declared (calibrate: TAO's own). */
static const char *const reserved_prefixes[] = {"-calibrate_", NULL};

/* Options given but never read (a misspelling, or one the scene's kind ignores): a warning each, as
 * PETSc's -options_left does. */
static PetscErrorCode warn_unused_options(void) {
  PetscInt  n;
  char    **names, **values;
  PetscBool left = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasName(NULL, NULL, "-options_left", &left)); /* PETSc reports them itself then */
  if (left) PetscFunctionReturn(0);
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt k = 0; k < n; k++)
    if (!options_set_by_driver(names[k])) /* a default the driver set (-indent_mat_mumps_icntl_14) was not the user's */
      PetscCall(PetscFPrintf(PETSC_COMM_WORLD, PETSC_STDERR, "driver: warning: option -%s%s%s was given but never used (misspelt, or not "
                             "read by this kind of scene; driver -help lists them)\n", names[k], values[k] ? " " : "", values[k] ? values[k] : ""));
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscFunctionReturn(0);
}

/* The message of a failed run: the module's own, else PETSc's (the innermost error, without a traceback;
 * bad_option: only its specific message, one of the driver's about an option). The last word: its own PETSc
 * calls have no one to report to. */
static void print_failure(int rc, const char *err, PetscBool bad_option) {
  const char *text = NULL;
  char       *specific = NULL;
  if (err[0]) {
    PetscFPrintf(PETSC_COMM_WORLD, PETSC_STDERR, "driver: %s\n", err);
    return;
  }
  PetscErrorMessage(rc, &text, &specific);
  if (bad_option && specific && specific[0]) {
    PetscFPrintf(PETSC_COMM_WORLD, PETSC_STDERR, "driver: %s; nothing was run\n", specific);
    return;
  }
  PetscBool said = specific && specific[0] && strcmp(specific, " ") ? PETSC_TRUE : PETSC_FALSE;
  PetscFPrintf(PETSC_COMM_WORLD, PETSC_STDERR, "driver: %s%s%s (-error_traceback shows where)\n", said ? specific : "",
               said && text ? ": " : "", text ? text : said ? "" : "a PETSc error");
}

static PetscErrorCode point_summary(const PointScene *sc, const PointSummary *sum, int rc) {
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "point scene %s: %d steps, %d cutbacks, worst control residual %.2e (relative), %.4f s%s -> %s/history.csv\n",
                        sc->name, sum->steps, sum->cutbacks, sum->worst_control_error, sum->wall, rc ? ", FAILED" : "", sc->outdir));
  if (sc->check_tangent)
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "tangent check: worst |DDSDDE - central differences| / |DDSDDE| = %.3e\n", sum->worst_tangent_error));
  PetscFunctionReturn(0);
}

/* A material-point scene: its run, then its summary (also after a failure). The run's status (docs/driver.md, "Error codes"). */
static int run_point(YdDoc *doc, const char *outdir, PetscBool check, PetscInt replay_step, char *err, size_t errlen) {
  PointScene    sc;
  PointSummary  sum;
  RunnerOptions opt;
  if (point_scene_read(doc, &sc, err, errlen)) return 2;
  if (check) sc.check_tangent = 1;
  if (outdir[0] && snprintf(sc.outdir, sizeof sc.outdir, "%s", outdir) >= (int)sizeof sc.outdir) {
    snprintf(err, errlen, "option -output_dir '%.200s...': a path of %zu characters; expected at most %d", outdir, strlen(outdir),
             (int)sizeof sc.outdir - 1);
    point_scene_free(&sc);
    return 2;
  }
  sc.replay_step      = (int)replay_step;
  PetscErrorCode ierr = app_runner_options(&opt);
  int            rc   = 0;
  if (!ierr) {
    RunnerSummary rs;
    clock_t       cpu0 = clock();
    memset(&rs, 0, sizeof rs);
    opt.scene_file = doc->file, opt.summary = &rs;
    rc             = point_run(&sc, &opt, &sum, err, errlen);
    ierr           = point_summary(&sc, &sum, rc);
    rs.failed      = rs.failed || rc;
    /* summary.json also after a failure once the run got past its set-up (not after bad input, rc 2), as
       summary.json.part while the run has no results of its own; its own failure only when the run went well */
    char   e2[512], msg[2048];
    RunEnd end = {rc ? msg : NULL, -1, rs.replaced};
    if (rc) run_summary_error(rc, err, msg, sizeof msg);
    if (sc.outdir[0] && run_summary_due(rc, &rs) && run_summary_point(&sc, &sum, &rs, (double)(clock() - cpu0) / CLOCKS_PER_SEC, &end, e2, sizeof e2) && !rc)
      rc = 1, snprintf(err, errlen, "%s", e2);
  }
  point_scene_free(&sc);
  return rc ? rc : stage_runner_status(ierr, err);
}

static int run_scene(YdDoc *doc, const char *outdir, PetscBool check, PetscInt replay_step, char *err, size_t errlen) {
  const char *kind = NULL;
  if (yd_string(doc, yd_get(doc->root, "scene"), "scene", &kind, err, errlen)) return 2;
  if (!strcmp(kind, "point")) return run_point(doc, outdir, check, replay_step, err, errlen);
  if (!strcmp(kind, "fe")) return fe_app_run(doc, outdir, err, errlen);
  if (!strcmp(kind, "sweep")) { /* its material block by the scene's declarations */
    scene_keys_attach(doc, SCENE_SWEEP);
    return sweep_run(doc, outdir, err, errlen);
  }
  if (!strcmp(kind, "replay")) return replay_run(doc, err, errlen);
  if (!strcmp(kind, "calibrate")) return calibrate_run(doc, outdir, err, errlen);
  snprintf(err, errlen, "%s:%d: key 'scene': expected calibrate, fe, point, replay or sweep, got '%s'", doc->file,
           yd_key_line(doc->root, "scene"), kind);
  return 2;
}

int main(int argc, char **argv) {
  char        err[2048] = "";
  PetscBool   help_asked = PETSC_FALSE, traceback = PETSC_FALSE;
  MainOptions m;

  make_help();
  /* Open MPI's MPI-IO (OMPIO) opens every file (the HDF5 fields and checkpoints) with a shared-file-pointer component,
     whose 'sm' one keeps a named POSIX semaphore per file name in /dev/shm (sem.OMPIO_<name>). A run killed by -9
     while it held one leaves it locked, and every later run that opens a file of that name, in any folder
     (checkpoint.64.h5.tmp), then waits forever (test_stage_runner.py::test_restart_after_a_locked_semaphore). The
     driver uses no shared file pointers: that component is left out, unless the user set the parameter. */
  setenv("OMPI_MCA_sharedfp", "^sm", 0);
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-help", &help_asked));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-error_traceback", &traceback));
  /* Errors come back to here and are reported once, by their message (no traceback of 40 lines). */
  if (!traceback) PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  PetscErrorCode ierr = declare_options(&m);
  int            rc   = 0;
  PetscBool      bad  = PETSC_FALSE;
  if (ierr) rc = 2, print_failure((int)ierr, "", PETSC_TRUE);
  else if ((ierr = options_check_unknown(NULL, 0, reserved_prefixes, NULL, err, sizeof err, &bad)) || bad) rc = 2, print_failure((int)ierr, err, PETSC_TRUE);
  else if (m.key_reference) keys_write(&scene_keys, m.key_reference == 2, stdout);
  else if (!m.given) {
    if (!help_asked) PetscFPrintf(PETSC_COMM_WORLD, PETSC_STDERR, "driver: give a scene: driver -input input/<scene>.yaml (-help lists the keys)\n");
    rc = help_asked ? 0 : 2;
  } else if ((ierr = options_forget_reads()) || (ierr = main_options(&m))) /* main's own are read (the others by the run) */
    rc = 1, print_failure((int)ierr, "", PETSC_FALSE);
  else {
    YdDoc doc;
    if (yd_load(m.input, &doc, err, sizeof err)) rc = 2;
    else {
      rc = run_scene(&doc, m.outdir, m.check, m.replay_step, err, sizeof err);
      yd_free(&doc);
      if (rc != 2 && (ierr = blas_check_note(PETSC_COMM_WORLD)) && !rc) rc = (int)ierr; /* a run was made: say if its BLAS was slow */
    }
    if (rc) print_failure(rc, err, PETSC_FALSE);
    if (rc > 2) rc = 1; /* a PETSc error code: the run failed */
    if (rc != 2 && (ierr = warn_unused_options()) && !rc) rc = 1, print_failure((int)ierr, "", PETSC_FALSE); /* not after a scene error: nothing was run */
  }
  if (!traceback) PetscPopErrorHandler();
  PetscCall(PetscFinalize());
  return rc;
}
