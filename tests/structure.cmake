# The structure of src/: the layers (cmake/layers.cmake) — every include between folders points
# the allowed way, and both the check and the build refuse an upward one — and functions that
# fit on a screen (tools/function_sizes.py).
add_test(NAME layers COMMAND ${CMAKE_COMMAND} -DSRC=${CMAKE_SOURCE_DIR}/src
  -P ${CMAKE_SOURCE_DIR}/cmake/check_layers.cmake)
add_test(NAME layers_check_catches_upward COMMAND ${CMAKE_COMMAND} -DSRC=${CMAKE_SOURCE_DIR}/src
  -DWORK=${CMAKE_CURRENT_BINARY_DIR}/layers_upward
  -DCHECK=${CMAKE_SOURCE_DIR}/cmake/check_layers.cmake
  -P ${CMAKE_CURRENT_SOURCE_DIR}/layers/check_catches.cmake)
add_test(NAME layers_build_refuses_upward COMMAND ${CMAKE_COMMAND} -DCC=${CMAKE_C_COMPILER}
  -DINCLUDE=${CMAKE_BINARY_DIR}/layers/solver -DDIR=${CMAKE_CURRENT_SOURCE_DIR}/layers
  -P ${CMAKE_CURRENT_SOURCE_DIR}/layers/check_build.cmake)
find_package(Python3 REQUIRED COMPONENTS Interpreter)
add_test(NAME function_sizes COMMAND ${Python3_EXECUTABLE}
  ${CMAKE_SOURCE_DIR}/tools/function_sizes.py ${CMAKE_SOURCE_DIR}/src --limit 80)
set_tests_properties(layers layers_check_catches_upward layers_build_refuses_upward function_sizes
  PROPERTIES LABELS "structure")
