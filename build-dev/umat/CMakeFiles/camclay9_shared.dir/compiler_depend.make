# Empty compiler generated dependencies file for camclay9_shared.
# This may be replaced when dependencies are built.
