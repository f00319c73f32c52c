# A FIFO given as the scene, as the particle file or as the checkpoint to resume from is refused
# at once (exit 2, "is not a regular file (a FIFO)"): nothing opens it, so nothing waits for a
# writer. Each command gets 5 s; a reader blocked on the FIFO would be killed and fail the test.
#   cmake -DBEDLAM=... -DSCENE=tests/scenes/limits_file.ini -DWORK=... -P fifo_cli.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND mkfifo ${WORK}/fifo RESULT_VARIABLE made)
if(NOT made EQUAL 0)
  message(FATAL_ERROR "mkfifo failed (${made})")
endif()
set(cases
  "check|${WORK}/fifo"
  "check|${SCENE}|--set|create.bed.file=${WORK}/fifo"
  "run|${SCENE}|--quiet|--out|${WORK}/run|--resume|${WORK}/fifo")
foreach(case ${cases})
  string(REPLACE "|" ";" args "${case}")
  execute_process(COMMAND ${BEDLAM} ${args} TIMEOUT 5
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("bedlam ${args}: exit ${rc}: ${out}${err}")
  if(NOT "${rc}" STREQUAL "2")
    message(FATAL_ERROR "exit ${rc}, expected 2 within 5 s")
  endif()
  if(NOT "${out}${err}" MATCHES "fifo.* is not a regular file \\(a FIFO\\)")
    message(FATAL_ERROR "the message does not say the FIFO is not a regular file")
  endif()
endforeach()
