file(REMOVE_RECURSE
  "CMakeFiles/asr_timing.dir/asr_timing.cpp.o"
  "CMakeFiles/asr_timing.dir/asr_timing.cpp.o.d"
  "asr_timing"
  "asr_timing.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/asr_timing.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
