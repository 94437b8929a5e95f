# CTest driver (issue 21): the single-file UMATs as hosts compile them. STEP=compile installs them
# (cmake --install, component host_files) and compiles each the way a host does; STEP=threads and
# STEP=errors run the programs built from them (tests/umat/host_driver.c).
#
#   compile  The installed camclay9_umat.f90 and camclay9_umat_abaqus.for, each compiled as:
#              host      camclay9_umat.f90, gfortran -O2 -fPIC (docs/umat.md; no OpenMP flag)
#              hazard    camclay9_umat.f90 with -fopenmp-simd -fno-automatic: flags under which an OpenMP
#                        threadprivate cache is silently shared, and non-RECURSIVE locals are static
#              hook      camclay9_umat.f90 with -cpp -DCAMCLAY9_STOP_HOOK=test_host_stop (the host's stop)
#              cpp       camclay9_umat.f90 with -cpp and the Abaqus flags below
#              abaqus72  camclay9_umat_abaqus.for with -cpp, fixed form in 72 columns (gfortran's default)
#              abaqus    camclay9_umat_abaqus.for with -cpp and the Abaqus flags, 132 columns
#            The Abaqus flags are gfortran's nearest to the compile line of Abaqus/Standard on Linux
#            (ifort -c -fpp -fPIC -extend_source -DABQ_LNX86_64 -DABQ_FORTRAN -auto -no-fma
#            -fprotect-parens -fstack-protector-strong -msse3 ..., docs/umat.md): -cpp -fPIC
#            -ffixed-line-length-132 -DABQ_LNX86_64 -DABQ_FORTRAN -frecursive -ffp-contract=off
#            -fprotect-parens -fstack-protector-strong -msse3. Only "host" is optimised (-O2, the line
#            docs/umat.md gives); the others test flags and forms, and compile faster at -O0. The Abaqus
#            file includes aba_param.inc, here the stand-in of tests/umat/mock_abaqus/, and its XIT is
#            mock_abaqus.f90's.
#            Asserts: every compile succeeds; the C preprocessor changes nothing in either file (its
#            output equals the file but for blank lines); no object has writable static data (nm: no
#            B/D/C/G/S symbol but gfortran's constant type descriptors __vtab_*, __def_init_*).
#            And tests/umat/host_nonfinite.f90 with floating-point traps on (-ffpe-trap=invalid,zero,
#            overflow) linked with host and abaqus, for umat.nonfinite_host_file and
#            umat.nonfinite_abaqus_file (host_nonfinite.cmake).
#   threads  host_driver threads with host, hazard, abaqus and the installed camclay9_umat.o (whose
#            per-thread cache is thread-local storage): 8 POSIX threads, 8 materials, every
#            STRESS/STATEV/DDSDDE/PNEWDT bit for bit the serial run's.
#   jacobi   tests/umat/test_against_jacobi.f90 linked with host, abaqus and the installed object: the host
#            file within 1e-12 of the numbers stored from the Jacobi derivation (as umat.test_against_jacobi
#            for the library), and the three builds' outputs of the 64 calls identical bit for bit (the
#            object keeps and prepares its material per thread; the files derive it in every call).
#   errors   bad PROPS: host stops (non-zero exit) with the message on standard error; hook: the host's
#            routine gets the message and ends the process (exit 3); abaqus: "***ERROR: ..." in job.msg
#            (unit 7) and XIT (exit 3). DTIME = -1: rejected with a message (standard error; abaqus:
#            "***WARNING: ..." in job.msg) and the analysis goes on (exit 0).
# Usage: cmake -DSTEP=compile|threads|jacobi|errors -DBUILD=<build dir> -DSRC=<project source> -DWORK=<scratch>
#              -DFC=<Fortran compiler> -DCC=<C compiler> -DNM=<nm> [-DHOST_SOURCE=<free-form file>]
#              -P host_files.cmake
# HOST_SOURCE replaces the installed camclay9_umat.f90 (to run the same checks on another version).
set(here ${SRC}/tests/umat)
set(mock ${here}/mock_abaqus)
set(abaqus_like -cpp -fPIC -DABQ_LNX86_64 -DABQ_FORTRAN -frecursive -ffp-contract=off -fprotect-parens
                 -fstack-protector-strong -msse3)

function(run what expect_rc)
  execute_process(COMMAND ${ARGN} TIMEOUT 600 RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
                  WORKING_DIRECTORY ${cwd})
  message("${out}${err}")
  if(NOT "${rc}" STREQUAL "${expect_rc}")
    message(FATAL_ERROR "host files: ${what}: exit ${rc}, expected ${expect_rc}")
  endif()
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()

function(expect text regex what)
  if(NOT "${text}" MATCHES "${regex}")
    message(FATAL_ERROR "host files: ${what}: /${regex}/ not found")
  endif()
