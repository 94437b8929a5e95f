file(REMOVE_RECURSE
  "CMakeFiles/test_objectivity.dir/test_objectivity.f90.o"
  "test_objectivity"
  "test_objectivity.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang Fortran)
  include(CMakeFiles/test_objectivity.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
