file(REMOVE_RECURSE
  "CMakeFiles/camclay9_single_files"
  "camclay9_umat.f90"
  "camclay9_umat_abaqus.for"
)

# Per-language clean rules from dependency scanning.
foreach(lang )
  include(CMakeFiles/camclay9_single_files.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
