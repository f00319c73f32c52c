# Hostile sizes, ranges and files: each is refused with exit 2 and a message naming the key (or
# the file), the value and the limit, within 5 s and before anything of its size is allocated
# (docs/validation/reliability.md, "Sizes, ranges and files"). The scenes are small and valid as
# written; --set pushes one key past its limit.
set(L ${CMAKE_CURRENT_SOURCE_DIR}/scenes)
function(bdl_limit_expect name code text)
  bdl_cli_expect(${name} ${code} "${text}" ${ARGN})
  set_tests_properties(${name} PROPERTIES TIMEOUT 5)
endfunction()

# Sizes, estimated before anything is allocated ([guards] max_memory and max_steps).
bdl_limit_expect(cli_limits_count_memory 2
  "limits.ini:19: \\[create bed\\] count = 1000000000000: about [0-9.e+]+ bytes for 1e\\+12 particles, above \\[guards\\] max_memory = [0-9.e+]+ bytes"
  check ${L}/limits.ini --set create.bed.count=1e12)
bdl_limit_expect(cli_limits_count_long 2
  "\\[create bed\\] count = 9223372036854775807: out of range.*integer in \\(0, 1e\\+15\\]"
  check ${L}/limits.ini --set create.bed.count=9223372036854775807)
bdl_limit_expect(cli_limits_gas_cells 2
  "\\[gas\\] cells = 4096 4096 4096: about [0-9.e+]+ bytes for a gas grid of 6.9e\\+10 cells, above \\[guards\\] max_memory"
  check ${L}/limits.ini --set "gas.cells=4096 4096 4096")
bdl_limit_expect(cli_limits_fill 2
  "\\[create bed\\] volume_fraction = 0.05 of particles of \\[species fine\\] diameter = 1e-06 m: about [0-9.e+]+ bytes for 9.55e\\+10 particles, above"
  check ${L}/limits_fill.ini --set species.fine.diameter=1e-6)
bdl_limit_expect(cli_limits_lattice 2
  "\\[create stack\\] type = lattice of \\[species coarse\\] diameter = 1e-06 m.*for 8e\\+11 particles, above \\[guards\\] max_memory"
  check ${L}/limits_fill.ini --set species.coarse.diameter=1e-6)
# A random fill asking for far more than random sequential insertion can place is refused when
# its success rate says so, not after its whole budget of tries (13 s for these 5000 rods).
bdl_limit_expect(cli_limits_jammed_fill 2
  "\\[create bed\\]: random fill placed only [0-9]+ of 5000 particles; random sequential insertion jams"
  check ${L}/rod_sweep.ini --set create.bed.count=5000)
bdl_limit_expect(cli_limits_max_memory 2
  "\\[camera cam\\] width = 100, height = 200, samples = 3: about 1.8e\\+06 bytes for the image buffers, above \\[guards\\] max_memory = 1e\\+06 bytes \\(as given"
  check ${L}/limits.ini --set guards.max_memory=1e6)
bdl_limit_expect(cli_limits_tiny_diameter 2
  "\\[run\\] end_time = 0.1 s with dt = 1.39e-15 s \\(dt_fraction = 0.02 of the smallest contact time, 6.95e-14 s\\): 7.2e\\+13 steps, above \\[guards\\] max_steps = 1e\\+10"
  check ${L}/limits.ini --set species.glass.diameter=1e-9)
# The same nanometre particles with the steps allowed: the placement grid no longer overflows.
bdl_limit_expect(cli_limits_tiny_diameter_built 0 "particles at start: 50 "
  check ${L}/limits.ini --set species.glass.diameter=1e-9 --set guards.max_steps=1e15)
bdl_limit_expect(cli_limits_dt 2
  "\\[run\\] end_time = 0.1 s with dt = 1e-300 s: 1e\\+299 steps, above \\[guards\\] max_steps = 1e\\+10"
  check ${L}/limits.ini --set run.dt=1e-300)

# Ranges.
bdl_limit_expect(cli_limits_end_time 2
  "\\[run\\] end_time = 1e300: out of range.*allowed: \\(0, 1e\\+09\\] \\(s\\)"
  check ${L}/limits.ini --set run.end_time=1e300)
bdl_limit_expect(cli_limits_gravity 2
  "\\[run\\] gravity = 1e308 1e308 1e308: length 1.73e\\+308 out of range.*length <= 1e\\+06 \\(m/s\\^2\\)"
  check ${L}/limits.ini --set "run.gravity=1e308 1e308 1e308")
bdl_limit_expect(cli_limits_domain 2
  "\\[domain\\] max = 1e300 1e300 1e300: component 1 \\(1e\\+300\\) out of range.*each in \\[-1e\\+06, 1e\\+06\\] \\(m\\)"
  check ${L}/limits.ini --set "domain.max=1e300 1e300 1e300")
bdl_limit_expect(cli_limits_diagnostics_interval 2
  "\\[output\\] diagnostics_interval = 1e-300: 1e\\+299 outputs up to end_time = 0.1 s.*must be >= end_time / 1e\\+09 = 1e-10 s"
  run ${L}/limits.ini --quiet --out ${CMAKE_CURRENT_BINARY_DIR}/runs/limits_diag
  --set output.diagnostics_interval=1e-300)
