bdl_add_test(test_determinism SOURCES test_determinism.c)
target_link_libraries(test_determinism PRIVATE OpenMP::OpenMP_C)
bdl_add_test(test_loop SOURCES test_loop.c)
# libgomp is not instrumented for ThreadSanitizer, so its barriers look like races: the TSan
# build checks the solver thread against the main thread with one OpenMP thread.
if(BDL_TSAN)
  set_tests_properties(test_loop test_determinism PROPERTIES
    ENVIRONMENT "OMP_NUM_THREADS=1;TSAN_OPTIONS=halt_on_error=1")
endif()
