# Empty compiler generated dependencies file for test_fp_exceptions.
# This may be replaced when dependencies are built.
