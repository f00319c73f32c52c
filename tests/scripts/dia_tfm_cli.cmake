# A synthetic camera filming a solids phase on the grid: bedlam run, then the truth beside the
# first image checked (dia_tfm_check.py). -DBEDLAM -DSCENE -DWORK -DPYTHON
include(${CMAKE_CURRENT_LIST_DIR}/run_util.cmake)
bdl_fresh_run()
foreach(f frame_000000.png frame_000000_particles.csv frame_000002_cells.csv)
  if(NOT EXISTS ${WORK}/dia/front/${f})
    message(FATAL_ERROR "dia/front/${f} was not written")
  endif()
endforeach()
execute_process(COMMAND ${PYTHON} ${CMAKE_CURRENT_LIST_DIR}/dia_tfm_check.py
  ${WORK}/dia/front/frame_000000_cells.csv
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the camera's truth of the solids phase is wrong")
endif()
