file(REMOVE_RECURSE
  "CMakeFiles/umat_bench.dir/umat_bench.f90.o"
  "umat_bench"
  "umat_bench.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang Fortran)
  include(CMakeFiles/umat_bench.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
