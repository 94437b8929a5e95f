# Empty compiler generated dependencies file for test_bad_props.
# This may be replaced when dependencies are built.
