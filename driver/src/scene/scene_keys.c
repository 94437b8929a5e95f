/* Every key of the FE, indentation and point scenes, declared once (scene_keys.h, io/keydecl.h). A reader that
 * asks for a key not declared here fails every scene that reaches it ("read by the driver without a declaration");
 * docs/driver.md's key reference is this table (tests/driver/test_scene_keys.py). */
#include "scene_keys.h"

#include <math.h>

#include "../material/umat_call.h"
#include "stage.h"

#define FE SCENE_FE
#define PT SCENE_POINT
#define SW SCENE_SWEEP
#define N NAN
#define REQ KEY_REQUIRED
#define GT KEY_LO_OPEN
#define LT KEY_HI_OPEN
#define STR_(x) #x
#define STR(x) STR_(x)

/* A stage table's keys (scene/time_function.h) under P: its value column and factor as help. */
#define TABLE(P, VALUE, FACTOR)                                                                                                       \
  {P ".table.file", FE, KEY_FILE, N, N, REQ, NULL, NULL, NULL, "the CSV file"},                                                       \
  {P ".table.time", FE, KEY_TEXT, N, N, REQ, NULL, NULL, NULL, "its time column (the stage's time, after time_factor)"},              \
  {P ".table.value", FE, KEY_TEXT, N, N, REQ, NULL, NULL, NULL, VALUE},                                                               \
  {P ".table.time_factor", FE, KEY_NUMBER, 0, N, GT, NULL, "1", "s per unit", "the table's time unit in s"},                          \
  {P ".table.factor", FE, KEY_NUMBER, N, N, 0, NULL, "1", NULL, FACTOR}

