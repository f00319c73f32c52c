# bedlam run with a [gas] sweep, then bedlam analyze sweep and spectrum on it. -DBEDLAM -DSCENE -DWORK
include(${CMAKE_CURRENT_LIST_DIR}/run_util.cmake)
bdl_fresh_run()
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
if(NOT rc EQUAL 0 OR NOT EXISTS ${WORK}/analysis/spectrum_pressure_drop.csv)
  message(FATAL_ERROR "analyze spectrum failed (${rc})")
endif()
execute_process(COMMAND ${BEDLAM} analyze spectrum ${WORK} --from 0.5 --segments 3 --no-plots
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0 OR NOT out MATCHES "Welch's average over 3 half-overlapping pieces")
  message(FATAL_ERROR "analyze spectrum --segments 3 failed (${rc})")
endif()
execute_process(COMMAND ${BEDLAM} analyze spectrum ${WORK} --from 0.5 --segments 0 --no-plots
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "--segments from 1 to 1000")
  message(FATAL_ERROR "analyze spectrum --segments 0: exit ${rc}, ${err}")
endif()
execute_process(COMMAND ${BEDLAM} analyze mean ${WORK} --column mean_height --from 0.5
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0 OR NOT out MATCHES "mean_height from 0.5")
  message(FATAL_ERROR "analyze mean failed (${rc})")
endif()
execute_process(COMMAND ${BEDLAM} analyze profile ${WORK} --from 0.5 --no-plots
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
file(STRINGS ${WORK}/analysis/profile.csv rows)
list(LENGTH rows n)
list(GET rows 1 first)
string(REPLACE "," ";" first "${first}")
list(GET first 1 phi)
# 15 layers of 4 mm; the lowest layer holds a fluidized or packed bed (solids fraction 0.3-0.65).
if(NOT rc EQUAL 0 OR NOT n EQUAL 16 OR phi LESS 0.3 OR phi GREATER 0.65)
  message(FATAL_ERROR "analyze profile failed (${rc}), ${n} lines, lowest layer ${phi}")
endif()
