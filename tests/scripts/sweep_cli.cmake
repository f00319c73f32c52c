# bedlam run with a [gas] sweep, then bedlam analyze sweep and spectrum on it. -DBEDLAM -DSCENE -DWORK
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${BEDLAM} run ${SCENE} --quiet --out ${WORK}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "run failed (${rc}):\n${out}\n${err}")
endif()
execute_process(COMMAND ${BEDLAM} analyze sweep ${WORK} --no-plots
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0 OR NOT out MATCHES "decreasing branch: 6 stages, U_mf")
  message(FATAL_ERROR "analyze sweep failed (${rc})")
endif()
file(STRINGS ${WORK}/analysis/sweep.csv rows)
list(LENGTH rows n)
if(NOT n EQUAL 15) # header, 13 stages (7 up to 1.6, 6 back down to 0.4), the U_mf comment
  message(FATAL_ERROR "sweep.csv has ${n} lines, expected 15")
endif()
execute_process(COMMAND ${BEDLAM} analyze spectrum ${WORK} --from 0.5 --no-plots
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0 OR NOT EXISTS ${WORK}/analysis/spectrum.csv)
  message(FATAL_ERROR "analyze spectrum failed (${rc})")
endif()
execute_process(COMMAND ${BEDLAM} analyze mean ${WORK} --column mean_height --from 0.5
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0 OR NOT out MATCHES "mean_height from 0.5")
  message(FATAL_ERROR "analyze mean failed (${rc})")
endif()
