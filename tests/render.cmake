# Renderer: golden images on the headless backends, frames of a run, the window under Xvfb.
bdl_add_test(test_colormap SOURCES test_colormap.c LABELS render)
bdl_add_test(test_font SOURCES test_font.c LABELS render)
set_tests_properties(test_font PROPERTIES SKIP_RETURN_CODE 77)
bdl_add_test(test_render SOURCES test_render.c LABELS render TIMEOUT 300)

foreach(gl egl osmesa)
  add_test(NAME cli_frames_${gl} COMMAND ${CMAKE_COMMAND} -DBEDLAM=$<TARGET_FILE:bedlam>
    -DSCENE=${CMAKE_CURRENT_SOURCE_DIR}/scenes/frames.ini -DWORK=${CMAKE_CURRENT_BINARY_DIR}/runs/frames_${gl}
    -DGL=${gl} -DCOUNT=6 -DWIDTH=320 -DHEIGHT=200 -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/frames_cli.cmake)
  set_tests_properties(cli_frames_${gl} PROPERTIES LABELS "render;cli" TIMEOUT 300)
endforeach()

if(BDL_WITH_SDL)
  add_test(NAME view_xvfb COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/scripts/view_xvfb.sh
    $<TARGET_FILE:bedlam> ${PROJECT_SOURCE_DIR}/scenes/vibrated_bed.ini ${CMAKE_CURRENT_BINARY_DIR}/runs/view)
  set_tests_properties(view_xvfb PROPERTIES LABELS "render;cli" TIMEOUT 300 SKIP_RETURN_CODE 77)
  add_test(NAME view_parcels COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/scripts/view_parcels.sh
    $<TARGET_FILE:bedlam> ${PROJECT_SOURCE_DIR}/scenes/parcels_settling.ini ${CMAKE_CURRENT_BINARY_DIR}/runs/view_parcels)
  set_tests_properties(view_parcels PROPERTIES LABELS "render;cli" TIMEOUT 300 SKIP_RETURN_CODE 77)
  # Under GLX, SDL unloads libGL at exit and Mesa's driver goes with it, so LeakSanitizer
  # sees the driver's lifetime allocations without a module to suppress them by. The renderer
  # itself is leak-checked by test_render and cli_frames_*; here only memory errors count.
  if(BDL_SANITIZE)
    set_property(TEST view_xvfb view_parcels APPEND PROPERTY ENVIRONMENT "ASAN_OPTIONS=detect_leaks=0:abort_on_error=1")
  else()
    # Every scene opens in the window (a few frames and a screenshot each); the sanitizer build
    # leaves it to view_xvfb, which drives the same window through every key.
    file(GLOB BDL_VIEW_SCENES ${PROJECT_SOURCE_DIR}/scenes/*.ini)
    add_test(NAME view_scenes COMMAND sh ${CMAKE_CURRENT_SOURCE_DIR}/scripts/view_open.sh
      $<TARGET_FILE:bedlam> ${CMAKE_CURRENT_BINARY_DIR}/runs/view_scenes ${BDL_VIEW_SCENES})
    set_tests_properties(view_scenes PROPERTIES LABELS "render;cli" TIMEOUT 600 SKIP_RETURN_CODE 77)
  endif()
endif()
bdl_cli_expect(cli_view_help 0 "Press H" view --help)
bdl_cli_expect(cli_bench_render_help 0 "frames per second|Frames per second" bench render --help)
bdl_cli_expect(cli_run_gl_sdl 2 "headless" run ${PROJECT_SOURCE_DIR}/scenes/bouncing_ball.ini --gl sdl)
bdl_cli_expect(cli_bad_gl 2 "egl or osmesa" run ${PROJECT_SOURCE_DIR}/scenes/bouncing_ball.ini --gl vulkan)

# Parcels: their display radius, real-particle count and solids fraction in the snapshot, drawn
# headless; frames of a run of parcels.
bdl_add_test(test_render_parcels SOURCES test_render_parcels.c LABELS render TIMEOUT 300)
add_test(NAME cli_frames_parcels COMMAND ${CMAKE_COMMAND} -DBEDLAM=$<TARGET_FILE:bedlam>
  -DSCENE=${CMAKE_CURRENT_SOURCE_DIR}/scenes/parcels_frames.ini -DWORK=${CMAKE_CURRENT_BINARY_DIR}/runs/frames_parcels
  -DGL=egl -DCOUNT=3 -DWIDTH=240 -DHEIGHT=320 -P ${CMAKE_CURRENT_SOURCE_DIR}/scripts/frames_cli.cmake)
set_tests_properties(cli_frames_parcels PROPERTIES LABELS "render;cli" TIMEOUT 300)
