# Shared by the CLI test scripts (cmake -P): bdl_fresh_run() runs ${SCENE} into an emptied
# ${WORK} with bedlam run (extra options after it), and fails the test with bedlam's output when
# the run does not exit with 0. -DBEDLAM -DSCENE -DWORK
macro(bdl_fresh_run)
  file(REMOVE_RECURSE ${WORK})
  execute_process(COMMAND ${BEDLAM} run ${SCENE} --quiet --out ${WORK} ${ARGN}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "run failed (${rc}):\n${out}\n${err}")
  endif()
endmacro()
