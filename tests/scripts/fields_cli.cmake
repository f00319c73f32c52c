# bedlam run with particle files, then bedlam analyze fields on them: every particle's volume on
# the grid, fields.vti written; a truncated particle file refused with its name. -DBEDLAM -DSCENE -DWORK
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${BEDLAM} run ${SCENE} --quiet --out ${WORK} --set run.end_time=0.1
  --set output.vtk_interval=0.02 --set output.frame_interval=0
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "run failed (${rc}):\n${out}\n${err}")
endif()
execute_process(COMMAND ${BEDLAM} analyze fields ${WORK} --from 0.03 --cell 0.0075
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0 OR NOT EXISTS ${WORK}/analysis/fields.vti)
  message(FATAL_ERROR "analyze fields failed (${rc})")
endif()
# 4 files (0.04 to 0.1 s) of 800 beads, all inside the domain: the grid holds their volume.
if(NOT out MATCHES "4 particle files from [0-9.]+ to [0-9.]+ s, 3200 particle samples; solids volume on the grid ([0-9.e-]+) m\\^3 of ([0-9.e-]+)")
  message(FATAL_ERROR "unexpected summary")
endif()
if(NOT CMAKE_MATCH_1 STREQUAL CMAKE_MATCH_2)
  message(FATAL_ERROR "volume on the grid ${CMAKE_MATCH_1} differs from the particles' ${CMAKE_MATCH_2}")
endif()
file(GLOB files ${WORK}/vtk/particles_*.vtp)
list(GET files -1 last)
execute_process(COMMAND head -c 3000 ${last} OUTPUT_FILE ${WORK}/cut.vtp)
file(RENAME ${WORK}/cut.vtp ${last})
execute_process(COMMAND ${BEDLAM} analyze fields ${WORK} --from 0.03
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 2 OR NOT err MATCHES "particles_000005.vtp is truncated: array '[a-zA-Z]+' runs past the end")
  message(FATAL_ERROR "a truncated particle file was not refused (${rc})")
endif()
