# Empty dependencies file for driver_elastic.
# This may be replaced when dependencies are built.
