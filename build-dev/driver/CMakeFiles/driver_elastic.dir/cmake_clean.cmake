file(REMOVE_RECURSE
  "../bin/driver_elastic"
  "../bin/driver_elastic.pdb"
  "CMakeFiles/driver_elastic.dir/src/app/main.c.o"
  "CMakeFiles/driver_elastic.dir/src/app/main.c.o.d"
)

# Per-language clean rules from dependency scanning.
foreach(lang C)
  include(CMakeFiles/driver_elastic.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
