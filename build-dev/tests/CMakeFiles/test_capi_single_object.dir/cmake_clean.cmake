file(REMOVE_RECURSE
  "CMakeFiles/test_capi_single_object.dir/umat/test_capi.c.o"
  "CMakeFiles/test_capi_single_object.dir/umat/test_capi.c.o.d"
  "test_capi_single_object"
  "test_capi_single_object.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang C)
  include(CMakeFiles/test_capi_single_object.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
