# Runs a command and checks its exit code and, optionally, that its output contains a text (and
# that it lacks another).
#   cmake -DEXPECT=2 -DCONTAINS="density" [-DLACKS="regex"] -DCMD="a;b;c" -P expect_exit.cmake
execute_process(COMMAND ${CMD} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT "${rc}" STREQUAL "${EXPECT}")
  message(FATAL_ERROR "exit code ${rc}, expected ${EXPECT}")
endif()
if(DEFINED CONTAINS AND NOT "${out}${err}" MATCHES "${CONTAINS}")
  message(FATAL_ERROR "output does not contain '${CONTAINS}'")
endif()
if(DEFINED LACKS AND "${out}${err}" MATCHES "${LACKS}")
  message(FATAL_ERROR "output contains '${LACKS}'")
endif()
