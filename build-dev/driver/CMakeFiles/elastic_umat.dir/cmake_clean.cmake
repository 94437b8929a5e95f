file(REMOVE_RECURSE
  "CMakeFiles/elastic_umat.dir/__/tests/elastic_umat/elastic_umat.f90.o"
  "libelastic_umat.a"
  "libelastic_umat.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang Fortran)
  include(CMakeFiles/elastic_umat.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
