file(REMOVE_RECURSE
  "../bin/driver"
  "../bin/driver.pdb"
  "CMakeFiles/driver.dir/src/app/main.c.o"
  "CMakeFiles/driver.dir/src/app/main.c.o.d"
)

# Per-language clean rules from dependency scanning.
foreach(lang C)
  include(CMakeFiles/driver.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
