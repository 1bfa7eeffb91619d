file(REMOVE_RECURSE
  "CMakeFiles/bench_distances.dir/bench_distances.cpp.o"
  "CMakeFiles/bench_distances.dir/bench_distances.cpp.o.d"
  "bench_distances"
  "bench_distances.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/bench_distances.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