endfunction()

function(expect_not text regex what)
  if("${text}" MATCHES "${regex}")
    message(FATAL_ERROR "host files: ${what}: /${regex}/ found")
  endif()
endfunction()

set(cwd ${WORK})
if(STEP STREQUAL "compile")
  file(REMOVE_RECURSE ${WORK})
  file(MAKE_DIRECTORY ${WORK})
  run("cmake --install (component host_files)" 0
      ${CMAKE_COMMAND} --install ${BUILD} --prefix ${WORK}/prefix --component host_files)
  set(plain ${WORK}/prefix/share/camclay9/camclay9_umat.f90)
  set(abaqus ${WORK}/prefix/share/camclay9/camclay9_umat_abaqus.for)
  if(HOST_SOURCE)
    set(plain ${HOST_SOURCE})
  endif()
  foreach(f ${plain} ${abaqus})
    if(NOT EXISTS ${f})
      message(FATAL_ERROR "host files: not installed: ${f}")
    endif()
    # Through the C preprocessor unchanged (blank lines aside), whatever the form.
    execute_process(COMMAND ${FC} -cpp -E -P ${f} TIMEOUT 600 RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(rc OR err)
      message(FATAL_ERROR "host files: the C preprocessor on ${f}: exit ${rc}\n${err}")
    endif()
    file(READ ${f} original)
    string(REGEX REPLACE "\n\n+" "\n" original "\n${original}\n")
    string(REGEX REPLACE "\n\n+" "\n" out "\n${out}\n")
    if(NOT out STREQUAL original)
      message(FATAL_ERROR "host files: the C preprocessor changed ${f}")
    endif()
  endforeach()

  set(variants host hazard hook cpp abaqus72 abaqus)
  set(host_src ${plain})
  set(host_flags -O2 -fPIC)
  set(hazard_src ${plain})
  set(hazard_flags -fPIC -fopenmp-simd -fno-automatic)
  set(hook_src ${plain})
  set(hook_flags -fPIC -cpp -DCAMCLAY9_STOP_HOOK=test_host_stop)
  set(cpp_src ${plain})
  set(cpp_flags ${abaqus_like})
  set(abaqus72_src ${abaqus})
  set(abaqus72_flags -fPIC -cpp -I${mock})
  set(abaqus_src ${abaqus})
  set(abaqus_flags ${abaqus_like} -ffixed-line-length-132 -I${mock})
  run("compile host_driver.c" 0 ${CC} -O2 -pthread -I${SRC}/umat/include -c ${here}/host_driver.c
      -o ${WORK}/host_driver.o)
  run("compile mock_abaqus.f90" 0 ${FC} -O2 -c ${mock}/mock_abaqus.f90 -o ${WORK}/mock_abaqus.o -J ${WORK})
  foreach(v ${variants})
    file(MAKE_DIRECTORY ${WORK}/${v})
    run("compile ${v}: ${${v}_flags}" 0 ${FC} ${${v}_flags} -c ${${v}_src} -o ${WORK}/${v}/umat.o
        -J ${WORK}/${v})
    # No writable static data: the UMAT keeps no state between calls, whatever the flags.
    run("nm ${v}" 0 ${NM} ${WORK}/${v}/umat.o)
    string(REGEX MATCHALL "[0-9a-f]* [BbDdCcGgSs] [^\n]*" data "${out}")
    list(FILTER data EXCLUDE REGEX "__vtab_|__def_init_")
    if(data)
      message(FATAL_ERROR "host files: ${v}: writable static data in the UMAT: ${data}")
    endif()
    set(extra "")
    if(v MATCHES "^abaqus")
      set(extra ${WORK}/mock_abaqus.o)
    endif()
    run("link ${v}" 0 ${FC} -pthread ${WORK}/host_driver.o ${WORK}/${v}/umat.o ${extra}
        -o ${WORK}/host_${v})
    if(v MATCHES "^(host|abaqus)$")
      run("link test_against_jacobi with ${v}" 0 ${FC} -O2 ${here}/test_against_jacobi.f90 ${WORK}/${v}/umat.o
          ${extra} -o ${WORK}/jacobi_${v} -J ${WORK}/${v})
    endif()
  endforeach()
  # Issue 34: a host with floating-point traps on (host_nonfinite.f90, host_nonfinite.cmake) around the
  # host file (-O2) and the Abaqus file (Abaqus' flags, unoptimised) with the mock Abaqus.
  set(traps -cpp -O2 -ffpe-trap=invalid,zero,overflow)
  run("link host_nonfinite with host" 0 ${FC} ${traps} ${here}/host_nonfinite.f90 ${WORK}/host/umat.o
      -o ${WORK}/nonfinite_host -J ${WORK}/host)
  run("link host_nonfinite with abaqus" 0 ${FC} ${traps} -DHOST_NONFINITE_MOCK_ABAQUS ${here}/host_nonfinite.f90
      ${WORK}/abaqus/umat.o ${WORK}/mock_abaqus.o -o ${WORK}/nonfinite_abaqus -J ${WORK}/abaqus)
  # The installed object (the per-thread cache, compiled by the build with OpenMP), linked as it is.
  run("link the installed camclay9_umat.o" 0 ${FC} -pthread ${WORK}/host_driver.o
      ${WORK}/prefix/share/camclay9/camclay9_umat.o -o ${WORK}/host_object)
  run("link test_against_jacobi with the installed camclay9_umat.o" 0 ${FC} -O2 ${here}/test_against_jacobi.f90
      ${WORK}/prefix/share/camclay9/camclay9_umat.o -o ${WORK}/jacobi_object -J ${WORK})
  file(MAKE_DIRECTORY ${WORK}/object)
  message(STATUS "host files: ${variants} compiled, preprocessed unchanged, no static data")

elseif(STEP STREQUAL "threads")
  foreach(v host hazard abaqus object)
    set(cwd ${WORK}/${v})
    run("${v}: 8 threads" 0 ${WORK}/host_${v} threads)
    expect("${out}" "8 threads, [0-9]+ increments: 0 differ" "${v}: threads")
  endforeach()

elseif(STEP STREQUAL "jacobi")
  set(cwd ${WORK})
  run("host file against the Jacobi derivation" 0 ${WORK}/jacobi_host check
      ${here}/data/jacobi_reference.txt)
  expect("${out}" "test_against_jacobi: 0 failed" "host: against the Jacobi derivation")
  foreach(v host abaqus object)
    run("${v}: the 64 calls" 0 ${WORK}/jacobi_${v} write ${WORK}/calls_${v}.txt)
  endforeach()
  foreach(v abaqus object)
    execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/calls_host.txt ${WORK}/calls_${v}.txt
                    TIMEOUT 600 RESULT_VARIABLE differ)
    if(differ)
      message(FATAL_ERROR "host files: the outputs of ${v} differ from the host file's")
    endif()
  endforeach()
  message(STATUS "host files: host, abaqus and object give the same 64 calls bit for bit")

