# CTest driver (issue 34): NaN and +-Inf in every real argument of the UMAT, in a host built with
# floating-point traps on (-ffpe-trap=invalid,zero,overflow), for one form of the UMAT: EXE is
# tests/umat/host_nonfinite.f90 linked with the library, the host file camclay9_umat.f90 or the Abaqus
# file camclay9_umat_abaqus.for (with the mock Abaqus). Standard error goes to a FILE, as a host's log:
# gfortran buffers it then, so a message not flushed comes out after the lines written past it.
#
#   rejections   exit 0 (a signal is not an exit code: SIGFPE fails), all cases passed (the program's
#                own count), and each rejected argument's line, "Cam-Clay IX UMAT: <argument> =
#                <NaN|Infinity|-Infinity>: expected ...; increment rejected (PNEWDT < 1) at element 12,
#                integration point 1", right before the host's "host: <argument> returned" (FORM
#                stderr), or in the same order as "***WARNING: ..." lines in job.msg and nothing on
#                standard error (FORM abaqus); arguments the UMAT does not read give no line.
#   props K V    for K = 1..23 and V = nan, inf, -inf: the UMAT stops (exit 1 from error stop; the
#                mock Abaqus' XIT: 3), never a signal, and never "host: PROPS returned"; the message
#                "PROPS(K) = <V>: expected a finite number, stopping at element 12, integration point
#                1, material WOODFORD" after the rejected call's line and before the "ERROR STOP" line
#                (FORM stderr), or "***ERROR: ..." after the "***WARNING: ..." line in job.msg and XIT
#                (FORM abaqus).
# Usage: cmake -DEXE=<program> -DFORM=stderr|abaqus -DWORK=<scratch> -P host_nonfinite.cmake
set(ENV{GFORTRAN_ERROR_BACKTRACE} 0)   # gfortran's backtrace after error stop: 0.2 s per run
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(umat "Cam-Clay IX UMAT: ")
set(value "(NaN|Infinity|-Infinity)")
# Lines are read as CMake lists, so each ";" of a line is read as "," (and the patterns say ",").
set(where ", increment rejected \\(PNEWDT < 1\\) at element 12, integration point 1$")

function(fail what)
  message(FATAL_ERROR "host_nonfinite (${FORM}): ${what}")
endfunction()

# read_lines(FILE VAR): the lines of FILE as a list, each ";" read as ",", "[" and "]" as "(" and ")".
function(read_lines f var)
  file(READ ${f} text)
  string(REPLACE ";" "," text "${text}")
  string(REPLACE "[" "(" text "${text}")
  string(REPLACE "]" ")" text "${text}")
  string(REGEX REPLACE "\n$" "" text "${text}")
  string(REPLACE "\n" ";" text "${text}")
  set(${var} "${text}" PARENT_SCOPE)
endfunction()

# run(ARGS...): EXE ARGS with standard error to ${WORK}/stderr.txt; sets rc, out, err_lines, msg_lines.
function(run)
  file(REMOVE ${WORK}/job.msg)
  execute_process(COMMAND ${EXE} ${ARGN} TIMEOUT 600 RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_FILE ${WORK}/stderr.txt WORKING_DIRECTORY ${WORK})
  read_lines(${WORK}/stderr.txt err_lines)
  set(msg_lines "")
  if(EXISTS ${WORK}/job.msg)
    read_lines(${WORK}/job.msg msg_lines)
  endif()
  foreach(v rc out err_lines msg_lines)
    set(${v} "${${v}}" PARENT_SCOPE)
  endforeach()
endfunction()

# A regex-safe argument name: DROT(1,2) -> DROT\(1,2\).
function(quoted name var)
  string(REGEX REPLACE "([()])" "\\\\\\1" q "${name}")
  set(${var} "${q}" PARENT_SCOPE)
endfunction()

# --- rejections ---
run(rejections)
if(NOT rc STREQUAL "0")
  file(READ ${WORK}/stderr.txt err)
  fail("rejections: exit '${rc}', expected 0 (a signal is a failure)\n${out}${err}")
endif()
if(NOT out MATCHES "host_nonfinite: [0-9]+ cases, 0 failed")
  fail("rejections: ${out}")
