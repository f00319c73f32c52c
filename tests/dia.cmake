# Synthetic camera (DIA) images, their ground truth and the calibration.
bdl_add_test(test_dia SOURCES test_dia.c LABELS dia)