bdl_limit_expect(cli_limits_camera_interval 2
  "\\[camera cam\\] interval = 1e-12: 1e\\+11 outputs up to end_time = 0.1 s"
  check ${L}/limits.ini --set camera.cam.interval=1e-12)
bdl_limit_expect(cli_limits_until 2
  "--until 1e\\+08: \\[output\\] diagnostics_interval = 0.01: 1e\\+10 outputs up to end_time = 1e\\+08 s"
  run ${L}/limits.ini --until 1e8 --quiet --out ${CMAKE_CURRENT_BINARY_DIR}/runs/limits_until)

# Particle files: values and coincident particles.
bdl_limit_expect(cli_limits_csv_nan 2 "limits_nan.csv:3: column 2 \\(y\\) is nan: not a finite number"
  check ${L}/limits_file.ini --set create.bed.file=limits_nan.csv)
bdl_limit_expect(cli_limits_csv_diameter 2
  "limits_huge.csv:3: diameter 1e\\+300 m is outside the sizes of \\[species glass\\], \\[0.001, 0.001\\] m"
  check ${L}/limits_file.ini --set create.bed.file=limits_huge.csv)
bdl_limit_expect(cli_limits_csv_coincident 2
  "limits_coincident.csv: lines 3 and 5: two particles at \\(0.005, 0.005, 0.005\\) m, closer than 1e-06 of the smaller diameter"
  check ${L}/limits_file.ini --set create.bed.file=limits_coincident.csv)

# Files that are not regular, refused before they are opened.
bdl_limit_expect(cli_limits_scene_device 2 "/dev/zero is not a regular file \\(a character device\\)"
  check /dev/zero)
bdl_limit_expect(cli_limits_scene_folder 2 "scenes is not a regular file \\(a folder\\)" check ${L})
bdl_limit_expect(cli_limits_file_device 2
  "\\[create bed\\] file = /dev/zero: '/dev/zero' is not a regular file \\(a character device\\)"
  check ${L}/limits_file.ini --set create.bed.file=/dev/zero)
bdl_limit_expect(cli_limits_file_folder 2 "'.*scenes' is not a regular file \\(a folder\\)"
  check ${L}/limits_file.ini --set create.bed.file=${L})
add_test(NAME cli_limits_fifo COMMAND ${CMAKE_COMMAND} -DBEDLAM=$<TARGET_FILE:bedlam>
  -DSCENE=${L}/limits_file.ini -DWORK=${CMAKE_CURRENT_BINARY_DIR}/runs/limits_fifo
  -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/fifo_cli.cmake)
set_tests_properties(cli_limits_fifo PROPERTIES LABELS cli TIMEOUT 20)

# The overflow-checked size arithmetic, the physical memory and the regular-file check.
bdl_add_test(test_sizes SOURCES test_sizes.c LABELS core TIMEOUT 10)

# Bad mesh files for a [wall] type = mesh: each named with its file and the reason.
foreach(bad "empty.stl;is empty" "truncated.stl;is truncated: its header claims 2 triangles"
    "huge_header.stl;has a header that claims 100000000 triangles; at most 4000000"
    "nan.obj;line 3: 'v' needs three finite numbers"
    "fin.obj;is not a manifold: the edge from \\(0, 0, 0\\) to \\(1, 0, 0\\) is shared by more than two"
    "missing.stl;cannot be read: No such file or directory")
  list(GET bad 0 file)
  list(GET bad 1 reason)
  string(REGEX REPLACE "\\..*" "" stem ${file})
  bdl_limit_expect(cli_limits_mesh_${stem} 2
    "\\[wall plate\\] file = .*meshes/${file}: '.*meshes/${file}' ${reason}"
    check ${L}/limits_mesh.ini --set wall.plate.file=meshes/${file})
endforeach()

# A fill region of region_shape = mesh needs an inside: an open plate, a tetrahedron with one
# triangle turned the other way and a mesh that reaches out of the region's box are refused.
bdl_limit_expect(cli_limits_region_open 2
  "region_file = .*meshes/plate.obj: '.*meshes/plate.obj' is not a closed, consistently turned surface: the edge from \\(-0.02, -0.02, 0\\) to \\(-0.02, 0.02, 0\\) borders one triangle only"
  check ${L}/limits_region.ini --set create.bed.region_file=meshes/plate.obj)
bdl_limit_expect(cli_limits_region_flipped 2
  "'.*meshes/tetra_flipped.obj' is not a closed, consistently turned surface: the edge from \\(0, 0, 0\\) to \\(0.02, 0, 0\\) is run the same way by its two triangles"
  check ${L}/limits_region.ini --set create.bed.region_file=meshes/tetra_flipped.obj)
bdl_limit_expect(cli_limits_region_outside 2
  "\\[create bed\\] region_file = .*meshes/tetra.obj: the mesh, placed, spans \\(0.005, 0, 0\\) to \\(0.025, 0.02, 0.02\\): region_min and region_max must enclose it"
  check ${L}/limits_region.ini --set "create.bed.region_translate=0.005 0 0")
