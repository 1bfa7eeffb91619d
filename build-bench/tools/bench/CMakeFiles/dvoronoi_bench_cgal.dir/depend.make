# Empty dependencies file for dvoronoi_bench_cgal.
# This may be replaced when dependencies are built.
