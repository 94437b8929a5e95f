/* A finite-element scene as read from YAML: mesh, kinematics, material, phi field, initial state,
 * boundary conditions, load stages and output. Every error names the file, the line and the key. */
#ifndef FE_SCENE_H
#define FE_SCENE_H

#include "../io/gmsh_mesh.h"
#include "../io/yaml_doc.h"
#include "../scene/stage.h"
#include "../scene/time_function.h"
#include "fe_problem.h"

#define FE_MAX_FIXED 16 /* boundary.fixed and boundary.mirror entries together */

/* A stage's loads on the body (the stage itself, scene/stage.h, is every kind's): the pressure or traction of each
 * group, a time function of the stage time (scene/time_function.h: a ramp to the value at the stage's end,
 * P0 exp(k t), or a table); and its indenter settings (read by the contact module). */
typedef struct {
  double    pressure[FE_MAX_GROUPS]; /* a ramp's value at the end of the stage; NAN: keep */
  TimeFn    fn[FE_MAX_GROUPS];
  YdNode   *indenter;                /* the stage's indenter settings (read by the contact module), or NULL */
} StageLoads;

/* mesh.adapt (docs/adapt.md): reruns of the scene on meshes made from the error indicator. */
typedef struct {
  int    levels;     /* reruns after the first run (0: none) */
  double growth;     /* cells of a level over the previous level's */
  double tol;        /* stop once every reported quantity's estimated mesh error is below this (relative); 0: never */
  int    line;       /* the key's line in the scene (0: not given) */
} MeshAdapt;

typedef struct {
  char         name[128], outdir[512], msh[1024]; /* input paths resolved against the scene's folder */
  char         geometry[1024];               /* a gmsh .geo meshed at run time (io/gmsh_mesh.h), or "" */
  int          ngmsh;                        /* its parameters, each one the .geo defines */
  char         gmsh_name[GMSH_MAX_PARAMS][64];
  double       gmsh_value[GMSH_MAX_PARAMS];
  MeshAdapt    adapt;
  int          order;
  Kinematics   kin;
  double       thickness;
  UmatMaterial mat;
  double       phi_mean, phi_std, phi_lo, phi_hi, phi_corr;
  int          phi_seed;
  double       stress0[6], pressure0[FE_MAX_GROUPS];
  int          nfixed;
  FeFixed      fixed[FE_MAX_FIXED];   /* boundary.fixed, then boundary.mirror (mirror set) */
  int          npressure;
  char         pressure_group[FE_MAX_GROUPS][64];
  int          nstage;
  Stage        stage[MAXSTAGES];
  StageLoads   loads[MAXSTAGES];
  int          axis;
  int          fields_every;         /* field output every N steps, besides the start and each stage's end */
  char         solver_options[1024]; /* PETSc options from the scene; the command line wins */
  YdNode      *indenter;             /* a rigid indenter (contact/indent_scene.h), or NULL */
} FeScene;


/* Read the scene; 0, or 1 with err filled. */
int fe_scene_read(YdDoc *doc, FeScene *sc, char *err, size_t errlen);
/* The load of group k at stage time ts: its time function, a ramp from start to target (lambda: the fraction of the
 * stage done then). */
double stage_pressure(const StageLoads *g, int k, double start, double target, double lambda, double ts);

#endif
