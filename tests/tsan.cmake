# ThreadSanitizer builds (-DBDL_TSAN=ON). GCC's OpenMP runtime, libgomp, is not instrumented: the
# start and end of its parallel regions are invisible to TSan, so every array one region writes
# and the next reads is reported as a race. With clang the build uses LLVM's libomp, whose tool
# Archer (libarcher) tells TSan about them; the threaded tests then run on two threads:
#
#   CC=clang cmake -S . -B build-tsan -DBDL_TSAN=ON && cmake --build build-tsan
#   ctest --test-dir build-tsan -R 'test_loop|test_determinism|test_coupling|tsan'
#
# Without Archer they run with one OpenMP thread (the solver thread against the main thread).
# Mesa's drivers, which draw the frames, are not instrumented either: ignore_noninstrumented_modules.
if(NOT BDL_TSAN)
  return()
endif()
set(BDL_TSAN_OPTIONS "TSAN_OPTIONS=halt_on_error=1 ignore_noninstrumented_modules=1")
get_filename_component(BDL_OMP_DIR "${OpenMP_omp_LIBRARY}" DIRECTORY)
find_library(BDL_ARCHER NAMES archer HINTS ${BDL_OMP_DIR})
set(BDL_TSAN_THREADED test_loop test_determinism test_coupling test_outputs)
if(OpenMP_omp_LIBRARY AND BDL_ARCHER)
  message(STATUS "ThreadSanitizer with libomp and Archer (${BDL_ARCHER}): threaded tests on two threads")
  set(BDL_TSAN_ENV "${BDL_TSAN_OPTIONS};OMP_TOOL_LIBRARIES=${BDL_ARCHER};OMP_WAIT_POLICY=passive")
  set_tests_properties(${BDL_TSAN_THREADED} PROPERTIES ENVIRONMENT "${BDL_TSAN_ENV}")
  # Short two-thread runs: a DEM scene above the parallel threshold, a gas scene, frames, and
  # every output of a run (tests/scenes/kill.ini); TSan exits 66 at its first report.
  add_test(NAME tsan_runs COMMAND sh -c
    "set -e; b=$1; s=$2; t=$3; o=$4; rm -rf $o
     $b run $s/brazil_nut.ini --steps 40 --threads 2 --quiet --out $o/dem
     $b run $s/fluidized_bed.ini --steps 300 --threads 2 --quiet --out $o/gas
     $b run $t/frames.ini --threads 2 --quiet --out $o/frames
     $b run $t/kill.ini --threads 2 --quiet --out $o/outputs
     echo 'no ThreadSanitizer report'" tsan_runs $<TARGET_FILE:bedlam> ${PROJECT_SOURCE_DIR}/scenes
    ${CMAKE_CURRENT_SOURCE_DIR}/scenes ${CMAKE_CURRENT_BINARY_DIR}/runs/tsan)
  set_tests_properties(tsan_runs PROPERTIES LABELS cli TIMEOUT 1200 ENVIRONMENT "${BDL_TSAN_ENV}")
else()
  set_tests_properties(${BDL_TSAN_THREADED} PROPERTIES
    ENVIRONMENT "OMP_NUM_THREADS=1;${BDL_TSAN_OPTIONS}")
endif()
