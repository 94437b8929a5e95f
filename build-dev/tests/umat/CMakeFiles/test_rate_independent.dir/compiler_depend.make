# Empty compiler generated dependencies file for test_rate_independent.
# This may be replaced when dependencies are built.
