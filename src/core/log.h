// bedlam — logging to stderr and, optionally, a run log file.
#ifndef BDL_LOG_H
#define BDL_LOG_H

#include <stdio.h>

typedef enum bdl_log_level {
    BDL_LOG_ERROR,
    BDL_LOG_WARN,
    BDL_LOG_INFO,
    BDL_LOG_DEBUG
} bdl_log_level;

/// Errors and warnings go to stderr; everything up to INFO also goes to `file` if set (the run's
/// run.log).
void bdl_log_set_file(FILE *file);
FILE *bdl_log_file(void);
/// Nothing is logged while on (the MPI ranks but the first, which say what it says).
void bdl_log_set_quiet(int on);

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
void bdl_log(bdl_log_level level, const char *fmt, ...);

#define bdl_error(...) bdl_log(BDL_LOG_ERROR, __VA_ARGS__)
#define bdl_warn(...)  bdl_log(BDL_LOG_WARN, __VA_ARGS__)
#define bdl_info(...)  bdl_log(BDL_LOG_INFO, __VA_ARGS__)

#endif