/* path, kinds, type, lo, hi, flags, choices, default, unit, help */
static const KeyDecl decl[] = {
  {"scene", FE | PT, KEY_WORD, N, N, REQ, "fe, point", NULL, NULL, "the scene's kind (sweep, calibrate and replay scenes: driver -help, docs/calibrate.md)"},
  {"name", FE | PT, KEY_TEXT, N, N, 0, NULL, "fe (point: point)", NULL, "the run's name: the output directory is out/NAME (point: out/point/NAME) unless output.directory says"},
  {"units", FE | PT, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "the units, stated for the reader (the UMAT's are MPa and s)"},
  {"units.*", FE | PT, KEY_TEXT, N, N, 0, NULL, NULL, NULL, "a quantity's unit, stated for the reader (stress: MPa, time: s)"},
  {"ntens", PT, KEY_INTEGER, N, N, 0, "6, 4", "6", NULL, "the point's stress components: 6 (3D) or 4 (plane strain: 11 22 33 12)"},
  {"check_tangent", PT, KEY_BOOL, N, N, 0, NULL, "false", NULL, "compare DDSDDE with central differences of the stress at every step (as -check_tangent)"},

  {"mesh", FE, KEY_MAPPING, N, N, REQ, NULL, NULL, NULL, "the mesh: geometry or file, order, kinematics, thickness, adapt"},
  {"mesh.geometry", FE, KEY_FILE, N, N, 0, NULL, NULL, NULL, "a gmsh .geo, meshed at run time (give geometry or file)"},
  {"mesh.parameters", FE, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "values of the .geo's parameters, each one it defines (Exists(NAME) or DefineConstant; its header lists them)"},
  {"mesh.parameters.*", FE, KEY_NUMBER, N, N, 0, NULL, "the .geo's", "the .geo's", "the value of the .geo's parameter of this name"},
  {"mesh.file", FE, KEY_FILE, N, N, 0, NULL, NULL, NULL, "a .msh in gmsh format 4.1 (give geometry or file)"},
  {"mesh.order", FE, KEY_INTEGER, N, N, 0, "1, 2", "1", NULL, "the elements' order: P1 or P2 (1 or 4 quadrature points per cell)"},
  {"mesh.kinematics", FE, KEY_WORD, N, N, 0, "3d, plane_strain, axisymmetric", "3d", NULL, "3D (NTENS 6) or a 2D mesh (NTENS 4; axisymmetric: x = r >= 0, y = z)"},
  {"mesh.thickness", FE, KEY_NUMBER, 0, N, GT, NULL, "1", "length", "plane strain only: the thickness the forces are per"},
  {"mesh.adapt", FE, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "with mesh.geometry: rerun the scene on meshes made from its error indicator (docs/adapt.md)"},
  {"mesh.adapt.levels", FE, KEY_INTEGER, 1, 8, 0, NULL, "2", NULL, "reruns after the first run (-adapt_levels overrides)"},
  {"mesh.adapt.growth", FE, KEY_NUMBER, 1.2, 8, 0, NULL, "2", NULL, "cells of a level over the previous level's (-adapt_growth overrides)"},
  {"mesh.adapt.tol", FE, KEY_NUMBER, 0, 1, GT | LT, NULL, "none (all levels)", NULL, "stop once every reported quantity's estimated mesh error is below this (relative: 0.01 is 1 %)"},

  {"material", FE | PT | SW, KEY_MAPPING, N, N, REQ, NULL, NULL, NULL, "the UMAT and its PROPS (docs/umat.md)"},
  {"material.umat", FE | PT | SW, KEY_TEXT, N, N, 0, NULL, "camclay9", NULL, "the UMAT linked in: camclay9 (its PROPS by name and checks), or another (elastic: tests/elastic_umat)"},
  {"material.name", FE | PT | SW, KEY_TEXT, N, N, 0, NULL, "CAMCLAY9", NULL, "the material name the UMAT gets (CMNAME)"},
  {"material.props", FE | PT | SW, KEY_FORMS, N, N, REQ, "woodford | a list of numbers", NULL, NULL, "the PROPS: Yin et al. 2021's Woodford shale (Tables 1-2) or the list"},
  {"material.set", FE | PT | SW, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "PROPS overrides by slot name (docs/umat.md; -material_set after it)"},
  {"material.set.*", FE | PT | SW, KEY_NUMBER, N, N, 0, NULL, NULL, "the slot's", "the value of the PROPS slot of this name (phi, M, ..., eta_soft, tol, n1, n2, n3)"},
  {"material.bedding_angle", FE | PT | SW, KEY_NUMBER, N, N, 0, NULL, "3D: the UMAT's e3; 2D: e2", "deg", "the bedding normal's angle to the loading axis (theory.md §4.1); axisymmetric: 0 only"},
  {"material.normal", FE | PT | SW, KEY_NUMBERS, N, N, 0, NULL, "as bedding_angle", NULL, "the bedding normal [n1, n2, n3] itself (PROPS 21-23)"},
  {"material.nstatv", FE | PT | SW, KEY_INTEGER, 0, UMAT_MAX_STATEV, 0, NULL, "camclay9: its diagnostics' count", NULL, "the STATEV slots per point"},

  {"phi", FE, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "the hard-frame fraction as a field over the elements (normal, clipped; the same on any number of ranks)"},
  {"phi.mean", FE, KEY_NUMBER, N, N, REQ, NULL, NULL, NULL, "its mean: 0 <= min <= mean <= max <= 1"},
  {"phi.std", FE, KEY_NUMBER, 0, N, 0, NULL, "0", NULL, "its standard deviation"},
  {"phi.min", FE, KEY_NUMBER, N, N, 0, NULL, "0", NULL, "the smallest value kept (0 <= min <= mean)"},
  {"phi.max", FE, KEY_NUMBER, N, N, 0, NULL, "1", NULL, "the largest value kept (mean <= max <= 1)"},
  {"phi.seed", FE, KEY_INTEGER, N, N, 0, NULL, "1", NULL, "the random seed (phi is a function of it and the cell centroids)"},
  {"phi.correlation_length", FE, KEY_NUMBER, 0, N, 0, NULL, "0", "length", "white noise smoothed by a Gaussian kernel of this length (0: none)"},

  {"initial", FE | PT, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "the initial state"},
  {"initial.stress", FE | PT, KEY_NUMBERS, N, N, 0, NULL, "0", "MPa", "both frames' initial stress, 11 22 33 12 13 23 (point with ntens 4: 4 values)"},
  {"initial.pressure", FE, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "the starting pressure of loaded groups, in equilibrium with initial.stress"},
  {"initial.pressure.*", FE, KEY_NUMBER, N, N, 0, NULL, "0", "MPa", "the starting pressure of this group of boundary.pressure"},
  {"initial.statev", PT, KEY_NUMBERS, N, N, 0, NULL, "the UMAT's start", NULL, "a full initial state (at most nstatv values)"},

  {"boundary", FE, KEY_MAPPING, N, N, REQ, NULL, NULL, NULL, "the supports and the loaded groups"},
  {"boundary.fixed", FE, KEY_LIST, N, N, 0, NULL, NULL, NULL, "groups with fixed displacement components (with mirror: at most 16)"},
  {"boundary.fixed[].group", FE, KEY_TEXT, N, N, REQ, NULL, NULL, NULL, "a physical group of points, edges or faces"},
  {"boundary.fixed[].components", FE, KEY_LIST, N, N, REQ, NULL, NULL, NULL, "1 to 3 of x, y, z (2D: x, y; axisymmetric x = r, y = z)"},
  {"boundary.mirror", FE, KEY_LIST, N, N, 0, NULL, NULL, NULL, "mirror (symmetry) planes u.n = 0, of any orientation"},
  {"boundary.mirror[].group", FE, KEY_TEXT, N, N, REQ, NULL, NULL, NULL, "a flat group of boundary faces (2D: edges) in the plane"},
  {"boundary.mirror[].normal", FE, KEY_NUMBERS, N, N, REQ, NULL, NULL, NULL, "the plane's normal (3 numbers; 2D: 2), not all zero"},
  {"boundary.pressure", FE, KEY_LIST, N, N, 0, NULL, NULL, NULL, "the groups a pressure acts on (the stages give its value)"},
  {"boundary.traction", FE, KEY_LIST, N, N, 0, NULL, NULL, NULL, "the groups a uniform traction acts on (the stages give its vector)"},

  {"indenter", FE, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "a rigid frictionless indenter (an indentation scene; docs/contact.md)"},
  {"indenter.shape", FE, KEY_WORD, N, N, REQ, "berkovich, cone, wedge, sphere, flat_punch", NULL, NULL, "berkovich: 3D; wedge: plane strain; cone: 3D or axisymmetric"},
  {"indenter.half_angle", FE, KEY_NUMBER, 0, 90, GT | LT, NULL, NULL, "deg", "berkovich, cone, wedge: axis to face (give half_angle or tip_angle)"},
  {"indenter.tip_angle", FE, KEY_NUMBER, 0, 180, GT | LT, NULL, NULL, "deg", "berkovich, cone, wedge: face to face, twice half_angle"},
  {"indenter.radius", FE, KEY_NUMBER, 0, N, GT, NULL, NULL, "length", "sphere, flat_punch: the radius (required for them)"},
  {"indenter.rotation", FE, KEY_NUMBER, N, N, 0, NULL, "0", "deg", "berkovich only: its rotation about the axis"},
  {"indenter.tip", FE, KEY_NUMBERS, N, N, 0, NULL, "0", "length", "the tip's position (3 numbers; 2D: 2; axisymmetric: on the axis, x = 0)"},
  {"indenter.contact", FE, KEY_TEXT, N, N, REQ, NULL, NULL, NULL, "the group of faces (2D: edges) that may come into contact"},
  {"indenter.gap", FE, KEY_WORD, N, N, 0, "normal, vertical", "normal", NULL, "the gap: normal to the indenter (current position) or vertical (Sneddon's, Hertz's)"},
  {"indenter.complementarity_c", FE, KEY_NUMBER, 0, N, GT, NULL, "E / contact-node spacing", "MPa/length", "the complementarity constant of eq. 13"},
  {"indenter.copies", FE, KEY_NUMBER, 1, N, 0, NULL, "1", NULL, "a whole number: copies of the model that make the body (2: half model, 6: 60-degree sector; plane strain: 1 or 2; axisymmetric: 1)"},

  {"stages", FE, KEY_LIST, N, N, REQ, NULL, NULL, NULL, "the load stages, 1 to " STR(MAXSTAGES) " ({stage} below)"},
  {"segments", PT, KEY_LIST, N, N, REQ, NULL, NULL, NULL, "the segments, at least one ({stage} below)"},
  {"{stage}.name", FE | PT, KEY_TEXT, N, N, 0, NULL, "stageN, segmentN", NULL, "the stage's name (history, plots, summary.json)"},
  {"{stage}.duration", FE | PT, KEY_NUMBER, N, N, REQ, NULL, NULL, "s", "the stage's duration: > 0, or 0 with load: instant (a range that depends on load)"},
  {"{stage}.load", FE | PT, KEY_WORD, N, N, 0, "instant, linear", "linear", NULL, "the targets reached linearly at the stage's end, or at once (a zero-time step, then held)"},
  {"{stage}.creep", FE | PT, KEY_BOOL, N, N, 0, NULL, "false", NULL, "a creep stage: the plots' time origin"},
  {"{stage}.steps", FE | PT, KEY_MAPPING, N, N, 0, NULL, "one step", NULL, "how the stage is divided: fixed (count, spacing, ratio) or adaptive (adaptive, first, min, max, growth, error)"},
  {"{stage}.steps.count", FE | PT, KEY_INTEGER, 1, N, KEY_TERSE, NULL, "1", NULL, "fixed steps: their number"},
  {"{stage}.steps.spacing", FE | PT, KEY_WORD, N, N, 0, "linear, geometric", "linear (geometric with ratio)", NULL, "fixed steps: equal, or each ratio times the one before"},
  {"{stage}.steps.ratio", FE | PT, KEY_NUMBER, 0, N, GT, NULL, "1.05", NULL, "geometric fixed steps: a step's length over the previous one's"},
  {"{stage}.steps.adaptive", FE | PT, KEY_BOOL, N, N, 0, NULL, "false", NULL, "steps that follow the error measure"},
  {"{stage}.steps.first", FE | PT, KEY_NUMBER, 0, N, GT, NULL, "duration / 100", "s", "adaptive: the first step"},
  {"{stage}.steps.min", FE | PT, KEY_NUMBER, 0, N, GT, NULL, "1e-12 max(duration, 1)", "s", "adaptive: the shortest step (a step that would be shorter stops the run)"},
  {"{stage}.steps.max", FE | PT, KEY_NUMBER, N, N, 0, NULL, "duration", "s", "adaptive: the longest step (>= min)"},
  {"{stage}.steps.growth", FE | PT, KEY_NUMBER, 1, N, 0, NULL, "1.5", NULL, "adaptive: at most this times the previous step"},
  {"{stage}.steps.error", FE | PT, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "adaptive: the error measure and its tolerance (docs/driver.md, Error measures)"},
  {"{stage}.steps.error.measure", FE | PT, KEY_WORD, N, N, 0, "worst_point, volume, output", "worst_point", NULL, "the UMAT's own (PNEWDT), the volume norm of the vp rate change, or what the scene reports"},
  {"{stage}.steps.error.tol", FE | PT, KEY_NUMBER, 0, 1, GT | LT, NULL, "worst_point: PROPS tol", NULL, "the tolerance (required with volume and output)"},
  {"{stage}.steps.error.relative_to", FE | PT, KEY_WORD, N, N, 0, "step, stage", "step", NULL, "output: the error relative to the step's increment, or to the larger of it and its share of the stage's mean change so far"},
  {"{stage}.steps.error.floor", FE | PT, KEY_NUMBER, 0, 1, LT, NULL, "0 (none)", NULL, "output: the increment the error is relative to is at least this share of the stage's change so far"},
  {"{stage}.until", FE | PT, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "an end event, one of its keys (an indentation stage's indenter.until, not both)"},
  {"{stage}.until.evp_rate_below", FE | PT, KEY_NUMBER, 0, N, GT, NULL, NULL, "1/s", "end after the first step whose volume-mean viscoplastic strain rate is below this"},
  {"{stage}.until.q_above", FE | PT, KEY_NUMBER, 0, N, GT, NULL, NULL, "MPa", "end when the (volume-mean) deviatoric stress q reaches this (landed on within 1e-5)"},
  {"{stage}.until.q_below", FE | PT, KEY_NUMBER, N, N, 0, NULL, NULL, "MPa", "end when q falls to this"},
  {"{stage}.until.p_above", FE | PT, KEY_NUMBER, 0, N, GT, NULL, NULL, "MPa", "end when the (volume-mean) mean stress p reaches this"},
  {"{stage}.output", FE, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "fields at chosen stage times"},
  {"{stage}.output.times", FE, KEY_NUMBERS, N, N, 0, NULL, NULL, "s", "increasing stage times in (0, duration], at most " STR(STAGE_MAX_OUT_TIMES) ": the steps land on them"},
  {"{stage}.pressure", FE, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "the pressure of groups of boundary.pressure (omitted: held)"},
  {"{stage}.pressure.*", FE, KEY_FORMS, N, N, 0, "a number | {exp: {P0, k}} | {table: {...}}", "held", "MPa", "the group's pressure: at the stage's end, P0 exp(k t) in the stage time, or a table"},
  {"{stage}.pressure.*.exp", FE, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "P0 exp(k t), t the stage time"},
  {"{stage}.pressure.*.exp.P0", FE, KEY_NUMBER, N, N, REQ, NULL, NULL, "MPa", "the pressure at the stage's start"},
  {"{stage}.pressure.*.exp.k", FE, KEY_NUMBER, N, N, REQ, NULL, NULL, "1/s", "the rate"},
  {"{stage}.pressure.*.table", FE, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "a CSV history, linear between its rows, its end values beyond them"},
  TABLE("{stage}.pressure.*", "its value column", "the values times this"),
  {"{stage}.traction", FE, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "the traction of groups of boundary.traction (omitted: held)"},
  {"{stage}.traction.*", FE, KEY_NUMBERS, N, N, 0, NULL, "held", "MPa", "the group's traction vector at the stage's end (3 numbers; 2D: 2)"},
  {"{stage}.indenter", FE, KEY_MAPPING, N, N, 0, NULL, "load: hold", NULL, "indentation: the indenter in this stage, load or depth, and until"},
  {"{stage}.indenter.load", FE, KEY_FORMS, 0, N, 0, "a number >= 0 | hold | {exp: {P0, k}} | {table: {...}}", NULL, "force", "force control: the whole indenter's load at the stage's end, held, P0 exp(k t) or a table"},
  {"{stage}.indenter.load.exp", FE, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "P0 exp(k t), t the stage time (Yin et al. 2021 eqs. 25, 26)"},
  {"{stage}.indenter.load.exp.P0", FE, KEY_NUMBER, 0, N, REQ | GT, NULL, NULL, "force", "the load at the stage's start"},
  {"{stage}.indenter.load.exp.k", FE, KEY_NUMBER, N, N, REQ, NULL, NULL, "1/s", "the rate"},
  {"{stage}.indenter.load.table", FE, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "a measured load history over the whole stage, loads >= 0"},
  TABLE("{stage}.indenter.load", "its load column", "the loads times this (the scene's units)"),
  {"{stage}.indenter.depth", FE, KEY_FORMS, N, N, 0, "a number | {table: {...}}", NULL, "length", "depth control: the depth at the stage's end, or a table"},
  {"{stage}.indenter.depth.table", FE, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "a depth history over the whole stage"},
  TABLE("{stage}.indenter.depth", "its depth column", "the depths times this"),
  {"{stage}.indenter.until", FE, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "end the stage on the indenter, one of depth or load, with a rising load (not with the stage's until)"},
  {"{stage}.indenter.until.depth", FE, KEY_NUMBER, 0, N, GT, NULL, NULL, "length", "end when the depth reaches this"},
  {"{stage}.indenter.until.load", FE, KEY_NUMBER, 0, N, GT, NULL, NULL, "force", "end when the whole indenter's load reaches this"},
  {"{stage}.control", PT, KEY_MAPPING, N, N, REQ, NULL, NULL, NULL, "each component's control: 11 22 33 12 13 23 (ntens 4: 11 22 33 12) and others"},
  {"{stage}.control.others", PT, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "the target of every component not given: {stress: v} or {strain: v}"},
  {"{stage}.control.*", PT, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "a component's target (11, 22, ...): {stress: v} or {strain: v} at the segment's end"},
  {"{stage}.control.*.stress", PT, KEY_FORMS, N, N, 0, "a number | {column, factor}", NULL, "MPa", "the stress at the segment's end, or a column of the segment's table"},
  {"{stage}.control.*.strain", PT, KEY_FORMS, N, N, 0, "a number | {column, factor}", NULL, NULL, "the strain (engineering shear) at the segment's end, or a column of the table"},
  {"{stage}.control.*.stress.column", PT, KEY_TEXT, N, N, REQ, NULL, NULL, NULL, "the table's column"},
  {"{stage}.control.*.stress.factor", PT, KEY_NUMBER, N, N, 0, NULL, "1", NULL, "the column's values times this"},
  {"{stage}.control.*.strain.column", PT, KEY_TEXT, N, N, REQ, NULL, NULL, NULL, "the table's column"},
  {"{stage}.control.*.strain.factor", PT, KEY_NUMBER, N, N, 0, NULL, "1", NULL, "the column's values times this"},
  {"{stage}.constraints", PT, KEY_LIST, N, N, 0, NULL, NULL, NULL, "linear constraints a.eps + b.sigma = value, each replacing one component's equation"},
  {"{stage}.constraints[].replaces", PT, KEY_WORD, N, N, REQ, "11, 22, 33, 12, 13, 23", NULL, NULL, "the component whose equation it replaces"},
  {"{stage}.constraints[].strain", PT, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "the strain coefficients a by component"},
  {"{stage}.constraints[].strain.*", PT, KEY_NUMBER, N, N, 0, NULL, "0", NULL, "a component's strain coefficient"},
  {"{stage}.constraints[].stress", PT, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "the stress coefficients b by component"},
  {"{stage}.constraints[].stress.*", PT, KEY_NUMBER, N, N, 0, NULL, "0", "1/MPa", "a component's stress coefficient"},
  {"{stage}.constraints[].value", PT, KEY_NUMBER, N, N, 0, NULL, "its value at the segment's start", NULL, "the right-hand side"},
  {"{stage}.axis", PT, KEY_WORD, N, N, 0, "11, 22, 33", "33 (ntens 4: 22)", NULL, "a creep segment's loading axis, for the plots"},
  {"{stage}.table", PT, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "lab data (CSV) the controls' columns read, linear between its rows"},
  {"{stage}.table.file", PT, KEY_FILE, N, N, REQ, NULL, NULL, NULL, "the CSV file"},
  {"{stage}.table.time", PT, KEY_TEXT, N, N, REQ, NULL, NULL, NULL, "its time column (the segment's time, after time_factor)"},
  {"{stage}.table.time_factor", PT, KEY_NUMBER, N, N, 0, NULL, "1", "s per unit", "the table's time unit in s"},

  {"output", FE | PT, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "where and how often the results are written"},
  {"output.directory", FE, KEY_TEXT, N, N, 0, NULL, "out/NAME", NULL, "the output directory, relative to the working directory (-output_dir overrides)"},
  {"output.directory", PT, KEY_TEXT, N, N, 0, NULL, "out/point/NAME", NULL, "the output directory, relative to the working directory (-output_dir overrides)"},
  {"output.fields_every", FE, KEY_INTEGER, 0, N, 0, NULL, "0", NULL, "fields every N steps besides the start and each stage's end (0: only those); they do not shape adapted meshes"},
  {"output.progress_every", PT, KEY_INTEGER, 0, N, 0, NULL, "0", NULL, "a progress line every N steps (0: none)"},
  {"solver", FE, KEY_MAPPING, N, N, 0, NULL, NULL, NULL, "the solvers"},
  {"solver.options", FE, KEY_TEXT, N, N, 0, NULL, NULL, NULL, "PETSc options ('-snes_monitor -ksp_...'); the command line wins"},
};

const KeyTable scene_keys = {
  .decl        = decl,
  .n           = (int)(sizeof decl / sizeof decl[0]),
  .kind_names  = {"fe", "point", "sweep"},
  .alias_lists = {"stages", "segments"},
  .alias       = "{stage}",
  .source      = "driver/src/scene/scene_keys.c",
};

void scene_keys_attach(YdDoc *doc, unsigned kind) { keys_attach(doc, &scene_keys, kind); }
