# Empty compiler generated dependencies file for test_step_control.
# This may be replaced when dependencies are built.
