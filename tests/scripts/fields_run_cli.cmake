# The time-averaged fields a run writes ([output] fields_interval) against bedlam analyze fields
# on the same particle samples, and across --resume. -DBEDLAM -DSOURCE (the project) -DWORK
#
#   1. spheres with a gas (fields_start and fields_cell given), rods and parcels (the default
#      window and cell): the run's fields.vti is the same bytes as analyze fields' of its
#      particle files (vtk_interval = fields_interval);
#   2. a run stopped at a checkpoint and resumed ends with the same fields.vti and sums as the
#      uninterrupted one; likewise when killed between moving the old sums aside and writing the
#      new ones (the sums of the checkpoint in fields.prev.sums, a later state's in fields.sums);
#   3. without the sums the resumed run says so and averages from where it resumed.
file(REMOVE_RECURSE ${WORK})

function(run_bedlam)
  execute_process(COMMAND ${BEDLAM} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out
    ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "bedlam ${ARGN} failed (${rc}):\n${out}\n${err}")
  endif()
  set(output "${out}${err}" PARENT_SCOPE)
endfunction()

function(same a b what)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${a} ${b} RESULT_VARIABLE differ)
  if(differ)
    message(FATAL_ERROR "${what}: ${a} differs from ${b}")
  endif()
endfunction()

# 1. The run against analyze fields.
set(BED ${SOURCE}/scenes/fluidized_bed.ini)
set(OUTS --set output.vtk_interval=0.02 --set output.frame_interval=0
  --set output.fields_interval=0.02 --set output.fields_start=0.03 --set output.fields_cell=0.0075
  --set run.end_time=0.1 --set output.checkpoint_interval=0.05)
run_bedlam(run ${BED} --quiet --out ${WORK}/bed ${OUTS})
run_bedlam(analyze fields ${WORK}/bed --from 0.03 --cell 0.0075)
if(NOT output MATCHES "4 particle files from")
  message(FATAL_ERROR "analyze fields took other files:\n${output}")
endif()
same(${WORK}/bed/fields.vti ${WORK}/bed/analysis/fields.vti "spheres")
file(READ ${WORK}/bed/run.log log)
if(NOT log MATCHES "fields.vti: 4 samples from t = 0.04[0-9]* to 0.1[0-9]* s")
  message(FATAL_ERROR "run.log does not report the 4 samples:\n${log}")
endif()
foreach(case rods parcels)
  if(case STREQUAL rods)
    set(scene ${SOURCE}/tests/scenes/rod_sweep.ini)
  else()
    set(scene ${SOURCE}/scenes/parcels_fluidized_bed.ini)
  endif()
  run_bedlam(run ${scene} --quiet --out ${WORK}/${case} --set run.end_time=0.03
    --set output.vtk_interval=0.01 --set output.frame_interval=0 --set output.fields_interval=0.01)
  run_bedlam(analyze fields ${WORK}/${case})
  same(${WORK}/${case}/fields.vti ${WORK}/${case}/analysis/fields.vti ${case})
endforeach()

# 2. Stopped at t = 0.05 s (after the sample of 0.04 s) and resumed.
run_bedlam(run ${BED} --quiet --out ${WORK}/split ${OUTS} --until 0.05)
file(COPY ${WORK}/split/ DESTINATION ${WORK}/moved)
file(COPY ${WORK}/split/ DESTINATION ${WORK}/lost)
run_bedlam(run ${BED} --quiet --resume ${WORK}/split ${OUTS})
same(${WORK}/bed/fields.vti ${WORK}/split/fields.vti "resumed")
same(${WORK}/bed/checkpoint/fields.sums ${WORK}/split/checkpoint/fields.sums "resumed sums")
file(RENAME ${WORK}/moved/checkpoint/fields.sums ${WORK}/moved/checkpoint/fields.prev.sums)
file(COPY ${WORK}/bed/checkpoint/fields.sums DESTINATION ${WORK}/moved/checkpoint)
run_bedlam(run ${BED} --quiet --resume ${WORK}/moved ${OUTS})
same(${WORK}/bed/fields.vti ${WORK}/moved/fields.vti "resumed from fields.prev.sums")

# 3. The sums lost: the averages start again at the resume.
file(REMOVE ${WORK}/lost/checkpoint/fields.sums ${WORK}/lost/checkpoint/fields.prev.sums)
run_bedlam(run ${BED} --resume ${WORK}/lost ${OUTS})
if(NOT output MATCHES "fields.vti averages from t = 0.05[0-9]* s only")
  message(FATAL_ERROR "a resume without the sums did not say so:\n${output}")
endif()
file(READ ${WORK}/lost/run.log log)
if(NOT log MATCHES "fields.vti: 3 samples from t = 0.06")
  message(FATAL_ERROR "a resume without the sums did not start again:\n${log}")
endif()
message("the run's fields.vti is analyze fields' for spheres, rods and parcels, and survives --resume")
