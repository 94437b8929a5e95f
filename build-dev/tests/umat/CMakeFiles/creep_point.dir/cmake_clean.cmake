file(REMOVE_RECURSE
  "CMakeFiles/creep_point.dir/creep_point.f90.o"
  "creep_point"
  "creep_point.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang Fortran)
  include(CMakeFiles/creep_point.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
