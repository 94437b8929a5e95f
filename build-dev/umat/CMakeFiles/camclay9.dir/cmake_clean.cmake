file(REMOVE_RECURSE
  "libcamclay9.a"
  "libcamclay9.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang Fortran)
  include(CMakeFiles/camclay9.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
