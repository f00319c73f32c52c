# The command line: every scene passes `check` and runs a few hundred steps; bad input exits 2.
set(BDL_EXPECT ${CMAKE_CURRENT_SOURCE_DIR}/scripts/expect_exit.cmake)
file(GLOB BDL_SCENES ${PROJECT_SOURCE_DIR}/scenes/*.ini)
foreach(scene ${BDL_SCENES})
  get_filename_component(stem ${scene} NAME_WE)
  add_test(NAME scene_check_${stem} COMMAND ${CMAKE_COMMAND} -DEXPECT=0 -DCONTAINS=valid
    "-DCMD=$<TARGET_FILE:bedlam>;check;${scene}" -P ${BDL_EXPECT})
  add_test(NAME scene_run_${stem} COMMAND ${CMAKE_COMMAND} -DEXPECT=0
    "-DCMD=$<TARGET_FILE:bedlam>;run;${scene};--steps;300;--quiet;--out;${CMAKE_CURRENT_BINARY_DIR}/runs/${stem}"
    -P ${BDL_EXPECT})
  set_tests_properties(scene_check_${stem} scene_run_${stem} PROPERTIES LABELS scenes TIMEOUT 600)
endforeach()

function(bdl_cli_expect name code text)
  add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} -DEXPECT=${code} -DCONTAINS=${text}
    "-DCMD=$<TARGET_FILE:bedlam>;${ARGN}" -P ${BDL_EXPECT})
  set_tests_properties(${name} PROPERTIES LABELS cli TIMEOUT 300)
endfunction()

set(S ${CMAKE_CURRENT_SOURCE_DIR}/scenes)
bdl_cli_expect(cli_help 0 "usage: bedlam" --help)
bdl_cli_expect(cli_run_help 0 "--resume" run --help)
bdl_cli_expect(cli_check_help 0 "usage: bedlam check" check --help)
bdl_cli_expect(cli_bench_help 0 "particle-steps" bench --help)
bdl_cli_expect(cli_unknown_command 2 "unknown command" frobnicate)
bdl_cli_expect(cli_missing_scene 2 "cannot|No such|not found|open" check ${S}/does_not_exist.ini)
bdl_cli_expect(cli_bad_set 2 "densty" check ${PROJECT_SOURCE_DIR}/scenes/bouncing_ball.ini --set species.steel.densty=3)
bdl_cli_expect(cli_negative_diameter 2 "diameter" check ${PROJECT_SOURCE_DIR}/scenes/bouncing_ball.ini --set species.steel.diameter=-0.01)
bdl_cli_expect(cli_overlap 2 "overlap" check ${S}/overlap.ini)
bdl_cli_expect(cli_outside 2 "outside the domain" check ${S}/outside.ini)
bdl_cli_expect(cli_dt_too_big 2 "contact time" check ${S}/dt_too_big.ini)
bdl_cli_expect(cli_dt_too_big_run 2 "contact time" run ${S}/dt_too_big.ini --quiet --out ${CMAKE_CURRENT_BINARY_DIR}/runs/dt)
bdl_cli_expect(cli_unwritable_out 2 "not writable" run ${PROJECT_SOURCE_DIR}/scenes/bouncing_ball.ini --quiet --out /proc/bedlam-cannot-write-here)
bdl_cli_expect(cli_bad_threads 2 "threads" run ${PROJECT_SOURCE_DIR}/scenes/bouncing_ball.ini --threads zero)
# [output] fields_*: bad values refused with the key (exit 2), the default cell too when it makes
# too many cells over the domain (the run refuses it before it starts; the memory limit raised so
# that the estimate does not refuse it first), and the estimate of a grid too large for memory.
set(BALL ${PROJECT_SOURCE_DIR}/scenes/bouncing_ball.ini)
bdl_cli_expect(cli_fields_negative 2 "fields_interval = -1: out of range; allowed: >= 0 .s." check ${BALL} --set output.fields_interval=-1)
bdl_cli_expect(cli_fields_nan 2 "fields_start = nan: not a finite number" check ${BALL} --set output.fields_start=nan)
bdl_cli_expect(cli_fields_cell_large 2 "fields_cell = 0.5: larger than the domain" check ${BALL} --set output.fields_cell=0.5)
bdl_cli_expect(cli_fields_cell_small 2 "fields_cell = 1e-05: makes about 2e.12 cells over the domain, more than 5e.07" run ${BALL} --set output.fields_cell=1e-5 --quiet --out ${CMAKE_CURRENT_BINARY_DIR}/runs/fields_small)
bdl_cli_expect(cli_fields_default_cell 2 "fields_cell is not given, and its default, three mean diameters of the particles .0.03 m., makes 1.18e.09 cells" run ${BALL} --set output.fields_interval=0.01 "--set;domain.min=-20 -20 0;--set;domain.max=20 20 20" --set guards.max_memory=1e12 --quiet --out ${CMAKE_CURRENT_BINARY_DIR}/runs/fields_default)
bdl_cli_expect(cli_fields_memory 2 "fields_cell = 0.001 m: about 1.3e.08 bytes for a fields grid of 2e.06 cells, above .guards. max_memory = 1e.08" check ${BALL} --set output.fields_interval=0.01 --set output.fields_cell=0.001 --set guards.max_memory=1e8)
bdl_cli_expect(cli_unstable 1 "overlap" run ${S}/explode.ini --quiet --out ${CMAKE_CURRENT_BINARY_DIR}/runs/explode)
# An elastic sticking Hertz-Mindlin impact runs through the default guards (checked every step).
bdl_cli_expect(cli_oblique_stick 0 "done: t = 0.0009" run ${S}/oblique_stick.ini --out ${CMAKE_CURRENT_BINARY_DIR}/runs/oblique_stick)

add_test(NAME cli_resume COMMAND ${CMAKE_COMMAND} -DBEDLAM=$<TARGET_FILE:bedlam>
  -DSCENE=${PROJECT_SOURCE_DIR}/scenes/vibrated_bed.ini -DWORK=${CMAKE_CURRENT_BINARY_DIR}/runs/resume
  -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/resume_cli.cmake)
set_tests_properties(cli_resume PROPERTIES LABELS cli TIMEOUT 600)
# The same for a solids phase on the gas grid (its fractions, velocities and fluxes).
add_test(NAME cli_resume_tfm COMMAND ${CMAKE_COMMAND} -DBEDLAM=$<TARGET_FILE:bedlam>
  -DSCENE=${PROJECT_SOURCE_DIR}/scenes/tfm_goldschmidt_bed.ini -DWORK=${CMAKE_CURRENT_BINARY_DIR}/runs/resume_tfm
  -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/resume_cli.cmake)
set_tests_properties(cli_resume_tfm PROPERTIES LABELS cli TIMEOUT 600)
add_test(NAME cli_resume_tfm_binary COMMAND ${CMAKE_COMMAND} -DBEDLAM=$<TARGET_FILE:bedlam>
  -DSCENE=${PROJECT_SOURCE_DIR}/scenes/tfm_goldschmidt_binary.ini
  -DWORK=${CMAKE_CURRENT_BINARY_DIR}/runs/resume_tfm_binary
  -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/resume_cli.cmake)
set_tests_properties(cli_resume_tfm_binary PROPERTIES LABELS cli TIMEOUT 600
  FIXTURES_SETUP tfm_binary_checkpoint)
# The mixture's checkpoint refused with a phase's diameter changed.
bdl_cli_expect(cli_resume_tfm_phase_changed 2
  "does not match the scene: \\[phase small\\]: diameter 0.00152 m in the checkpoint, 0.002 m in the scene"
  run ${PROJECT_SOURCE_DIR}/scenes/tfm_goldschmidt_binary.ini --steps 10 --quiet
  --out ${CMAKE_CURRENT_BINARY_DIR}/runs/resume_tfm_binary/changed
  --resume ${CMAKE_CURRENT_BINARY_DIR}/runs/resume_tfm_binary/split --set phase.small.diameter=0.002)
set_tests_properties(cli_resume_tfm_phase_changed PROPERTIES FIXTURES_REQUIRED tfm_binary_checkpoint)
# Each phase's layer fractions in profile.csv, averaged by analyze profile.
bdl_cli_expect(cli_profile_phases 0
  "solids fraction against height \\(and each phase's: small, large\\), averaged over 2 rows"
  analyze profile ${CMAKE_CURRENT_BINARY_DIR}/runs/resume_tfm_binary/straight
  --out ${CMAKE_CURRENT_BINARY_DIR}/runs/resume_tfm_binary/profile --no-plots)
set_tests_properties(cli_profile_phases PROPERTIES FIXTURES_REQUIRED tfm_binary_checkpoint)

add_test(NAME cli_sigint COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/scripts/sigint.sh $<TARGET_FILE:bedlam>
  ${PROJECT_SOURCE_DIR}/scenes/settling_box.ini ${CMAKE_CURRENT_BINARY_DIR}/runs/sigint)
set_tests_properties(cli_sigint PROPERTIES LABELS cli TIMEOUT 120)

# Nothing lost to kill -9: 20 kills at fixed steps, each resumed, end with the files of a run
# never interrupted (the final checkpoint and every output, byte for byte).
add_test(NAME cli_kill COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/scripts/kill_cli.sh
  $<TARGET_FILE:bedlam> ${S}/kill.ini ${CMAKE_CURRENT_BINARY_DIR}/runs/kill 20)
set_tests_properties(cli_kill PROPERTIES LABELS cli TIMEOUT 300)

# Failures: a blow-up and a gas stop keep the last good checkpoint and write no non-finite
# number; checkpoints that cannot be written and a full disk exit with the path.
find_package(Python3 REQUIRED COMPONENTS Interpreter)
add_test(NAME cli_failure COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/scripts/failure_cli.sh
  $<TARGET_FILE:bedlam> ${CMAKE_CURRENT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}/runs/failure)
set_tests_properties(cli_failure PROPERTIES LABELS cli TIMEOUT 300
  ENVIRONMENT PYTHON=${Python3_EXECUTABLE})

add_test(NAME cli_threads COMMAND ${CMAKE_COMMAND} -DBEDLAM=$<TARGET_FILE:bedlam>
  -DSCENE=${PROJECT_SOURCE_DIR}/scenes/settling_box.ini -DWORK=${CMAKE_CURRENT_BINARY_DIR}/runs/threads
  -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/threads_cli.cmake)
set_tests_properties(cli_threads PROPERTIES LABELS cli TIMEOUT 600)
bdl_cli_expect(cli_bench_coupled 0 "per gas step: gas" bench coupled ${PROJECT_SOURCE_DIR}/scenes/fluidized_bed.ini --warmup 0.01 --time 0.01 --repeat 2)
bdl_cli_expect(cli_bench_coupled_no_gas 2 "no .gas. section" bench coupled ${PROJECT_SOURCE_DIR}/scenes/bouncing_ball.ini --time 0.01)
# Every run reports its own errors beside its speed (off a terminal, every 10 progress intervals).
bdl_cli_expect(cli_progress_errors 0 "energy balance .* dp/weight [0-9.]+  gas volume" run ${PROJECT_SOURCE_DIR}/scenes/fluidized_bed.ini --until 0.4 --set output.progress_interval=0.02 --set output.frame_interval=0 --out ${CMAKE_CURRENT_BINARY_DIR}/runs/progress_errors)

# bedlam verify: options, bad input, one case end to end (CSV, README), and the --quick set
# (label verify: run by the README's test command, left out of the sanitizer build, where the
# same measurements run as the verification tests).
bdl_cli_expect(cli_verify_help 0 "usage: bedlam verify" verify --help)
bdl_cli_expect(cli_verify_unknown 2 "unknown case 'nosuchcase'" verify nosuchcase)
bdl_cli_expect(cli_verify_unwritable 2 "--out" verify poiseuille --out ${PROJECT_SOURCE_DIR}/README.md/x)
bdl_cli_expect(cli_verify_one 0 "1 case, 0 failed" verify poiseuille --quick --no-plots
  --out ${CMAKE_CURRENT_BINARY_DIR}/verify-one)
# Drawn again from that run's CSV (a fixture: cli_verify_one runs first); a folder without the
# case's CSV is refused.
bdl_cli_expect(cli_verify_from 0 "poiseuille .*3 runs read, pass.*1 case, 0 failed" verify
  poiseuille --from ${CMAKE_CURRENT_BINARY_DIR}/verify-one --no-plots
  --out ${CMAKE_CURRENT_BINARY_DIR}/verify-from)
set_tests_properties(cli_verify_one PROPERTIES FIXTURES_SETUP verify_one)
set_tests_properties(cli_verify_from PROPERTIES FIXTURES_REQUIRED verify_one)
# A series whose name holds a comma (the CSV does not quote it) is read back whole: the committed
# report's parcel_boycott, which fails (exit 1), with its three series.
bdl_cli_expect(cli_verify_from_comma 1 "parcel_boycott .*3 runs read, FAIL" verify parcel_boycott
  --from ${PROJECT_SOURCE_DIR}/docs/validation --no-plots
  --out ${CMAKE_CURRENT_BINARY_DIR}/verify-from-comma)
bdl_cli_expect(cli_verify_from_missing 2 "--from .*: no runs of poiseuille" verify poiseuille
  --from ${PROJECT_SOURCE_DIR}/docs --no-plots --out ${CMAKE_CURRENT_BINARY_DIR}/verify-from2)
add_test(NAME verify_quick COMMAND ${CMAKE_COMMAND} -DEXPECT=0 "-DCONTAINS= 0 failed"
  "-DCMD=$<TARGET_FILE:bedlam>;verify;--quick;--out;${CMAKE_CURRENT_BINARY_DIR}/validation-quick"
  -P ${BDL_EXPECT})
set_tests_properties(verify_quick PROPERTIES LABELS verify TIMEOUT 900)
bdl_cli_expect(cli_analyze_help 0 "usage: bedlam analyze" analyze --help)
bdl_cli_expect(cli_analyze_bad 2 "expected 'sweep RUN'" analyze nonsense somewhere)
# analyze orientation refuses what it cannot read (runs/ keeps --out out of the source tree).
set(O ${S}/orientation)
set(AO ${CMAKE_CURRENT_BINARY_DIR}/runs/orientation_errors)
bdl_cli_expect(cli_orientation_missing 2 "orientation.csv cannot be read: .*orientation_interval" analyze orientation ${O}/missing --out ${AO})
bdl_cli_expect(cli_orientation_no_rods 2 "no rods in 2 rows" analyze orientation ${O}/norods --out ${AO})
bdl_cli_expect(cli_orientation_bad_count 2 "orientation.csv:3: a bin count is not a whole number" analyze orientation ${O}/badcount --out ${AO})
bdl_cli_expect(cli_orientation_bad_number 2 "--from abc: not a number" analyze orientation ${O}/hand --from abc --out ${AO})
bdl_cli_expect(cli_orientation_bad_window 2 "--from must be below --to" analyze orientation ${O}/hand --from 3 --to 1 --out ${AO})
bdl_cli_expect(cli_orientation_empty_window 1 "no rows between 10 and inf" analyze orientation ${O}/hand --from 10 --no-plots --out ${AO})
bdl_cli_expect(cli_orientation_not_table 2 "not an orientation table" analyze orientation ${O}/notable --out ${AO})
bdl_cli_expect(cli_orientation_help 0 "orientation RUN .*--by-velocity" analyze --help)


add_test(NAME cli_bench_bed_dir COMMAND ${CMAKE_COMMAND} -DBEDLAM=$<TARGET_FILE:bedlam>
  -DWORK=${CMAKE_CURRENT_BINARY_DIR}/runs/bench_beds -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/bench_bed_cli.cmake)
set_tests_properties(cli_bench_bed_dir PROPERTIES LABELS cli TIMEOUT 300)

# The rod bed refuses the thesis's own step (5e-5 s is about the rods' shortest contact time).
bdl_cli_expect(cli_rods_thesis_dt 2 "of the contact time .* of species 'rod' with 'rod'" run
  ${PROJECT_SOURCE_DIR}/scenes/rod_bed_packed.ini --set run.dt=5e-5 --quiet --out ${CMAKE_CURRENT_BINARY_DIR}/runs/rods_dt)

# analyze dia: a small rod scene's synthetic camera images through the image-analysis chain.
add_test(NAME cli_dia_rods_run COMMAND ${CMAKE_COMMAND} -DEXPECT=0 -DCONTAINS=
  "-DCMD=$<TARGET_FILE:bedlam>;run;${S}/dia_rods.ini;--quiet;--out;${CMAKE_CURRENT_BINARY_DIR}/runs/dia_rods"
  -P ${BDL_EXPECT})
set_tests_properties(cli_dia_rods_run PROPERTIES LABELS cli FIXTURES_SETUP dia_rods)
bdl_cli_expect(cli_analyze_dia 0 "rods along the front wall: [0-9]+ in the truth.*PIV against"
  analyze dia ${CMAKE_CURRENT_BINARY_DIR}/runs/dia_rods/dia/front)
set_tests_properties(cli_analyze_dia PROPERTIES FIXTURES_REQUIRED dia_rods)
bdl_cli_expect(cli_analyze_dia_missing 2 "camera.json" analyze dia ${S}/no_such_camera)
# analyze ptv: the high-speed camera's frames tracked; falling rods a few pixels apart per frame
# are linked to themselves (at least 95 % of the links; a linking or matching error shows here).
bdl_cli_expect(cli_analyze_ptv 0 "links joining the same particle: (9[5-9]|100)[.][0-9]+ %.*coordination"
  analyze ptv ${CMAKE_CURRENT_BINARY_DIR}/runs/dia_rods/dia/ptv)
set_tests_properties(cli_analyze_ptv PROPERTIES FIXTURES_REQUIRED dia_rods)
bdl_cli_expect(cli_analyze_ptv_pairs 2 "double frames" analyze ptv
  ${CMAKE_CURRENT_BINARY_DIR}/runs/dia_rods/dia/front)
set_tests_properties(cli_analyze_ptv_pairs PROPERTIES FIXTURES_REQUIRED dia_rods)
# With a calibration fit of the same images: the solids mass flux and the coalignment by zone.
bdl_cli_expect(cli_dia_rods_calibrate 0 "rational" calibrate
  ${CMAKE_CURRENT_BINARY_DIR}/runs/dia_rods/dia/front --normalise --cap 0.49 --method adaptive
  --no-plots --out ${CMAKE_CURRENT_BINARY_DIR}/runs/dia_rods_fit)
set_tests_properties(cli_dia_rods_calibrate PROPERTIES FIXTURES_REQUIRED dia_rods
  FIXTURES_SETUP dia_rods_fit)
bdl_cli_expect(cli_analyze_dia_flux 0 "0-2 +L_p: detected.*upward solids mass flux.*correlation"
  analyze dia ${CMAKE_CURRENT_BINARY_DIR}/runs/dia_rods/dia/front --fit
  ${CMAKE_CURRENT_BINARY_DIR}/runs/dia_rods_fit/fit.json --density 1395 --height 0.02
  --out ${CMAKE_CURRENT_BINARY_DIR}/runs/dia_rods_flux)
set_tests_properties(cli_analyze_dia_flux PROPERTIES FIXTURES_REQUIRED "dia_rods;dia_rods_fit")
bdl_cli_expect(cli_analyze_dia_fit_density 2 "--fit needs --density" analyze dia
  ${S}/no_such_camera --fit ${S}/no_such_fit.json)

# --resume refuses damaged checkpoints (exit 2, the reason) and resumes stiffer contacts with the
# scene's time step (docs/checkpoints.md).
add_test(NAME cli_resume_hostile COMMAND ${CMAKE_COMMAND} -DBEDLAM=$<TARGET_FILE:bedlam>
  -DSCENE=${CMAKE_CURRENT_SOURCE_DIR}/scenes/vibrated_pair.ini -DWORK=${CMAKE_CURRENT_BINARY_DIR}/runs/resume_hostile
  -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/resume_hostile_cli.cmake)
set_tests_properties(cli_resume_hostile PROPERTIES LABELS cli TIMEOUT 300)

# Parcels: check prints what parcels have (and nothing of contacts); the viewer's colours exclude
# the coordination number; the bench times one thread count against another from the same state.
add_test(NAME cli_check_parcels COMMAND ${CMAKE_COMMAND} -DEXPECT=0
  "-DCONTAINS=parcels per filled cell: mean [0-9.]+, min [0-9]+, max [0-9]+.*stress at close packing.*of the parcels' stable step"
  "-DLACKS=contact time|t_c |dt_refuse"
  "-DCMD=$<TARGET_FILE:bedlam>;check;${PROJECT_SOURCE_DIR}/scenes/parcels_settling.ini" -P ${BDL_EXPECT})
set_tests_properties(cli_check_parcels PROPERTIES LABELS cli TIMEOUT 300)
bdl_cli_expect(cli_parcels_no_coordination 2 "parcels have no contacts" check ${PROJECT_SOURCE_DIR}/scenes/parcels_settling.ini --set camera.color=coordination)
bdl_cli_expect(cli_parcels_display 2 "display = point" check ${PROJECT_SOURCE_DIR}/scenes/parcels_settling.ini --set parcels.display=point)
bdl_cli_expect(cli_bench_parcels_help 0 "parcel updates per second" bench parcels --help)
bdl_cli_expect(cli_bench_parcels 0 "speed-up 2 vs 1 threads: [0-9.]+x; the state after the window is the same bit for bit" bench parcels ${PROJECT_SOURCE_DIR}/scenes/parcels_settling.ini --warmup 0.02 --time 0.02)
bdl_cli_expect(cli_bench_parcels_no_parcels 2 "has no parcels" bench parcels ${PROJECT_SOURCE_DIR}/scenes/bouncing_ball.ini --time 0.01)

# With no display `bedlam view` stops at once (exit 2) and says how to get frames headless,
# instead of running unseen on SDL's offscreen driver.
add_test(NAME cli_view_no_display COMMAND ${CMAKE_COMMAND} -DEXPECT=2
  "-DCONTAINS=no display: neither X11 \\(DISPLAY\\) nor Wayland"
  "-DCMD=${CMAKE_COMMAND};-E;env;--unset=DISPLAY;--unset=WAYLAND_DISPLAY;--unset=SDL_VIDEODRIVER;$<TARGET_FILE:bedlam>;view;${CMAKE_SOURCE_DIR}/scenes/bouncing_ball.ini"
  -P ${BDL_EXPECT})
set_tests_properties(cli_view_no_display PROPERTIES LABELS cli TIMEOUT 5)

# A solids phase on the grid: bad input is refused with exit 2 and a message naming the key.
set(TFM ${PROJECT_SOURCE_DIR}/scenes/tfm_goldschmidt_bed.ini)
bdl_cli_expect(cli_tfm_check 0 "solids at start: 0.0001312 m\\^3.*cell-steps/s" check ${TFM})
bdl_cli_expect(cli_tfm_bed_height 2
  "\\[solids\\] bed_height = 0.6: out of range; allowed: > 0 and <= the domain's height, 0.45"
  check ${TFM} --set solids.bed_height=0.6)
bdl_cli_expect(cli_tfm_fraction 2 "\\[solids\\] fraction = 0.7: out of range; allowed: \\(0, 0.6\\]"
  check ${TFM} --set solids.fraction=0.7)
bdl_cli_expect(cli_tfm_typo 2 "unknown key in \\[solids\\]; did you mean 'density'"
  check ${TFM} --set solids.densty=3)
bdl_cli_expect(cli_tfm_dt 2 "\\[run\\] dt = 0.002 s is 4 times the gas's expected stable step"
  check ${TFM} --set solids.courant=0 --set run.dt=0.002)
bdl_cli_expect(cli_tfm_no_gas_dt 2 "with \\[solids\\] the gas and the solids share one step"
  check ${TFM} --set run.dt=0)
bdl_cli_expect(cli_tfm_species 2 "tfm_species.ini:11: \\[species\\]: a scene with \\[solids\\] holds no particles"
  check ${CMAKE_CURRENT_SOURCE_DIR}/scenes/tfm_species.ini)
bdl_cli_expect(cli_tfm_no_gas 2 "tfm_no_gas.ini:10: \\[solids\\]: a solids phase lives on the gas's grid"
  check ${CMAKE_CURRENT_SOURCE_DIR}/scenes/tfm_no_gas.ini)
bdl_cli_expect(cli_tfm_fields 2 "\\[output\\] fields_interval = 0.1: the field files average particles"
  check ${TFM} --set output.fields_interval=0.1)
set(TFM2 ${PROJECT_SOURCE_DIR}/scenes/tfm_goldschmidt_binary.ini)
bdl_cli_expect(cli_tfm_phases_check 0 "solids phases \\(multi-fluid model: 1.52 mm.*2.49 mm" check ${TFM2})
bdl_cli_expect(cli_tfm_phases_sum 2
  "\\[phase large\\] fraction = 0.4: out of range: the phases' fractions add up to 0.69167; allowed: a sum <= 0.6"
  check ${TFM2} --set phase.large.fraction=0.4)
bdl_cli_expect(cli_tfm_phases_own 2
  "\\[solids\\] diameter = 0.002: the scene has \\[phase NAME\\] sections, and each phase gives its own"
  check ${TFM2} --set solids.diameter=0.002)
bdl_cli_expect(cli_tfm_phases_kinetic_pressure 2
  "\\[solids\\] kinetic_pressure = implicit: implicit is built for one phase"
  check ${TFM2} --set solids.kinetic_pressure=implicit)
bdl_cli_expect(cli_tfm_phases_one 2 "tfm_one_phase.ini:[0-9]+: \\[phase\\]: one \\[phase NAME\\] section"
  check ${CMAKE_CURRENT_SOURCE_DIR}/scenes/tfm_one_phase.ini)
bdl_cli_expect(cli_tfm_phases_missing 2 "\\[phase small\\] fraction: missing required key; allowed: \\(0, 0.6\\]"
  check ${CMAKE_CURRENT_SOURCE_DIR}/scenes/tfm_phase_no_fraction.ini)
bdl_cli_expect(cli_tfm_phases_layers 2
  "\\[phase large\\] fraction = 0.58: out of range: the phases' fractions add up to 0.87167 at 0.05 m"
  check ${TFM2} --set phase.small.bed_top=0.1 --set phase.large.bed_bottom=0.05 --set phase.large.fraction=0.58)
bdl_cli_expect(cli_tfm_phases_top 2
  "\\[phase small\\] bed_top = 0.5: out of range: the phase's layer runs from 0 to 0.5 m"
  check ${TFM2} --set phase.small.bed_top=0.5)
bdl_cli_expect(cli_parcels_mean_drag 2
  "\\[coupling\\] drag_velocity = mean: a parcel's drag is implicit in its own velocity"
  check ${PROJECT_SOURCE_DIR}/scenes/parcels_bubbling_bed.ini --set coupling.drag_velocity=mean)
bdl_cli_expect(cli_point_implicit_particles 2
  "\\[gas\\] convection_step = point_implicit: point_implicit is for a solids phase on the grid"
  check ${PROJECT_SOURCE_DIR}/scenes/parcels_bubbling_bed.ini --set gas.convection_step=point_implicit)
bdl_cli_expect(cli_tfm_elastic 2 "\\[solids\\] restitution = 1: out of range; allowed: \\(0, 1\\)"
  check ${TFM} --set solids.restitution=1)
bdl_cli_expect(cli_tfm_wave_weight 2
  "\\[solids\\] wave_weight = 0.3: weighs the pressure waves in the step of kinetic_pressure = implicit"
  check ${TFM} --set solids.kinetic_pressure=explicit)
bdl_cli_expect(cli_direct_periodic 2
  "\\[gas\\] pressure_solver = direct: direct needs no periodic axis of more than one cell"
  check ${TFM} --set "domain.periodic=x y")
