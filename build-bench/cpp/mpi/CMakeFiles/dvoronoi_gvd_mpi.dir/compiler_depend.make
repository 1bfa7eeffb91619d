# Empty compiler generated dependencies file for dvoronoi_gvd_mpi.
# This may be replaced when dependencies are built.
