# Empty compiler generated dependencies file for umat_test_support.
# This may be replaced when dependencies are built.
