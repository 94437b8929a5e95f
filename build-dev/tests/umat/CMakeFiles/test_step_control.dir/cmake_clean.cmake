file(REMOVE_RECURSE
  "CMakeFiles/test_step_control.dir/test_step_control.f90.o"
  "test_step_control"
  "test_step_control.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang Fortran)
  include(CMakeFiles/test_step_control.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
