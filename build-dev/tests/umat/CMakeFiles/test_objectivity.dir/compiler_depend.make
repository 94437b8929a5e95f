# Empty compiler generated dependencies file for test_objectivity.
# This may be replaced when dependencies are built.
