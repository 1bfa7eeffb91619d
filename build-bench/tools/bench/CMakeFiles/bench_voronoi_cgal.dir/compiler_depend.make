# Empty compiler generated dependencies file for bench_voronoi_cgal.
# This may be replaced when dependencies are built.
