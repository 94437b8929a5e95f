# Remove fortran modules provided by this target.
FILE(REMOVE
  "modules/test_support.mod"
  "modules/TEST_SUPPORT.mod"
  "CMakeFiles/umat_test_support.dir/test_support.mod.stamp"
  )
