# Empty custom commands generated dependencies file for camclay9_single_files.
# This may be replaced when dependencies are built.
