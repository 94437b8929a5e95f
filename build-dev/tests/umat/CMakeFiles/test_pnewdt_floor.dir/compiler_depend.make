# Empty compiler generated dependencies file for test_pnewdt_floor.
# This may be replaced when dependencies are built.
