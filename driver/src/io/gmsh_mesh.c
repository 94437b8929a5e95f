#include "gmsh_mesh.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

int gmsh_valid_name(const char *s) {
  if (!(isalpha((unsigned char)s[0]) || s[0] == '_')) return 0;
  for (const char *c = s; *c; c++)
    if (!(isalnum((unsigned char)*c) || *c == '_')) return 0;
  return strlen(s) < 64;
}

static void add_name(const char *start, char (*names)[64], int max, int *n) {
  char name[64];
  int  len = 0;
  while (*start == ' ' || *start == '\t') start++;
  while ((isalnum((unsigned char)start[len]) || start[len] == '_') && len < 63) len++;
  if (!len) return;
  snprintf(name, sizeof name, "%.*s", len, start);
  for (int i = 0; i < *n; i++)
    if (!strcmp(names[i], name)) return;
  if (*n < max) snprintf(names[(*n)++], 64, "%s", name);
}

int gmsh_geo_parameters(const char *geo, char (*names)[64], int max, int *n, char *err, size_t errlen) {
  FILE *fp = fopen(geo, "r");
  char  line[4096];
  *n = 0;
  if (!fp) {
    snprintf(err, errlen, "%s: cannot open: %s", geo, strerror(errno));
    return 1;
  }
  while (fgets(line, sizeof line, fp)) {
    char *c = strstr(line, "//");
    if (c) *c = '\0';
    for (char *p = line; (p = strstr(p, "Exists(")); p += 7) add_name(p + 7, names, max, n);
    for (char *p = line; (p = strstr(p, "DefineConstant[")); p += 15) add_name(p + 15, names, max, n);
  }
  fclose(fp);
  return 0;
}

/* The first line of gmsh's log that reports an error, or its last line. */
static void log_error_line(const char *log, char *out, size_t n) {
  FILE *fp = fopen(log, "r");
  char  line[1024];
  out[0] = '\0';
  if (!fp) return;
  while (fgets(line, sizeof line, fp)) {
    line[strcspn(line, "\r\n")] = '\0';
    if (!line[0]) continue;
    snprintf(out, n, "%s", line);
    if (strstr(line, "Error")) break;
  }
  fclose(fp);
}

int gmsh_mesh(const char *geo, int dim, int nparam, const char (*names)[64], const double *values,
              const char *out_msh, char *err, size_t errlen) {
  char  *argv[16 + 3 * GMSH_MAX_PARAMS], vals[GMSH_MAX_PARAMS][32], log[4096];
  int    a = 0;
  pid_t  pid;
  if (nparam > GMSH_MAX_PARAMS) {
    snprintf(err, errlen, "%s: at most %d parameters, got %d", geo, GMSH_MAX_PARAMS, nparam);
    return 1;
  }
  for (int i = 0; i < nparam; i++)
    if (!gmsh_valid_name(names[i])) {
      snprintf(err, errlen, "%s: '%s' is not a parameter name ([A-Za-z_][A-Za-z0-9_]*)", geo, names[i]);
      return 1;
    }
  snprintf(log, sizeof log, "%s.log", out_msh);
  argv[a++] = "gmsh", argv[a++] = "-3", argv[a++] = "-format", argv[a++] = "msh41", argv[a++] = "-v", argv[a++] = "2";
  argv[a++] = (char *)geo;
  for (int i = 0; i < nparam; i++) {
    snprintf(vals[i], sizeof vals[i], "%.17g", values[i]);
    argv[a++] = "-setnumber", argv[a++] = (char *)names[i], argv[a++] = vals[i];
  }
  argv[a++] = "-o", argv[a++] = (char *)out_msh, argv[a] = NULL;
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  int rc = posix_spawnp(&pid, "gmsh", &fa, NULL, argv, environ), status = 0;
  posix_spawn_file_actions_destroy(&fa);
  if (rc) {
    snprintf(err, errlen, "%s: cannot run gmsh (the mesher, looked up on PATH): %s", geo, strerror(rc));
    return 1;
  }
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) {
      snprintf(err, errlen, "%s: waiting for gmsh: %s", geo, strerror(errno));
      return 1;
    }
  char first[1024];
  log_error_line(log, first, sizeof first);
  if (!WIFEXITED(status) || WEXITSTATUS(status) || (first[0] && strstr(first, "Error"))) {
    snprintf(err, errlen, "%s: gmsh failed (%s %d)%s%s; its log: %s", geo,
             WIFEXITED(status) ? "exit status" : "signal", WIFEXITED(status) ? WEXITSTATUS(status) : WTERMSIG(status),
             first[0] ? ": " : "", first, log);
    return 1;
  }
  remove(log); /* kept only when gmsh failed */
  return msh_check(out_msh, dim, 0, NULL, err, errlen);
}

typedef struct {
  FILE       *fp;
  const char *file;
  long        line;
  char        buf[4096];
} Reader;

static int next_line(Reader *r) {
  if (!fgets(r->buf, sizeof r->buf, r->fp)) return 1;
  r->line++;
  return 0;
}

#define TRUNC(what)                                                                                            \
  do {                                                                                                         \
    snprintf(err, errlen, "%s: the mesh file is truncated or damaged at line %ld (%s)", r->file, r->line, what); \
    return 1;                                                                                                  \
  } while (0)

