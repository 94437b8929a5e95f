file(REMOVE_RECURSE
  "CMakeFiles/test_rate_independent.dir/test_rate_independent.f90.o"
  "test_rate_independent"
  "test_rate_independent.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang Fortran)
  include(CMakeFiles/test_rate_independent.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
