file(REMOVE_RECURSE
  "libdvoronoi_bench_cgal.a"
)