/* $Nodes of msh 4.1: blocks of tags then coordinates; the smallest x. */
static int scan_nodes(Reader *r, double *xmin, long *xmin_line, char *err, size_t errlen) {
  long nblock, nnode, a, b;
  if (next_line(r) || sscanf(r->buf, "%ld %ld %ld %ld", &nblock, &nnode, &a, &b) != 4) TRUNC("$Nodes header");
  for (long k = 0; k < nblock; k++) {
    long dim, tag, param, n;
    if (next_line(r) || sscanf(r->buf, "%ld %ld %ld %ld", &dim, &tag, &param, &n) != 4) TRUNC("node block header");
    for (long i = 0; i < n; i++)
      if (next_line(r)) TRUNC("node tags");
    for (long i = 0; i < n; i++) {
      double x, y, z;
      if (next_line(r) || sscanf(r->buf, "%lf %lf %lf", &x, &y, &z) != 3) TRUNC("node coordinates");
      if (x < *xmin) *xmin = x, *xmin_line = r->line;
    }
  }
  if (next_line(r) || strncmp(r->buf, "$EndNodes", 9)) TRUNC("expected $EndNodes");
  return 0;
}

/* $Elements of msh 4.1: the highest entity dimension with elements. */
static int scan_elements(Reader *r, int *maxdim, char *err, size_t errlen) {
  long nblock, nel, a, b;
  if (next_line(r) || sscanf(r->buf, "%ld %ld %ld %ld", &nblock, &nel, &a, &b) != 4) TRUNC("$Elements header");
  for (long k = 0; k < nblock; k++) {
    long dim, tag, type, n;
    if (next_line(r) || sscanf(r->buf, "%ld %ld %ld %ld", &dim, &tag, &type, &n) != 4) TRUNC("element block header");
    if (n > 0 && dim > *maxdim) *maxdim = (int)dim;
    for (long i = 0; i < n; i++)
      if (next_line(r)) TRUNC("elements");
  }
  if (next_line(r) || strncmp(r->buf, "$EndElements", 12)) TRUNC("expected $EndElements");
  return 0;
}

static int scan_msh(Reader *r, int dim, int axisymmetric, int *periodic, char *err, size_t errlen) {
  double version = 0;
  int    filetype = 0, full, maxdim = -1, nodes = 0, elements = 0;
  double xmin = INFINITY;
  long   xmin_line = 0;
  if (next_line(r) || strncmp(r->buf, "$MeshFormat", 11)) {
    r->buf[strcspn(r->buf, "\r\n")] = '\0';
    snprintf(err, errlen, "%s: not a gmsh mesh (line 1 is '%.40s', expected $MeshFormat)", r->file, r->line ? r->buf : "");
    return 1;
  }
  if (next_line(r) || sscanf(r->buf, "%lf %d", &version, &filetype) != 2) TRUNC("$MeshFormat");
  if (version < 4) { /* PETSc 3.18's reader of msh 2.x files put the faces of another group into a physical
                        group (the triaxial cylinder's 'top' held 178 faces instead of its 84: the axial
                        pressure cancelled, silently); so msh 2.x is refused */
    snprintf(err, errlen, "%s: a gmsh mesh in format %g; the driver reads format 4.1 only (PETSc mislabels the physical "
             "groups of format 2 files): convert it with 'gmsh %s -0 -format msh41 -o NEW.msh'", r->file, version, r->file);
    return 1;
  }
  full = version >= 4.05 && version < 4.15 && filetype == 0;
  while (!next_line(r)) {
    if (!strncmp(r->buf, "$Nodes", 6) && full) {
      if (scan_nodes(r, &xmin, &xmin_line, err, errlen)) return 1;
      nodes = 1;
    } else if (!strncmp(r->buf, "$Elements", 9) && full) {
      if (scan_elements(r, &maxdim, err, errlen)) return 1;
      elements = 1;
    } else if (!strncmp(r->buf, "$EndNodes", 9)) nodes = 1;
    else if (!strncmp(r->buf, "$EndElements", 12)) elements = 1;
    else if (!strncmp(r->buf, "$Periodic", 9) && periodic) *periodic = 1;
  }
  if (!nodes || !elements) TRUNC(nodes ? "no $EndElements" : "no $EndNodes");
  if (!full) return 0;
  if (maxdim != dim) {
    snprintf(err, errlen, "%s: a %dD mesh, but the kinematics need a %dD mesh (3d: tetrahedra; plane_strain and "
             "axisymmetric: triangles in the x-y plane)", r->file, maxdim, dim);
    return 1;
  }
  if (axisymmetric && xmin < 0) {
    snprintf(err, errlen, "%s:%ld: a node at r = x = %g < 0: an axisymmetric mesh must lie in x >= 0 (x is the radius)",
             r->file, xmin_line, xmin);
    return 1;
  }
  return 0;
}

int msh_check(const char *msh, int dim, int axisymmetric, int *periodic, char *err, size_t errlen) {
  Reader r = {fopen(msh, "rb"), msh, 0, ""};
  if (!r.fp) {
    snprintf(err, errlen, "%s: cannot open: %s", msh, strerror(errno));
    return 1;
  }
  if (periodic) *periodic = 0;
  int rc = scan_msh(&r, dim, axisymmetric, periodic, err, errlen);
  fclose(r.fp);
  return rc;
}
