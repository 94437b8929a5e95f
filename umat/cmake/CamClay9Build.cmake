# Build settings shared by the whole project (top-level CMakeLists.txt) and the UMAT built alone
# (umat/CMakeLists.txt as the top-level project). Included after project().
if(NOT CMAKE_BUILD_TYPE AND NOT CMAKE_CONFIGURATION_TYPES)
  set(CMAKE_BUILD_TYPE Release CACHE STRING "Build type" FORCE)
endif()
set(CMAKE_POSITION_INDEPENDENT_CODE ON)
set(CMAKE_C_STANDARD 11)

option(CAMCLAY9_NATIVE "Optimise for this machine's CPU (-march=native); off for portable binaries" OFF)
if(CMAKE_Fortran_COMPILER_ID STREQUAL "GNU")
  set(CAMCLAY9_FFLAGS -Wall -Wno-unused-dummy-argument)
  set(CMAKE_Fortran_FLAGS_RELEASE "-O3 -funroll-loops")
  set(CMAKE_Fortran_FLAGS_DEBUG "-O0 -g -fcheck=all -ffpe-trap=invalid,zero,overflow -fbacktrace")
  if(CAMCLAY9_NATIVE)
    list(APPEND CAMCLAY9_FFLAGS -march=native)
  endif()
endif()
