/* Meshing a gmsh .geo without a shell, and checking a .msh before PETSc reads it. */
#ifndef GMSH_MESH_H
#define GMSH_MESH_H

#include <stddef.h>

#define GMSH_MAX_PARAMS 32

/* The parameters a .geo accepts: the names it tests with Exists(NAME) or declares with
 * DefineConstant[NAME = ...]. 0, or 1 with err filled (cannot read). */
int gmsh_geo_parameters(const char *geo, char (*names)[64], int max, int *n, char *err, size_t errlen);

/* A valid parameter name: [A-Za-z_][A-Za-z0-9_]* and at most 63 characters. */
int gmsh_valid_name(const char *name);

/* Mesh 'geo' (gmsh -3: a 2D geometry gives a 2D mesh) into out_msh (format msh41) with 'gmsh' from PATH, run as
 * gmsh -3 -format msh41 -v 2 GEO [-setnumber NAME VALUE]... -o OUT through an argument vector (no
 * shell: any path works). gmsh's own output goes to OUT.log, which is removed when gmsh succeeds. Returns 0, or 1 with err filled (gmsh's
 * first error line quoted). Call on one rank only. */
int gmsh_mesh(const char *geo, int dim, int nparam, const char (*names)[64], const double *values,
              const char *out_msh, char *err, size_t errlen);

/* Check a .msh before PETSc reads it: a gmsh file (first line $MeshFormat), complete ($EndNodes,
 * $EndElements present), its highest element dimension equal to dim, and, when axisymmetric, no node
 * at x < 0. ASCII msh 4.1 is checked in full; other versions for the first two only. 0, or 1 with err
 * filled (naming the file). periodic (may be NULL): set to whether the file has a $Periodic section (gmsh's
 * copies of a mesh through an affine map, such as a mirrored half: meshes/indent_block2d.geo, mirror = 1). */
int msh_check(const char *msh, int dim, int axisymmetric, int *periodic, char *err, size_t errlen);

#endif
