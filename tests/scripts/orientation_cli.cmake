# orientation.csv of a run with rods ([output] orientation_interval): one row per interval, the
# same bytes on one thread and on two and after a --resume; then bedlam analyze orientation on it.
# -DBEDLAM -DSCENE -DWORK
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${BEDLAM} run ${SCENE} --quiet --threads 1 --out ${WORK}/one RESULT_VARIABLE a)
execute_process(COMMAND ${BEDLAM} run ${SCENE} --quiet --threads 2 --until 0.071 --out ${WORK}/split
  RESULT_VARIABLE b)
execute_process(COMMAND ${BEDLAM} run ${SCENE} --quiet --threads 2 --resume ${WORK}/split RESULT_VARIABLE c)
if(NOT a EQUAL 0 OR NOT b EQUAL 0 OR NOT c EQUAL 0)
  message(FATAL_ERROR "runs failed: ${a} ${b} ${c}")
endif()
file(STRINGS ${WORK}/one/orientation.csv rows)
list(LENGTH rows n)
list(GET rows 0 header)
string(REPLACE "," ";" columns "${header}")
list(LENGTH columns m)
# 0.15 s every 2 ms: 76 rows and the header; time, inlet velocity and (2 + 36) per zone.
if(NOT n EQUAL 77 OR NOT m EQUAL 78)
  message(FATAL_ERROR "orientation.csv: ${n} lines of ${m} columns, expected 77 of 78")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files
  ${WORK}/one/orientation.csv ${WORK}/split/orientation.csv RESULT_VARIABLE same)
if(NOT same EQUAL 0)
  message(FATAL_ERROR "orientation.csv differs between one thread and two threads with a resume")
endif()
# The run's PDFs per stage of its sweep (0.5, 1, 1.5, 1, 0.5 m/s): five, each integrating to 1.
execute_process(COMMAND ${BEDLAM} analyze orientation ${WORK}/one --by-velocity --no-plots
  RESULT_VARIABLE rc)
file(STRINGS ${WORK}/one/analysis/orientation_summary.csv stages)
list(LENGTH stages n)
if(NOT rc EQUAL 0 OR NOT n EQUAL 6)
  message(FATAL_ERROR "analyze orientation --by-velocity: exit ${rc}, ${n} lines, expected 6")
endif()
