# bedlam run with a synthetic camera, then bedlam calibrate on its images and --apply of the fit.
# -DBEDLAM -DSCENE -DWORK
include(${CMAKE_CURRENT_LIST_DIR}/run_util.cmake)
bdl_fresh_run()
set(dir ${WORK}/dia/front)
foreach(f camera.json frames.csv frame_000000_a.png frame_000000_b.png frame_000000_cells.csv
          frame_000000_a_particles.csv frame_000004_b_particles.csv)
  if(NOT EXISTS ${dir}/${f})
    message(FATAL_ERROR "missing ${dir}/${f}")
  endif()
endforeach()
file(STRINGS ${dir}/frames.csv rows)
list(LENGTH rows n)
if(NOT n EQUAL 11) # header + 5 pairs of 2 images (t = 0.01 ... 0.05 s)
  message(FATAL_ERROR "frames.csv has ${n} lines, expected 11")
endif()
file(STRINGS ${dir}/frame_000000_a_particles.csv prow)
list(LENGTH prow np)
if(NOT np EQUAL 301)
  message(FATAL_ERROR "particles truth has ${np} lines, expected 301")
endif()
execute_process(COMMAND ${BEDLAM} calibrate ${dir} --holdout 2 --no-plots
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0 OR NOT EXISTS ${dir}/calibration/fit.json OR NOT out MATCHES "held out")
  message(FATAL_ERROR "calibrate failed (${rc})")
endif()
execute_process(COMMAND ${BEDLAM} calibrate --apply ${dir}/calibration/fit.json
  ${dir}/frame_000001_a.png --cells 5 8 --out ${WORK}/applied
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0 OR NOT EXISTS ${WORK}/applied/frame_000001_a_voidage.csv)
  message(FATAL_ERROR "calibrate --apply failed (${rc})")
endif()
# Resumed into a new folder: the camera's index there starts with its header and goes on with
# the images after the checkpoint (t = 0.07, 0.08: two pairs).
file(REMOVE_RECURSE ${WORK}_resumed)
execute_process(COMMAND ${BEDLAM} run ${SCENE} --quiet --resume ${WORK} --out ${WORK}_resumed
  --until 0.085 RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "resumed run failed (${rc}):\n${out}\n${err}")
endif()
file(STRINGS ${WORK}_resumed/dia/front/frames.csv rows)
list(LENGTH rows n)
list(GET rows 0 head)
if(NOT head STREQUAL "frame,time,image,particles,cells" OR NOT n EQUAL 5)
  message(FATAL_ERROR "resumed frames.csv: '${head}' and ${n} lines, expected the header and 4 images")
endif()
