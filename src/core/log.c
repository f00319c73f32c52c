#include "core/log.h"

#include <stdarg.h>

// Logging configuration is process-wide by nature (one terminal, one run log).
static FILE *log_file = NULL;
static int quiet = 0;

void bdl_log_set_file(FILE *file) { log_file = file; }
void bdl_log_set_quiet(int on) { quiet = on; }
FILE *bdl_log_file(void) { return log_file; }

void bdl_log(bdl_log_level level, const char *fmt, ...)
{
    static const char *const prefix[] = {"error: ", "warning: ", "", ""};
    va_list ap;
    if (quiet)
        return;
    if (level <= BDL_LOG_WARN) {
        va_start(ap, fmt);
        fputs(prefix[level], stderr);
        vfprintf(stderr, fmt, ap);
        fputc('\n', stderr);
        va_end(ap);
    }
    if (log_file && level <= BDL_LOG_INFO) {
        va_start(ap, fmt);
        fputs(prefix[level], log_file);
        vfprintf(log_file, fmt, ap);
        fputc('\n', log_file);
        va_end(ap);
    }
}
