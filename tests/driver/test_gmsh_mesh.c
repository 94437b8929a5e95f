/* gmsh_mesh() and msh_check() (driver/src/io/gmsh_mesh.h) without the FE driver: a box meshed into a
 * folder whose name has a space and a quote, its parameter applied (the box's length Lx is the
 * largest node x), a parameter name that would be a shell command refused, and gmsh's failure on a missing .geo
 * reported with its own error line. Exit 0 when all hold; 77 (skipped) without gmsh on PATH. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "io/gmsh_mesh.h"

static int failures = 0;
#define CHECK(cond, ...)                         \
  do {                                           \
    if (!(cond)) {                               \
      fprintf(stderr, "FAILED: " __VA_ARGS__);   \
      fprintf(stderr, "\n");                     \
      failures++;                                \
    }                                            \
  } while (0)

/* The largest x of the nodes (the lines of three numbers in $Nodes). */
static double max_x(const char *msh) {
  FILE  *fp = fopen(msh, "r");
  char   line[512];
  int    in = 0;
  double xmax = -1e300;
  while (fp && fgets(line, sizeof line, fp)) {
    double x, y, z;
    int    end = 0;
    if (!strncmp(line, "$Nodes", 6)) in = 1;
    else if (!strncmp(line, "$EndNodes", 9)) in = 0;
    else if (in && sscanf(line, "%lf %lf %lf %n", &x, &y, &z, &end) == 3 && line[end] == '\0' && x > xmax) xmax = x;
  }
  if (fp) fclose(fp);
  return xmax;
}

int main(int argc, char **argv) {
  char dir[] = "/tmp/gmsh mesh 'x' XXXXXX", geo[1024], msh[1100], err[2048];
  char   names[1][64] = {"Lx"}, bad[1][64] = {"Lx;touch"};
  double short_box = 0.75, long_box = 2.5;
  if (argc < 2) return fprintf(stderr, "usage: test_gmsh_mesh MESHES_DIR\n"), 2;
  if (system("command -v gmsh > /dev/null 2>&1")) return 77;
  if (!mkdtemp(dir)) return perror("mkdtemp"), 1;
  snprintf(geo, sizeof geo, "%s/box.geo", argv[1]);
  snprintf(msh, sizeof msh, "%s/mesh.msh.part", dir);

  char known[GMSH_MAX_PARAMS][64];
  int  nknown = 0;
  CHECK(!gmsh_geo_parameters(geo, known, GMSH_MAX_PARAMS, &nknown, err, sizeof err), "%s", err);
  CHECK(nknown == 4 && !strcmp(known[0], "Lx") && !strcmp(known[3], "size"), "box.geo parameters: %d", nknown);

  CHECK(!gmsh_mesh(geo, 3, 1, (const char(*)[64])names, &short_box, msh, err, sizeof err), "Lx 0.75: %s", err);
  double x1 = max_x(msh);
  CHECK(!gmsh_mesh(geo, 3, 1, (const char(*)[64])names, &long_box, msh, err, sizeof err), "Lx 2.5: %s", err);
  double x2 = max_x(msh);
  CHECK(x1 == 0.75 && x2 == 2.5, "Lx not applied: largest x %g (Lx 0.75), %g (Lx 2.5)", x1, x2);
  CHECK(!msh_check(msh, 3, 0, NULL, err, sizeof err), "msh_check 3D: %s", err);
  CHECK(msh_check(msh, 2, 0, NULL, err, sizeof err) && strstr(err, "a 3D mesh, but the kinematics need a 2D mesh"), "2D: %s", err);
  { /* the same mesh in format 2.2 is refused, naming the file and the conversion */
    char cmd22[2400], msh22[1200];
    snprintf(msh22, sizeof msh22, "%s/mesh22.msh", dir);
    snprintf(cmd22, sizeof cmd22, "gmsh \"%s\" -0 -format msh22 -o \"%s\" > /dev/null 2>&1", msh, msh22);
    CHECK(!system(cmd22), "gmsh could not write msh 2.2");
    CHECK(msh_check(msh22, 3, 0, NULL, err, sizeof err) && strstr(err, "format 2.2") && strstr(err, "mesh22.msh") && strstr(err, "-format msh41"),
          "msh 2.2: %s", err);
  }

  CHECK(gmsh_mesh(geo, 3, 1, (const char(*)[64])bad, &short_box, msh, err, sizeof err) && strstr(err, "not a parameter name"),
        "bad name: %s", err);
  snprintf(geo, sizeof geo, "%s/nothere.geo", dir);
  CHECK(gmsh_mesh(geo, 3, 0, NULL, NULL, msh, err, sizeof err) && strstr(err, "gmsh failed") && strstr(err, "nothere.geo"),
        "missing geo: %s", err);
  char cmd[1200];
  snprintf(cmd, sizeof cmd, "rm -rf \"%s\"", dir);
  if (system(cmd)) fprintf(stderr, "could not remove %s\n", dir);
  if (!failures) printf("gmsh_mesh: Lx applied (largest x %g, %g); bad names refused; gmsh's errors reported\n", x1, x2);
  return failures ? 1 : 0;
}
