# The build refuses an upward include: a file that includes render/renderer.h does not compile
# with the solver layer's include path, while the control file (solver headers only) does.
#   cmake -DCC=compiler -DINCLUDE=build/layers/solver -DDIR=tests/layers -P check_build.cmake
foreach(case downward upward)
  execute_process(COMMAND ${CC} -std=c11 -fsyntax-only -I${INCLUDE} ${DIR}/${case}.c
                  RESULT_VARIABLE rc_${case} OUTPUT_VARIABLE out ERROR_VARIABLE out)
  message("${case}.c: exit ${rc_${case}}")
  if(out)
    message("${out}")
  endif()
endforeach()
if(NOT rc_downward EQUAL 0)
  message(FATAL_ERROR "the control file does not compile with the solver layer's include path")
endif()
if(rc_upward EQUAL 0)
  message(FATAL_ERROR "an include of a higher layer compiled in the solver layer")
endif()
