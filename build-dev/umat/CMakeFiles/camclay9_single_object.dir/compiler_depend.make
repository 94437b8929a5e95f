# Empty custom commands generated dependencies file for camclay9_single_object.
# This may be replaced when dependencies are built.
