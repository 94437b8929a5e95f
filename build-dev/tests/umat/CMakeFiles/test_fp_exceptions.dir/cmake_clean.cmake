file(REMOVE_RECURSE
  "CMakeFiles/test_fp_exceptions.dir/test_fp_exceptions.f90.o"
  "test_fp_exceptions"
  "test_fp_exceptions.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang Fortran)
  include(CMakeFiles/test_fp_exceptions.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
