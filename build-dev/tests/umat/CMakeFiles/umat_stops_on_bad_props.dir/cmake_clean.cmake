file(REMOVE_RECURSE
  "CMakeFiles/umat_stops_on_bad_props.dir/umat_stops_on_bad_props.f90.o"
  "umat_stops_on_bad_props"
  "umat_stops_on_bad_props.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang Fortran)
  include(CMakeFiles/umat_stops_on_bad_props.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
