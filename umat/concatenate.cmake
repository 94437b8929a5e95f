# Writes OUT as the concatenation of SOURCES (in order): the single-file UMAT.
file(WRITE ${OUT} "! Cam-Clay IX UMAT, single-file form generated from umat/src/*.f90 by the build.\n")
string(REPLACE "|" ";" SOURCES "${SOURCES}")
foreach(src ${SOURCES})
  get_filename_component(name ${src} NAME)
  file(READ ${src} text)
  file(APPEND ${OUT} "\n! ---- ${name} ----\n${text}")
endforeach()
