# Empty dependencies file for driver_core.
# This may be replaced when dependencies are built.
