bdl_add_test(test_io SOURCES test_io.c)
bdl_add_test(test_png SOURCES test_png.c)
