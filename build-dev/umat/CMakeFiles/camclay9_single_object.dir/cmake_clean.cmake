file(REMOVE_RECURSE
  "CMakeFiles/camclay9_single_object"
  "camclay9_umat.o"
  "object/camclay9_umat.f90"
)

# Per-language clean rules from dependency scanning.
foreach(lang )
  include(CMakeFiles/camclay9_single_object.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
