file(REMOVE_RECURSE
  "CMakeFiles/bench_limited_cgal.dir/bench_limited_cgal.cpp.o"
  "CMakeFiles/bench_limited_cgal.dir/bench_limited_cgal.cpp.o.d"
  "bench_limited_cgal"
  "bench_limited_cgal.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/bench_limited_cgal.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
