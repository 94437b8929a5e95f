# Empty compiler generated dependencies file for umat_bench.
# This may be replaced when dependencies are built.
