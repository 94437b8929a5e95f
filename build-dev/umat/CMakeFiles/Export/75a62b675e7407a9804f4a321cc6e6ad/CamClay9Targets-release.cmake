#----------------------------------------------------------------
# Generated CMake target import file for configuration "Release".
#----------------------------------------------------------------

# Commands may need to know the format version.
set(CMAKE_IMPORT_FILE_VERSION 1)

# Import target "CamClay9::camclay9" for configuration "Release"
set_property(TARGET CamClay9::camclay9 APPEND PROPERTY IMPORTED_CONFIGURATIONS RELEASE)
set_target_properties(CamClay9::camclay9 PROPERTIES
  IMPORTED_LINK_INTERFACE_LANGUAGES_RELEASE "Fortran"
  IMPORTED_LOCATION_RELEASE "${_IMPORT_PREFIX}/lib/libcamclay9.a"
  )

list(APPEND _cmake_import_check_targets CamClay9::camclay9 )
list(APPEND _cmake_import_check_files_for_CamClay9::camclay9 "${_IMPORT_PREFIX}/lib/libcamclay9.a" )

# Import target "CamClay9::camclay9_shared" for configuration "Release"
set_property(TARGET CamClay9::camclay9_shared APPEND PROPERTY IMPORTED_CONFIGURATIONS RELEASE)
set_target_properties(CamClay9::camclay9_shared PROPERTIES
  IMPORTED_LOCATION_RELEASE "${_IMPORT_PREFIX}/lib/libcamclay9.so.0.1.0"
  IMPORTED_SONAME_RELEASE "libcamclay9.so.0"
  )

list(APPEND _cmake_import_check_targets CamClay9::camclay9_shared )
list(APPEND _cmake_import_check_files_for_CamClay9::camclay9_shared "${_IMPORT_PREFIX}/lib/libcamclay9.so.0.1.0" )

# Commands beyond this point should not need to know the version.
set(CMAKE_IMPORT_FILE_VERSION)
