# Empty compiler generated dependencies file for test_tangent.
# This may be replaced when dependencies are built.
