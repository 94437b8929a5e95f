# Empty compiler generated dependencies file for test_elasticity.
# This may be replaced when dependencies are built.