endif()
set(previous "")
set(expected_warnings "")
set(n 0)
foreach(line IN LISTS err_lines)
  if(line MATCHES "^host: (.*) returned$")
    set(name "${CMAKE_MATCH_1}")
    quoted("${name}" q)
    set(message_line "^${umat}${q} = ${value}: expected .*${where}")
    if(name MATCHES "^(DTIME|DSTRAN\\(.\\)|DROT\\(.,.\\)|STATEV\\([0-9]+\\)|STRESS\\(.\\))$")
      math(EXPR n "${n} + 1")
      if(FORM STREQUAL "stderr" AND NOT previous MATCHES "${message_line}")
        fail("rejections: '${line}' not right after its message: '${previous}'")
      endif()
      list(APPEND expected_warnings "${q}")
    elseif(previous MATCHES "^Cam-Clay")
      fail("rejections: '${line}' (an argument not read) came after a message: '${previous}'")
    endif()
  elseif(FORM STREQUAL "abaqus")
    fail("rejections: on standard error in the Abaqus file: '${line}'")
  endif()
  set(previous "${line}")
endforeach()
if(n LESS 150)
  fail("rejections: only ${n} rejected calls seen")
endif()
if(FORM STREQUAL "abaqus")
  list(LENGTH expected_warnings ne)
  list(LENGTH msg_lines nm)
  if(NOT ne EQUAL nm)
    fail("rejections: ${nm} lines in job.msg, expected ${ne}")
  endif()
  math(EXPR last "${ne} - 1")
  foreach(i RANGE ${last})
    list(GET expected_warnings ${i} q)
    list(GET msg_lines ${i} line)
    if(NOT line MATCHES "^\\*\\*\\*WARNING: ${umat}${q} = ${value}: expected .*${where}")
      fail("rejections: job.msg line ${i}: '${line}', expected the warning of ${q}")
    endif()
  endforeach()
endif()
message(STATUS "host_nonfinite (${FORM}): rejections: ${n} rejected calls, each with its message in order")

# --- props K V: stops ---
set(stop_rc 1)
if(FORM STREQUAL "abaqus")
  set(stop_rc 3)
endif()
foreach(k RANGE 1 23)
  foreach(v nan inf -inf)
    run(props ${k} ${v})
    set(case "PROPS(${k}) = ${v}")
    file(READ ${WORK}/stderr.txt err)
    if(NOT rc STREQUAL "${stop_rc}")
      fail("${case}: exit '${rc}', expected ${stop_rc} (a signal is a failure)\n${out}${err}")
    endif()
    if(err MATCHES "host: PROPS returned")
      fail("${case}: the UMAT returned instead of stopping")
    endif()
    set(rejected_line "${umat}DSTRAN\\(1\\) = NaN: expected a finite strain increment${where}")
    set(stop_line "${umat}PROPS\\(${k}\\) = +${value}: expected a finite number, stopping at element 12, ")
    set(stop_line "${stop_line}integration point 1, material WOODFORD$")
    if(FORM STREQUAL "stderr")
      set(lines "${err_lines}")
      set(patterns "^${rejected_line}" "^host: DSTRAN\\(1\\) returned$" "^${stop_line}" "^ERROR STOP ")
    else()
      set(lines "${msg_lines}")
      set(patterns "^\\*\\*\\*WARNING: ${rejected_line}" "^\\*\\*\\*ERROR: ${stop_line}")
      if(NOT out MATCHES "mock Abaqus: XIT called")
        fail("${case}: XIT not called\n${out}")
      endif()
    endif()
    # The patterns in this order, each on a line after the previous one's.
    set(at -1)
    foreach(p IN LISTS patterns)
      set(found -1)
      set(i 0)
      foreach(line IN LISTS lines)
        if(i GREATER at AND line MATCHES "${p}")
          set(found ${i})
          break()
        endif()
        math(EXPR i "${i} + 1")
      endforeach()
      if(found LESS 0)
        fail("${case}: /${p}/ not found after line ${at} of:\n${err}\njob.msg: ${msg_lines}")
      endif()
      set(at ${found})
    endforeach()
  endforeach()
endforeach()
message(STATUS "host_nonfinite (${FORM}): PROPS 1-23 NaN, +Inf, -Inf: each stops with its message, in order")
