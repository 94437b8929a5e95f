file(REMOVE_RECURSE
  "CMakeFiles/test_gmsh_mesh.dir/driver/test_gmsh_mesh.c.o"
  "CMakeFiles/test_gmsh_mesh.dir/driver/test_gmsh_mesh.c.o.d"
  "test_gmsh_mesh"
  "test_gmsh_mesh.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang C)
  include(CMakeFiles/test_gmsh_mesh.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
