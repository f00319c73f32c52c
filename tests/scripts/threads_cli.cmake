# bedlam run gives byte-identical final states with --threads 1 and --threads 2.
file(REMOVE_RECURSE ${WORK})
foreach(t 1 2)
  execute_process(COMMAND ${BEDLAM} run ${SCENE} --steps 400 --threads ${t} --quiet --out ${WORK}/t${t}
    RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "run with ${t} threads failed: ${rc}")
  endif()
endforeach()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files
  ${WORK}/t1/checkpoint/state.bdlckpt ${WORK}/t2/checkpoint/state.bdlckpt RESULT_VARIABLE same)
if(NOT same EQUAL 0)
  message(FATAL_ERROR "states after 400 steps differ between 1 and 2 threads")
endif()
