# The include check fails on an upward include: a copy of src/ with one added line
# (dem/particles.h includes render/renderer.h) must be refused, and the unchanged copy accepted.
#   cmake -DSRC=src -DWORK=scratch-folder -DCHECK=cmake/check_layers.cmake -P check_catches.cmake
file(REMOVE_RECURSE ${WORK})
file(COPY ${SRC}/ DESTINATION ${WORK}/src)
execute_process(COMMAND ${CMAKE_COMMAND} -DSRC=${WORK}/src -P ${CHECK} RESULT_VARIABLE rc_clean
                OUTPUT_QUIET ERROR_QUIET)
file(APPEND ${WORK}/src/dem/particles.h "#include \"render/renderer.h\"\n")
execute_process(COMMAND ${CMAKE_COMMAND} -DSRC=${WORK}/src -P ${CHECK} RESULT_VARIABLE rc_upward
                OUTPUT_VARIABLE out ERROR_VARIABLE out)
file(REMOVE_RECURSE ${WORK})
message("${out}")
if(NOT rc_clean EQUAL 0)
  message(FATAL_ERROR "the check refuses the unchanged sources")
endif()
if(rc_upward EQUAL 0 OR NOT out MATCHES "src/dem/particles.h: #include \"render/renderer.h\": dem may not include render")
  message(FATAL_ERROR "the check did not catch dem/particles.h including render/renderer.h")
endif()
message("the upward include was caught")
