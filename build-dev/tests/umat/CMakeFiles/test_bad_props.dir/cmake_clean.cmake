file(REMOVE_RECURSE
  "CMakeFiles/test_bad_props.dir/test_bad_props.f90.o"
  "test_bad_props"
  "test_bad_props.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang Fortran)
  include(CMakeFiles/test_bad_props.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
