file(REMOVE_RECURSE
  "CMakeFiles/camclay9_objects.dir/src/ccix_capi.f90.o"
  "CMakeFiles/camclay9_objects.dir/src/ccix_elasticity.f90.o"
  "CMakeFiles/camclay9_objects.dir/src/ccix_frame.f90.o"
  "CMakeFiles/camclay9_objects.dir/src/ccix_host.f90.o"
  "CMakeFiles/camclay9_objects.dir/src/ccix_material_cache.f90.o"
  "CMakeFiles/camclay9_objects.dir/src/ccix_mixture.f90.o"
  "CMakeFiles/camclay9_objects.dir/src/ccix_projection.f90.o"
  "CMakeFiles/camclay9_objects.dir/src/ccix_props.f90.o"
  "CMakeFiles/camclay9_objects.dir/src/ccix_tensor.f90.o"
  "CMakeFiles/camclay9_objects.dir/src/umat.f90.o"
)

# Per-language clean rules from dependency scanning.
foreach(lang Fortran)
  include(CMakeFiles/camclay9_objects.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
