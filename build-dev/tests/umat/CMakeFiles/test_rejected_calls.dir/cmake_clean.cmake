file(REMOVE_RECURSE
  "CMakeFiles/test_rejected_calls.dir/test_rejected_calls.f90.o"
  "test_rejected_calls"
  "test_rejected_calls.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang Fortran)
  include(CMakeFiles/test_rejected_calls.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
