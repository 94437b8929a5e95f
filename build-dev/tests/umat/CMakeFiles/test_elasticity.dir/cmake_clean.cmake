file(REMOVE_RECURSE
  "CMakeFiles/test_elasticity.dir/test_elasticity.f90.o"
  "test_elasticity"
  "test_elasticity.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang Fortran)
  include(CMakeFiles/test_elasticity.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
