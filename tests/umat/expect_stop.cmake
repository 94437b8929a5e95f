# Run EXE; pass only if it exits non-zero AND prints the message matching REGEX (stdout or stderr)
# AND never prints "returned instead of stopping". Usage:
#   cmake -DEXE=<program> -DREGEX=<regex> -P expect_stop.cmake
execute_process(COMMAND ${EXE} TIMEOUT 600 RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}exit status: ${rc}")
if(rc STREQUAL "0")
  message(FATAL_ERROR "${EXE} exited 0: the UMAT must stop (error stop) on bad PROPS")
endif()
if(NOT "${out}${err}" MATCHES "${REGEX}")
  message(FATAL_ERROR "${EXE}: the expected message /${REGEX}/ was not printed")
endif()
if("${out}${err}" MATCHES "returned instead of stopping")
  message(FATAL_ERROR "${EXE}: the UMAT returned instead of stopping")
endif()
