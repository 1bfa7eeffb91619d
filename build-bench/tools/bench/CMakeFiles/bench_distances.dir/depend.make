# Empty dependencies file for bench_distances.
# This may be replaced when dependencies are built.
