# Empty compiler generated dependencies file for elastic_umat.
# This may be replaced when dependencies are built.
