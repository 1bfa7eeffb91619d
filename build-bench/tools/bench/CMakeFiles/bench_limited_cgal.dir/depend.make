# Empty dependencies file for bench_limited_cgal.
# This may be replaced when dependencies are built.