elseif(STEP STREQUAL "errors")
  set(props17 "Cam-Clay IX UMAT: PROPS\\(17\\) =  0\\.000000E\\+00: expected lambda_p > 0 \\(soft frame\\); ")
  set(props17 "${props17}stopping at element 12, integration point 1, material WOODFORD")
  set(dtime "Cam-Clay IX UMAT: DTIME = -1\\.000000E\\+000: expected a finite time increment >= 0; ")
  set(dtime "${dtime}increment rejected \\(PNEWDT < 1\\) at element 12, integration point 1")
  set(cwd ${WORK}/host)
  execute_process(COMMAND ${WORK}/host_host bad_props TIMEOUT 600 RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err WORKING_DIRECTORY ${cwd})
  message("${out}${err}exit ${rc}")
  if(rc STREQUAL "0")
    message(FATAL_ERROR "host files: host: the UMAT did not stop on bad PROPS")
  endif()
  expect("${err}" "${props17}" "host: the message on standard error")
  run("host: DTIME = -1" 0 ${WORK}/host_host rejected)
  expect("${err}" "${dtime}" "host: the rejection on standard error")

  set(cwd ${WORK}/hook)
  run("hook: bad PROPS" 3 ${WORK}/host_hook bad_props)
  expect("${out}" "test host: stopped by the UMAT: ${props17}" "hook: the host's routine got the message")
  expect_not("${err}" "PROPS\\(17\\)" "hook: the default writer was replaced")

  set(cwd ${WORK}/abaqus)
  run("mock Abaqus: bad PROPS" 3 ${WORK}/host_abaqus bad_props)
  expect("${out}" "mock Abaqus: XIT called" "abaqus: XIT")
  expect_not("${err}" "PROPS\\(17\\)" "abaqus: nothing on standard error")
  file(READ ${cwd}/job.msg msg)
  expect("${msg}" "\\*\\*\\*ERROR: ${props17}" "abaqus: the message in job.msg")
  run("mock Abaqus: DTIME = -1" 0 ${WORK}/host_abaqus rejected)
  file(READ ${cwd}/job.msg msg)
  expect("${msg}" "\\*\\*\\*WARNING: ${dtime}" "abaqus: the rejection in job.msg")
  expect_not("${err}" "DTIME" "abaqus: nothing on standard error")
else()
  message(FATAL_ERROR "host_files.cmake: STEP must be compile, threads, jacobi or errors")
endif()
