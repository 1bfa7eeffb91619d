file(REMOVE_RECURSE
  "CMakeFiles/bench_voronoi_cgal.dir/bench_voronoi_cgal.cpp.o"
  "CMakeFiles/bench_voronoi_cgal.dir/bench_voronoi_cgal.cpp.o.d"
  "bench_voronoi_cgal"
  "bench_voronoi_cgal.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/bench_voronoi_cgal.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
