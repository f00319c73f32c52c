# The layers of src/ and the folders in each, bottom up, and which folders each folder may
# include. One table, read by the build (CMakeLists.txt: one library per layer, each seeing only
# its own and lower folders' headers) and by the test that checks every #include between folders
# (cmake/check_layers.cmake). docs/architecture.md draws it.
#
#   solver   core, then the solvers and what they are built from: particles (dem), gas (cfd),
#            their coupling (couple), parcels of many real particles (parcels, next), solids
#            phases on the gas grid (solids, next), array analyses (analysis), scene descriptions
#            (scene), the world that owns one of each
#   output   plain data and file formats (io: snapshots, CSV, VTK, PNG) and what a run writes of
#            a world (output: capturing snapshots, diagnostics, checkpoints, field files)
#   render   drawing snapshots (render) and synthetic camera images (dia)
#   run      the solver thread and the run driver (run), verification cases (verify)
#   app      the command line

set(BDL_LAYERS solver output render run app)
set(BDL_LAYER_solver core dem dist cfd couple parcels solids analysis scene world)
set(BDL_LAYER_output io output)
set(BDL_LAYER_render render dia)
set(BDL_LAYER_run run verify)
set(BDL_LAYER_app app)

# Folder: the other folders it may include. Within a layer the order is the one listed above:
# a folder uses only folders before it.
set(BDL_USES_core "")
set(BDL_USES_dem core)
set(BDL_USES_dist core dem)
set(BDL_USES_cfd core)
set(BDL_USES_couple core dem cfd)
# The next solvers have their places before their folders exist (docs/architecture.md).
set(BDL_USES_parcels core dem cfd couple)
set(BDL_USES_solids core cfd couple)
set(BDL_USES_analysis core)
set(BDL_USES_scene core dem cfd couple parcels solids)
set(BDL_USES_world core dem dist cfd couple parcels solids analysis scene)
set(BDL_USES_io core)
set(BDL_USES_output core dem dist cfd couple parcels solids analysis scene world io)
set(BDL_USES_render core analysis scene io)
set(BDL_USES_dia core scene io)
set(BDL_USES_run core dem dist cfd couple parcels solids analysis scene world io output render dia)
set(BDL_USES_verify core dem dist cfd couple parcels solids analysis scene world io output render dia
    run)
set(BDL_USES_app core dem dist cfd couple parcels solids analysis scene world io output render dia run
    verify)
