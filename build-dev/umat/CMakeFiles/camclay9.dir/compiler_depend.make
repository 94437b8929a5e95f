# Empty compiler generated dependencies file for camclay9.
# This may be replaced when dependencies are built.
