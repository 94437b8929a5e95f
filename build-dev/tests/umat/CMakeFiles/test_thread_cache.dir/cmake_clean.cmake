file(REMOVE_RECURSE
  "CMakeFiles/test_thread_cache.dir/test_thread_cache.f90.o"
  "test_thread_cache"
  "test_thread_cache.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang Fortran)
  include(CMakeFiles/test_thread_cache.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
