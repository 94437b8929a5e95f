file(REMOVE_RECURSE
  "CMakeFiles/umat_test_support.dir/test_support.f90.o"
  "libumat_test_support.a"
  "libumat_test_support.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang Fortran)
  include(CMakeFiles/umat_test_support.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
