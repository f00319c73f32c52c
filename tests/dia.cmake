# Synthetic camera (DIA) images, their ground truth and the calibration.
bdl_add_test(test_dia SOURCES test_dia.c LABELS dia)
add_test(NAME dia_cli COMMAND ${CMAKE_COMMAND} -DBEDLAM=$<TARGET_FILE:bedlam>
  -DSCENE=${CMAKE_CURRENT_SOURCE_DIR}/scenes/dia.ini -DWORK=${CMAKE_CURRENT_BINARY_DIR}/dia_cli
  -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/dia_cli.cmake)
set_tests_properties(dia_cli PROPERTIES LABELS "dia;cli" TIMEOUT 300)
bdl_cli_expect(cli_calibrate_help 0 "usage: bedlam calibrate" calibrate --help)
bdl_cli_expect(cli_calibrate_missing 2 "camera.json cannot be read" calibrate ${CMAKE_CURRENT_SOURCE_DIR}/scenes)
# The thesis's image-analysis chain on synthetic images with known answers.
bdl_add_test(test_bed_height SOURCES test_bed_height.c LABELS dia)
bdl_add_test(test_orient SOURCES test_orient.c LABELS dia)
bdl_add_test(test_piv SOURCES test_piv.c LABELS dia)
bdl_add_test(test_ptv SOURCES test_ptv.c LABELS dia)
# analyze dia's coalignment by wall zone and mass flux: app code, built into the test with it.
bdl_add_test(test_dia_flux SOURCES test_dia_flux.c ${PROJECT_SOURCE_DIR}/src/app/analyze_dia_flux.c
  ${PROJECT_SOURCE_DIR}/src/app/analyze_files.c
  LABELS dia)
target_include_directories(test_dia_flux PRIVATE ${PROJECT_BINARY_DIR}/layers/app)
# The camera filming a solids phase on the grid (the two-fluid model): spheres sampled from the
# field, their truth at the field's fraction.
find_package(Python3 REQUIRED COMPONENTS Interpreter)
add_test(NAME dia_tfm_cli COMMAND ${CMAKE_COMMAND} -DBEDLAM=$<TARGET_FILE:bedlam>
  -DSCENE=${CMAKE_CURRENT_SOURCE_DIR}/scenes/tfm_camera.ini
  -DWORK=${CMAKE_CURRENT_BINARY_DIR}/dia_tfm_cli -DPYTHON=${Python3_EXECUTABLE}
  -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/dia_tfm_cli.cmake)
set_tests_properties(dia_tfm_cli PROPERTIES LABELS "dia;cli;solids" TIMEOUT 300)
