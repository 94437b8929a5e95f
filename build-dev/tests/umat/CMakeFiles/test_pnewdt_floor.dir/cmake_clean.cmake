file(REMOVE_RECURSE
  "CMakeFiles/test_pnewdt_floor.dir/test_pnewdt_floor.f90.o"
  "test_pnewdt_floor"
  "test_pnewdt_floor.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang Fortran)
  include(CMakeFiles/test_pnewdt_floor.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
