# Empty dependencies file for test_gmsh_mesh.
# This may be replaced when dependencies are built.
