# Empty dependencies file for test_capi_single_object.
# This may be replaced when dependencies are built.
