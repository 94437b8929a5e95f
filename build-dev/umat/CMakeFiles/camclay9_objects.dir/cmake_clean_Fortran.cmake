# Remove fortran modules provided by this target.
FILE(REMOVE
  "modules/ccix_capi.mod"
  "modules/CCIX_CAPI.mod"
  "CMakeFiles/camclay9_objects.dir/ccix_capi.mod.stamp"

  "modules/ccix_elasticity.mod"
  "modules/CCIX_ELASTICITY.mod"
  "CMakeFiles/camclay9_objects.dir/ccix_elasticity.mod.stamp"

  "modules/ccix_frame.mod"
  "modules/CCIX_FRAME.mod"
  "CMakeFiles/camclay9_objects.dir/ccix_frame.mod.stamp"

  "modules/ccix_host.mod"
  "modules/CCIX_HOST.mod"
  "CMakeFiles/camclay9_objects.dir/ccix_host.mod.stamp"

  "modules/ccix_material_cache.mod"
  "modules/CCIX_MATERIAL_CACHE.mod"
  "CMakeFiles/camclay9_objects.dir/ccix_material_cache.mod.stamp"

  "modules/ccix_mixture.mod"
  "modules/CCIX_MIXTURE.mod"
  "CMakeFiles/camclay9_objects.dir/ccix_mixture.mod.stamp"

  "modules/ccix_projection.mod"
  "modules/CCIX_PROJECTION.mod"
  "CMakeFiles/camclay9_objects.dir/ccix_projection.mod.stamp"

  "modules/ccix_props.mod"
  "modules/CCIX_PROPS.mod"
  "CMakeFiles/camclay9_objects.dir/ccix_props.mod.stamp"

  "modules/ccix_tensor.mod"
  "modules/CCIX_TENSOR.mod"
  "CMakeFiles/camclay9_objects.dir/ccix_tensor.mod.stamp"
  )
