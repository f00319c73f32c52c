// bedlam analyze — reading columns of a run's CSV files, and drawing plots with gnuplot.
#ifndef BDL_ANALYZE_FILES_H
#define BDL_ANALYZE_FILES_H

#include <stddef.h>

/// Reads one column of RUN/FILE (a CSV with a header) into a malloc'ed array; prints an error
/// and returns 0 when it is missing or empty.
int bdl_analyze_read_column(const char *run, const char *file, const char *column, double **out,
                            long *n);

/// Reads the time column and `column` of RUN/FILE into malloc'ed arrays of *n rows each; returns
/// 0 (nothing to free) when either is missing or their lengths differ.
int bdl_analyze_read_series(const char *run, const char *file, const char *column, double **t,
                            double **x, long *n);

/// Reads DIR/FILE (at most len - 1 bytes) into text, NUL-terminated; 0 when it cannot be read.
int bdl_analyze_read_text(const char *dir, const char *file, char *text, size_t len);

/// Reads the whole regular file at `path` into a malloc'ed, NUL-terminated text; prints "error:
/// LABEL PATH REASON" (label "" or e.g. "--fit") and returns NULL when it is no regular file or
/// cannot be read.
char *bdl_analyze_read_regular(const char *path, const char *label);

/// The number after "key": in a JSON text written by bedlam (camera.json, fit.json); 0 if none.
int bdl_analyze_json_number(const char *text, const char *key, double *out);

/// The three numbers of "key": [x, y, z] in such a text; 0 if none.
int bdl_analyze_json_vec3(const char *text, const char *key, double out[3]);

/// Writes a gnuplot script (a printf format and its arguments) to `script_path`, runs gnuplot on
/// it and deletes it; warns when gnuplot is missing. Nothing happens when the script cannot be
/// written: a plot is never what an analysis fails on.
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
void bdl_analyze_plot(const char *script_path, const char *format, ...);

#endif
