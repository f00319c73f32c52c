# bedlam run of a small vibrated two-species bed, then its species.csv, its contact files and
# bedlam analyze phase and networks on them. -DBEDLAM -DSCENE -DWORK
include(${CMAKE_CURRENT_LIST_DIR}/run_util.cmake)
bdl_fresh_run()
file(STRINGS ${WORK}/species.csv rows LIMIT_COUNT 1)
if(NOT rows STREQUAL "time,count_small,mean_height_small,top_height_small,coordination_small,count_large,mean_height_large,top_height_large,coordination_large,lacey,lacey_horizontal,lacey_vertical")
  message(FATAL_ERROR "species.csv header: ${rows}")
endif()
file(GLOB contacts ${WORK}/contacts/contacts_*.csv)
list(LENGTH contacts n)
if(NOT n EQUAL 10) # t = 0, 0.05, ..., 0.45
  message(FATAL_ERROR "${n} contact files, expected 10")
endif()
# Gamma = 3: the bed flies for part of every cycle; then the walls (side walls grazed) carry
# less than a tenth of its weight (0.036 N), against six times it at the landing.
execute_process(COMMAND ${BEDLAM} analyze phase ${WORK} --column wall_force --period 0.05
  --start 0.15 --from-cycle 2 --bins 25 --below 0.0036 --no-plots
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0 OR NOT out MATCHES "wall_force below 0.0036 from phase 0\\.[0-9]+ to 0\\.[0-9]+")
  message(FATAL_ERROR "analyze phase failed (${rc}) or found no flight")
endif()
execute_process(COMMAND ${BEDLAM} analyze phase ${WORK} --file species.csv
  --column mean_height_large --period 0.05 --start 0.15 --no-plots
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0 OR NOT EXISTS ${WORK}/analysis/phase_mean_height_large.csv)
  message(FATAL_ERROR "analyze phase on species.csv failed (${rc})")
endif()
# Nearly settled, just before the shaking: one network holds at least 250 of the 301 particles
# (a few still bounce, rattlers sit in cages).
execute_process(COMMAND ${BEDLAM} analyze networks ${WORK}/contacts/contacts_000003.csv --no-plots
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0 OR NOT out MATCHES "force networks: [1-5]; the largest has (2[5-9][0-9]|30[01]) particles"
   OR NOT EXISTS ${WORK}/contacts/force_pdf.csv)
  message(FATAL_ERROR "analyze networks failed (${rc})")
endif()
# With the particle file of the same moment: Sun's spanning trees of all the centres, kept where
# the particles touch, against the force networks (table 6.2): the first pass is a tree (its
# edges one fewer than its particles), and the union of five passes holds the largest network's
# particles; the force correlation is written.
execute_process(COMMAND ${BEDLAM} analyze networks ${WORK}/contacts/contacts_000003.csv
  --file ${WORK}/vtk/particles_000003.vtp --no-plots
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
string(REGEX MATCH "\\| 1 \\| ([0-9]+) \\| ([0-9]+) \\|" first "${out}")
set(np ${CMAKE_MATCH_1})
set(ne ${CMAKE_MATCH_2})
string(REGEX MATCH "\\| 5 \\| ([0-9]+) \\|" fifth "${out}")
set(np5 ${CMAKE_MATCH_1})
string(REGEX MATCH "\\| force networks \\| ([0-9]+) \\|" net "${out}")
set(nf ${CMAKE_MATCH_1})
if(NOT rc EQUAL 0 OR NOT first OR NOT np5 OR NOT nf OR NOT EXISTS ${WORK}/contacts/force_correlation.csv)
  message(FATAL_ERROR "analyze networks --file failed (${rc})")
endif()
math(EXPR tree "${np} - 1")
if(NOT ne EQUAL tree OR NOT np5 EQUAL nf)
  message(FATAL_ERROR "spanning trees: first pass ${np} particles, ${ne} edges; five passes ${np5} particles, networks ${nf}")
endif()
execute_process(COMMAND ${BEDLAM} analyze networks ${WORK}/species.csv --no-plots
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "analyze networks of a non-contacts file: exit ${rc}, expected 2")
endif()
