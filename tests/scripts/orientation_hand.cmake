# bedlam analyze orientation on a hand-written orientation.csv of 4 bins (45° wide) and 6 rows,
# with the PDFs worked out by hand. -DBEDLAM -DRUN -DWORK
#   --from 1 --to 2: rows t = 1, 2. Near the walls counts (1 1 1 1) + (0 0 1 1) = (1 1 2 2) of 6
#   rods: PDF (1 1 2 2) / (6 45°) = 1/270, 1/270, 2/270, 2/270; mean |cos| (4 0.5 + 2 0.3) / 6.
#   Bulk (1 0 0 1) of 2 rods: 1/90, 0, 0, 1/90.
#   --by-velocity: the 0.5 m/s stage (t = 0..2) over t >= 1, as above; the 1 m/s stage (t = 3..5)
#   over t >= 4: near the walls (3 0 0 5) / (8 45°), mean |cos| (4 0.1 + 4 0.2) / 8 = 0.15; bulk
#   (0 3 5 0) / (8 45°).
file(REMOVE_RECURSE ${WORK})
function(expect_lines file)
  file(STRINGS ${file} lines)
  if(NOT "${lines}" STREQUAL "${ARGN}")
    message(FATAL_ERROR "${file}:\n${lines}\nexpected\n${ARGN}")
  endif()
endfunction()
execute_process(COMMAND ${BEDLAM} analyze orientation ${RUN} --from 1 --to 2 --no-plots
  --out ${WORK}/window RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "analyze orientation --from 1 --to 2: exit ${rc}")
endif()
set(stage0 "0,0.5,-67.5,0.0037037,0.0111111" "0,0.5,-22.5,0.0037037,0"
  "0,0.5,22.5,0.00740741,0" "0,0.5,67.5,0.00740741,0.0111111")
expect_lines(${WORK}/window/orientation.csv "stage,inlet_velocity,angle,wall_pdf,bulk_pdf" ${stage0})
set(summary "stage,inlet_velocity,from,to,rows,wall_rods,wall_abs_cos,bulk_rods,bulk_abs_cos")
expect_lines(${WORK}/window/orientation_summary.csv ${summary} "0,0.5,1,2,2,3,0.433333,1,0.2")
execute_process(COMMAND ${BEDLAM} analyze orientation ${RUN} --by-velocity --no-plots
  --out ${WORK}/stages RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "analyze orientation --by-velocity: exit ${rc}")
endif()
expect_lines(${WORK}/stages/orientation.csv "stage,inlet_velocity,angle,wall_pdf,bulk_pdf" ${stage0}
  "1,1,-67.5,0.00833333,0" "1,1,-22.5,0,0.00833333" "1,1,22.5,0,0.0138889"
  "1,1,67.5,0.0138889,0")
expect_lines(${WORK}/stages/orientation_summary.csv ${summary} "0,0.5,1,2,2,3,0.433333,1,0.2"
  "1,1,4,5,2,4,0.15,4,0.85")
