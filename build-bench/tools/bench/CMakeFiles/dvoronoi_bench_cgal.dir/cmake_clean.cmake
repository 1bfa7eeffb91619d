file(REMOVE_RECURSE
  "CMakeFiles/dvoronoi_bench_cgal.dir/bench_cgal.cpp.o"
  "CMakeFiles/dvoronoi_bench_cgal.dir/bench_cgal.cpp.o.d"
  "libdvoronoi_bench_cgal.a"
  "libdvoronoi_bench_cgal.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/dvoronoi_bench_cgal.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
