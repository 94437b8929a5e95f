file(REMOVE_RECURSE
  "CMakeFiles/test_extremes.dir/test_extremes.f90.o"
  "test_extremes"
  "test_extremes.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang Fortran)
  include(CMakeFiles/test_extremes.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
