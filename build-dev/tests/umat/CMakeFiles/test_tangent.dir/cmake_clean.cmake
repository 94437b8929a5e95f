file(REMOVE_RECURSE
  "CMakeFiles/test_tangent.dir/test_tangent.f90.o"
  "test_tangent"
  "test_tangent.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang Fortran)
  include(CMakeFiles/test_tangent.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
