bdl_add_test(test_io SOURCES test_io.c)
bdl_add_test(test_png SOURCES test_png.c)
# Checkpoints as untrusted input: damaged, truncated, crafted and mismatched files are refused.
bdl_add_test(test_checkpoint_hostile SOURCES test_checkpoint_hostile.c TIMEOUT 120)
