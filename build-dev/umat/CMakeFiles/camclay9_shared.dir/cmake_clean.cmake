file(REMOVE_RECURSE
  "libcamclay9.pdb"
  "libcamclay9.so"
  "libcamclay9.so.0"
  "libcamclay9.so.0.1.0"
)

# Per-language clean rules from dependency scanning.
foreach(lang Fortran)
  include(CMakeFiles/camclay9_shared.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
