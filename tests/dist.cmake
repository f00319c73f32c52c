# The division of the box between MPI ranks (any build; no MPI needed).
bdl_add_test(test_decomp SOURCES test_decomp.c LABELS dem)
