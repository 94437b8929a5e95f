# CTest driver (issue 11): `cmake --install` puts the scenes and meshes next to the driver, and the
# installed driver runs an installed scene. Asserts: every file under input/ and meshes/ of the source
# tree (generated meshes and results excepted) is in <prefix>/share/camclay9/, no generated file is,
# and the installed driver integrates the installed oedometer scene (exit 0, its summary line).
# Usage: cmake -DBUILD=<build dir> -DSRC=<project source> -DWORK=<scratch dir> -P installed_scenes.cmake
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD} --prefix ${WORK}/prefix
                TIMEOUT 600 RESULT_VARIABLE rc OUTPUT_QUIET)
if(rc)
  message(FATAL_ERROR "installed scenes: cmake --install failed")
endif()
set(share ${WORK}/prefix/share/camclay9)
foreach(dir input meshes)
  file(GLOB_RECURSE files RELATIVE ${SRC} ${SRC}/${dir}/*)
  list(FILTER files EXCLUDE REGEX "\\.(msh|h5|xdmf)$|/out/|__pycache__")
  list(LENGTH files n)
  if(n EQUAL 0)
    message(FATAL_ERROR "installed scenes: no files found under ${SRC}/${dir}")
  endif()
  foreach(f ${files})
    if(NOT EXISTS ${share}/${f})
      message(FATAL_ERROR "installed scenes: not installed: ${f}")
    endif()
  endforeach()
  message(STATUS "installed scenes: ${n} files of ${dir}/ installed")
endforeach()
file(GLOB_RECURSE generated ${share}/*.msh ${share}/*.h5 ${share}/*.xdmf)
if(generated)
  message(FATAL_ERROR "installed scenes: generated files installed: ${generated}")
endif()
execute_process(COMMAND ${WORK}/prefix/bin/driver -input ${share}/input/point/oedometer.yaml
                        -output_dir ${WORK}/out
                TIMEOUT 600 RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc OR NOT out MATCHES "point scene oedometer: [0-9]+ steps" OR NOT EXISTS ${WORK}/out/history.csv)
  message(FATAL_ERROR "installed scenes: the installed driver did not run the installed scene "
                      "(exit ${rc})\n${out}\n${err}")
endif()
