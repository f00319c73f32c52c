# bedlam run of the Lees-Edwards shear cell (a short one), then bedlam analyze rheology on it: the
# row per run beside Lun et al., the jamming fit refused with one run but a run's own nu_cr given
# with the amplitude held, Grad's limit with a drag, and bad options refused with exit 2.
# -DBEDLAM -DSCENE -DWORK
file(REMOVE_RECURSE ${WORK})
execute_process(COMMAND ${BEDLAM} run ${SCENE} --quiet --out ${WORK} --set run.end_time=0.15
  --set create.bed.count=213 --set output.checkpoint_interval=0
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT EXISTS ${WORK}/rheology.csv)
  message(FATAL_ERROR "run failed (${rc}):\n${out}\n${err}")
endif()
execute_process(COMMAND ${BEDLAM} analyze rheology ${WORK} --restitution 0.7 --jamming 4 --no-plots
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0 OR NOT EXISTS ${WORK}/analysis/rheology.csv)
  message(FATAL_ERROR "analyze rheology failed (${rc})")
endif()
# 213 spheres in the 72 x 48 x 48 mm box: solids fraction 0.100; the shear rate the imposed
# 100/s of the Lees-Edwards images; Lun et al. beside it.
if(NOT out MATCHES "nu 0\\.100[0-9]  rate 100/s" OR NOT out MATCHES "Lun et al\\. \\(e = 0\\.7\\)")
  message(FATAL_ERROR "unexpected summary")
endif()
# The run's reduced viscosity and shear rate beside Lun et al.'s and Grad's dilute limit at 0.7.
if(NOT out MATCHES "reduced \\(eta0, nu0 at T\\): eta/eta0 0\\.[0-9]+  rate/nu0 0\\.[0-9]+"
   OR NOT out MATCHES "Grad's method\\) 0\\.8006  0\\.6310  0\\.652")
  message(FATAL_ERROR "no reduced viscosity and shear rate beside Grad's limit")
endif()
if(NOT out MATCHES "jamming fit: needs three runs or more")
  message(FATAL_ERROR "the jamming fit did not say it needs three runs")
endif()
# With A held the one run gives nu_cr = nu + (A / y)^(1/4) > nu.
execute_process(COMMAND ${BEDLAM} analyze rheology ${WORK} --jamming 4 --amplitude 1e-4 --no-plots
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "A = 0\\.0001 held: [^\n]* \\(nu 0\\.100[0-9]\\) gives nu_cr 0\\.[1-9]"
   OR out MATCHES "needs three runs")
  message(FATAL_ERROR "no nu_cr with the amplitude held (${rc}):\n${out}${err}")
endif()
# On the soft branch too (the dilute run lies on its inertial side), and --stiffness alone refused.
execute_process(COMMAND ${BEDLAM} analyze rheology ${WORK} --jamming 4 --amplitude 1e-4
  --stiffness 6e5 --a2 39.56 --no-plots RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "held on the soft branch: [^\n]* gives nu_cr 0\\.[1-9]")
  message(FATAL_ERROR "no nu_cr on the soft branch (${rc}):\n${out}${err}")
endif()
execute_process(COMMAND ${BEDLAM} analyze rheology ${WORK} --jamming 4 --amplitude 1e-4
  --stiffness 6e5 --no-plots RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "both positive")
  message(FATAL_ERROR "--stiffness without --a2 was not refused (${rc}): ${err}")
endif()
execute_process(COMMAND ${BEDLAM} analyze rheology ${WORK} --amplitude 1e-4 --no-plots
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "comes with --jamming")
  message(FATAL_ERROR "--amplitude without --jamming was not refused (${rc}): ${err}")
endif()
execute_process(COMMAND ${BEDLAM} analyze rheology ${WORK} --restitution 1 --no-plots
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 2 OR NOT err MATCHES "--restitution 1: must lie in \\(0, 1\\) \\(an elastic gas")
  message(FATAL_ERROR "a restitution of 1 was not refused (${rc}): ${err}")
endif()
# With --damping, Grad's limit with that drag at the run's own reduced drag; without
# --restitution, or negative, refused.
execute_process(COMMAND ${BEDLAM} analyze rheology ${WORK} --restitution 0.7 --damping 3 --no-plots
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "Grad's method, drag 3/s: b/nu0 0\\.[0-9]+\\) 0\\.[0-7]")
  message(FATAL_ERROR "no Grad's limit with the drag (${rc}):\n${out}${err}")
endif()
foreach(bad "--damping;3" "--restitution;0.7;--damping;-1")
  execute_process(COMMAND ${BEDLAM} analyze rheology ${WORK} ${bad} --no-plots
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 2 OR NOT err MATCHES "--damping")
    message(FATAL_ERROR "${bad} was not refused (${rc}): ${err}")
  endif()
endforeach()
execute_process(COMMAND ${BEDLAM} analyze rheology ${WORK}/missing --no-plots
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 2)
  message(FATAL_ERROR "a run folder without rheology.csv was not refused (${rc}): ${err}")
endif()
