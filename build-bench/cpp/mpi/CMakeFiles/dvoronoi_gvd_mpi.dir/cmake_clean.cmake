file(REMOVE_RECURSE
  "CMakeFiles/dvoronoi_gvd_mpi.dir/gvd_mpi.cpp.o"
  "CMakeFiles/dvoronoi_gvd_mpi.dir/gvd_mpi.cpp.o.d"
  "dvoronoi_gvd_mpi"
  "dvoronoi_gvd_mpi.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/dvoronoi_gvd_mpi.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
