# bedlam run --resume reads a checkpoint as untrusted input: a truncated one, one with a changed
# byte and a file that is no checkpoint are refused with exit code 2 and the reason; a scene whose
# contacts are 100 times stiffer resumes with its own time step and says why (the checkpoint's
# would be 2.5 times the stable limit). -DBEDLAM -DSCENE -DWORK
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${BEDLAM} run ${SCENE} --steps 100 --quiet --out ${WORK}/base RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the first run failed: ${rc}")
endif()
set(state ${WORK}/base/checkpoint/state.bdlckpt)
execute_process(COMMAND head -c 1000 ${state} OUTPUT_FILE ${WORK}/cut.bdlckpt)
file(COPY ${state} DESTINATION ${WORK}/flipped)
execute_process(COMMAND sh -c "printf 'Z' | dd of=${WORK}/flipped/state.bdlckpt bs=1 seek=5000 conv=notrunc 2>/dev/null")

# Runs bedlam resuming from `from` and checks the exit code and that the output matches `pattern`.
function(expect code pattern from)
  execute_process(COMMAND ${BEDLAM} run ${SCENE} --steps 20 --out ${WORK}/resumed --resume ${from} ${ARGN}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${out}${err}")
  if(NOT rc EQUAL ${code})
    message(FATAL_ERROR "resume from ${from}: exit code ${rc}, expected ${code}")
  endif()
  if(NOT "${out}${err}" MATCHES "${pattern}")
    message(FATAL_ERROR "resume from ${from}: the output does not match '${pattern}'")
  endif()
endfunction()

expect(2 "cut.bdlckpt': is truncated: its header announces [0-9]+ bytes of state, the file holds 968"
  ${WORK}/cut.bdlckpt)
expect(2 "is damaged: the checksum of its [0-9]+ bytes of state does not match" ${WORK}/flipped/state.bdlckpt)
expect(2 "is not a bedlam checkpoint" ${SCENE})
expect(0 "species 'small': stiffness 2000 N/m in the checkpoint, 200000 N/m in the scene.*the checkpoint's would be 2.5 times the scene's stable limit"
  ${state} --set species.small.stiffness=200000 --set species.large.stiffness=200000)
