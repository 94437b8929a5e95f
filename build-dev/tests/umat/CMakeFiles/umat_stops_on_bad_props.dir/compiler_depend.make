# Empty compiler generated dependencies file for umat_stops_on_bad_props.
# This may be replaced when dependencies are built.
