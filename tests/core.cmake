bdl_add_test(test_determinism SOURCES test_determinism.c)
target_link_libraries(test_determinism PRIVATE OpenMP::OpenMP_C)
bdl_add_test(test_loop SOURCES test_loop.c)
bdl_add_test(test_outputs SOURCES test_outputs.c)
# Their ThreadSanitizer settings: tests/tsan.cmake.
