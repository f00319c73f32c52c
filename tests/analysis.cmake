# Analyses of runs (spectra, U_mf from sweeps, time windows, block means, phase folding) on
# constructed inputs with known answers.
bdl_add_test(test_analysis SOURCES test_analysis.c LABELS analysis)
bdl_add_test(test_series SOURCES test_series.c LABELS analysis)
bdl_add_test(test_rod_angles SOURCES test_rod_angles.c LABELS analysis)
bdl_add_test(test_fields SOURCES test_fields.c LABELS analysis)
bdl_add_test(test_rheology SOURCES test_rheology.c LABELS analysis)
add_test(NAME cli_sweep COMMAND ${CMAKE_COMMAND} -DBEDLAM=$<TARGET_FILE:bedlam>
  -DSCENE=${CMAKE_CURRENT_SOURCE_DIR}/scenes/sweep.ini -DWORK=${CMAKE_CURRENT_BINARY_DIR}/sweep_cli
  -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/sweep_cli.cmake)
set_tests_properties(cli_sweep PROPERTIES LABELS "analysis;cli" TIMEOUT 600)
bdl_add_test(test_granular SOURCES test_granular.c LABELS analysis)
# Bubbles in a voidage field: discs and balls found with their sizes, the freeboard left out.
bdl_add_test(test_bubbles SOURCES test_bubbles.c LABELS analysis)
add_test(NAME cli_granular COMMAND ${CMAKE_COMMAND} -DBEDLAM=$<TARGET_FILE:bedlam>
  -DSCENE=${CMAKE_CURRENT_SOURCE_DIR}/scenes/vibrated_pair.ini
  -DWORK=${CMAKE_CURRENT_BINARY_DIR}/granular_cli
  -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/granular_cli.cmake)
set_tests_properties(cli_granular PROPERTIES LABELS "analysis;cli" TIMEOUT 600)
add_test(NAME cli_orientation COMMAND ${CMAKE_COMMAND} -DBEDLAM=$<TARGET_FILE:bedlam>
  -DSCENE=${CMAKE_CURRENT_SOURCE_DIR}/scenes/rod_sweep.ini
  -DWORK=${CMAKE_CURRENT_BINARY_DIR}/orientation_cli
  -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/orientation_cli.cmake)
set_tests_properties(cli_orientation PROPERTIES LABELS "analysis;cli" TIMEOUT 600)
add_test(NAME cli_orientation_hand COMMAND ${CMAKE_COMMAND} -DBEDLAM=$<TARGET_FILE:bedlam>
  -DRUN=${CMAKE_CURRENT_SOURCE_DIR}/scenes/orientation/hand
  -DWORK=${CMAKE_CURRENT_BINARY_DIR}/orientation_hand
  -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/orientation_hand.cmake)
set_tests_properties(cli_orientation_hand PROPERTIES LABELS "analysis;cli" TIMEOUT 60)
add_test(NAME cli_fields COMMAND ${CMAKE_COMMAND} -DBEDLAM=$<TARGET_FILE:bedlam>
  -DSCENE=${CMAKE_SOURCE_DIR}/scenes/fluidized_bed.ini -DWORK=${CMAKE_CURRENT_BINARY_DIR}/fields_cli
  -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/fields_cli.cmake)
set_tests_properties(cli_fields PROPERTIES LABELS "analysis;cli" TIMEOUT 300)
add_test(NAME cli_fields_run COMMAND ${CMAKE_COMMAND} -DBEDLAM=$<TARGET_FILE:bedlam>
  -DSOURCE=${CMAKE_SOURCE_DIR} -DWORK=${CMAKE_CURRENT_BINARY_DIR}/fields_run_cli
  -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/fields_run_cli.cmake)
set_tests_properties(cli_fields_run PROPERTIES LABELS "analysis;cli" TIMEOUT 300)
add_test(NAME cli_rheology COMMAND ${CMAKE_COMMAND} -DBEDLAM=$<TARGET_FILE:bedlam>
  -DSCENE=${CMAKE_SOURCE_DIR}/scenes/shear_cell.ini -DWORK=${CMAKE_CURRENT_BINARY_DIR}/rheology_cli
  -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/rheology_cli.cmake)
set_tests_properties(cli_rheology PROPERTIES LABELS "analysis;cli" TIMEOUT 300)
# Sun's segregation percentage in diagnostics.csv: layered, interleaved and upside-down beds.
bdl_add_test(test_segregation SOURCES test_segregation.c LABELS analysis)
