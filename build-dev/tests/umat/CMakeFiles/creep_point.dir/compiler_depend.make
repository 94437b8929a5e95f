# Empty compiler generated dependencies file for creep_point.
# This may be replaced when dependencies are built.
