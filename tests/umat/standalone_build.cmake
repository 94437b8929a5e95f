# CTest driver (issue 11): the UMAT alone, as a user of Abaqus or CalculiX builds it, on a machine where
# PETSc, MPI, HDF5 and libyaml cannot be found. Configures, builds, tests and installs umat/ as its own
# project in a scratch directory, then configures the whole project with -DCAMCLAY9_DRIVER=OFF.
# Asserts: every step succeeds; the cache of either configuration holds no PETSc/MPI/HDF5/yaml entry
# (nothing was looked for); the install has the library, the package files, the single-file UMATs and
# the object, and no driver, scenes or meshes.
# Usage: cmake -DSRC=<project source> -DWORK=<scratch dir> -P standalone_build.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/empty_pkgconfig)
set(ENV{PKG_CONFIG_LIBDIR} ${WORK}/empty_pkgconfig)
set(ENV{PKG_CONFIG_PATH} "")
unset(ENV{PETSC_DIR})
unset(ENV{PETSC_ARCH})
set(hide -DCMAKE_DISABLE_FIND_PACKAGE_PETSc=ON -DCMAKE_DISABLE_FIND_PACKAGE_MPI=ON
         -DCMAKE_DISABLE_FIND_PACKAGE_HDF5=ON -DCMAKE_DISABLE_FIND_PACKAGE_PkgConfig=ON)

function(run what)
  execute_process(COMMAND ${ARGN} TIMEOUT 900 RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc)
    message(FATAL_ERROR "standalone UMAT: ${what} failed (exit ${rc})\n${out}\n${err}")
  endif()
  message(STATUS "standalone UMAT: ${what}: ok")
endfunction()

function(assert_nothing_looked_for cache)
  file(STRINGS ${cache} found REGEX "^(PETSC|PkgConfig|PKG_CONFIG|MPI|HDF5|YAML)[A-Za-z0-9_]*[:=]")
  if(found)
    message(FATAL_ERROR "standalone UMAT: ${cache} has driver dependencies: ${found}")
  endif()
endfunction()

set(b ${WORK}/build)
run("configure umat/ alone" ${CMAKE_COMMAND} -S ${SRC}/umat -B ${b} -DCMAKE_BUILD_TYPE=Release ${hide})
assert_nothing_looked_for(${b}/CMakeCache.txt)
run("build" ${CMAKE_COMMAND} --build ${b} -j 2)
# Its own tests: the UMAT's and tests/calculix (same_mesh skips: no driver here). The CalculiX run
# (calculix.drop_in, ~20 s) and the host files (umat.host_*, ~15-40 s) are left to the full build, which
# runs them on the same code; the installed host files are checked below.
# umat.nonfinite_host_file and _abaqus_file run the host files too (their fixture is umat.host_files_compile).
run("ctest" ${CMAKE_CTEST_COMMAND} --test-dir ${b} --output-on-failure
    -E "^calculix[.]drop_in$|^umat[.]host_|^umat[.]nonfinite_(host|abaqus)_file$")
run("install" ${CMAKE_COMMAND} --install ${b} --prefix ${WORK}/prefix)
foreach(f share/camclay9/camclay9_umat.f90 share/camclay9/camclay9_umat_abaqus.for share/camclay9/camclay9_umat.o
          include/camclay9/camclay9.h
          include/camclay9/ccix_props.mod lib/libcamclay9.a lib/cmake/CamClay9/CamClay9Config.cmake
          lib/cmake/CamClay9/CamClay9Targets.cmake)
  if(NOT EXISTS ${WORK}/prefix/${f})
    message(FATAL_ERROR "standalone UMAT: not installed: ${f}")
  endif()
endforeach()
foreach(f bin share/camclay9/input share/camclay9/meshes)
  if(EXISTS ${WORK}/prefix/${f})
    message(FATAL_ERROR "standalone UMAT: installed although only the UMAT was built: ${f}")
  endif()
endforeach()
# The exported targets name the Fortran runtime CMake found, not a list written in the project.
file(READ ${WORK}/prefix/lib/cmake/CamClay9/CamClay9Targets.cmake targets)
if(NOT targets MATCHES "INTERFACE_LINK_LIBRARIES \"gfortran")
  message(FATAL_ERROR "standalone UMAT: exported targets do not link the Fortran runtime:\n${targets}")
endif()

# The whole project with the driver switched off: configures without PETSc & co., installs no driver.
set(t ${WORK}/top)
run("configure the project with -DCAMCLAY9_DRIVER=OFF"
    ${CMAKE_COMMAND} -S ${SRC} -B ${t} -DCMAKE_BUILD_TYPE=Release -DCAMCLAY9_DRIVER=OFF ${hide})
assert_nothing_looked_for(${t}/CMakeCache.txt)
file(GLOB_RECURSE install_scripts ${t}/cmake_install.cmake)
foreach(s ${install_scripts})
  file(STRINGS ${s} hits REGEX "bin/driver|share/camclay9/input|share/camclay9/meshes")
  if(hits)
    message(FATAL_ERROR "standalone UMAT: CAMCLAY9_DRIVER=OFF still installs driver parts: ${hits}")
  endif()
endforeach()
if(EXISTS ${t}/driver)
  message(FATAL_ERROR "standalone UMAT: CAMCLAY9_DRIVER=OFF still configures driver/")
endif()
