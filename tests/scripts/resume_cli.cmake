# bedlam run --resume continues bit-for-bit: a 300-step run and a 150 + 150-step run with a
# resume in between end in byte-identical checkpoints.
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${BEDLAM} run ${SCENE} --steps 300 --quiet --out ${WORK}/straight RESULT_VARIABLE a)
execute_process(COMMAND ${BEDLAM} run ${SCENE} --steps 150 --quiet --out ${WORK}/split RESULT_VARIABLE b)
execute_process(COMMAND ${BEDLAM} run ${SCENE} --steps 150 --quiet --resume ${WORK}/split RESULT_VARIABLE c)
if(NOT a EQUAL 0 OR NOT b EQUAL 0 OR NOT c EQUAL 0)
  message(FATAL_ERROR "runs failed: ${a} ${b} ${c}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files
  ${WORK}/straight/checkpoint/state.bdlckpt ${WORK}/split/checkpoint/state.bdlckpt RESULT_VARIABLE same)
if(NOT same EQUAL 0)
  message(FATAL_ERROR "resumed checkpoint differs from the uninterrupted run")
endif()
file(READ ${WORK}/split/diagnostics.csv rows)
string(REGEX MATCHALL "\n" lines "${rows}")
list(LENGTH lines n)
message("resumed diagnostics rows: ${n}")
