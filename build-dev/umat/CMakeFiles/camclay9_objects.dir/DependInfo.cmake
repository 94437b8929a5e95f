
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  "Fortran"
  )
# The set of files for implicit dependencies of each language:
set(CMAKE_DEPENDS_CHECK_Fortran
  "/work/main/umat/src/ccix_capi.f90" "/work/main/build-dev/umat/CMakeFiles/camclay9_objects.dir/src/ccix_capi.f90.o"
  "/work/main/umat/src/ccix_elasticity.f90" "/work/main/build-dev/umat/CMakeFiles/camclay9_objects.dir/src/ccix_elasticity.f90.o"
  "/work/main/umat/src/ccix_frame.f90" "/work/main/build-dev/umat/CMakeFiles/camclay9_objects.dir/src/ccix_frame.f90.o"
  "/work/main/umat/src/ccix_host.f90" "/work/main/build-dev/umat/CMakeFiles/camclay9_objects.dir/src/ccix_host.f90.o"
  "/work/main/umat/src/ccix_material_cache.f90" "/work/main/build-dev/umat/CMakeFiles/camclay9_objects.dir/src/ccix_material_cache.f90.o"
  "/work/main/umat/src/ccix_mixture.f90" "/work/main/build-dev/umat/CMakeFiles/camclay9_objects.dir/src/ccix_mixture.f90.o"
  "/work/main/umat/src/ccix_projection.f90" "/work/main/build-dev/umat/CMakeFiles/camclay9_objects.dir/src/ccix_projection.f90.o"
  "/work/main/umat/src/ccix_props.f90" "/work/main/build-dev/umat/CMakeFiles/camclay9_objects.dir/src/ccix_props.f90.o"
  "/work/main/umat/src/ccix_tensor.f90" "/work/main/build-dev/umat/CMakeFiles/camclay9_objects.dir/src/ccix_tensor.f90.o"
  "/work/main/umat/src/umat.f90" "/work/main/build-dev/umat/CMakeFiles/camclay9_objects.dir/src/umat.f90.o"
  )
set(CMAKE_Fortran_COMPILER_ID "GNU")
set(CMAKE_Fortran_SUBMODULE_SEP "@")
set(CMAKE_Fortran_SUBMODULE_EXT ".smod")

# The include file search paths:
set(CMAKE_Fortran_TARGET_INCLUDE_PATH
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "/work/main/build-dev/umat/modules")
