# Empty compiler generated dependencies file for camclay9_objects.
# This may be replaced when dependencies are built.
