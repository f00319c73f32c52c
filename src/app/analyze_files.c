// bedlam analyze — reading columns of a run's CSV files, and drawing plots with gnuplot.
#include "app/analyze_files.h"

#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/file.h"
#include "io/csv.h"

int bdl_analyze_read_column(const char *run, const char *file, const char *column, double **out,
                            long *n)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/%s", run, file);
    *out = NULL;
    long rows = bdl_csv_read_column(path, column, NULL, 0); // count, then read
    *out = rows > 0 ? malloc((size_t)rows * sizeof(double)) : NULL;
    *n = *out ? bdl_csv_read_column(path, column, *out, rows) : -1;
    if (*n <= 0) {
        fprintf(stderr, "error: %s: no column '%s' (or no rows)\n", path, column);
        free(*out);
        *out = NULL;
        return 0;
    }
    return 1;
}

int bdl_analyze_read_series(const char *run, const char *file, const char *column, double **t,
                            double **x, long *n)
{
    long m = 0;
    *t = *x = NULL;
    if (bdl_analyze_read_column(run, file, "time", t, n) &&
        bdl_analyze_read_column(run, file, column, x, &m) && m == *n)
        return 1;
    free(*t), free(*x);
    *t = *x = NULL;
    return 0;
}

int bdl_analyze_read_text(const char *dir, const char *file, char *text, size_t len)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/%s", dir, file);
    char why[256];
    FILE *f = bdl_open_regular(path, why, sizeof why);
    const size_t n = f ? fread(text, 1, len - 1, f) : 0;
    if (f)
        fclose(f);
    text[n] = 0;
    return f != NULL;
}

char *bdl_analyze_read_regular(const char *path, const char *label)
{
    size_t length;
    char why[256];
    char *text = NULL;
    if (bdl_check_regular_file(path, NULL, why, sizeof why) == BDL_OK &&
        !(text = bdl_read_file(path, &length)))
        snprintf(why, sizeof why, "cannot be read: %s", strerror(errno));
    if (!text)
        fprintf(stderr, "error: %s%s%s %s\n", label, *label ? " " : "", path, why);
    return text;
}

/// Where the value of "key" starts in text (NULL when the key is missing).
static const char *json_value(const char *text, const char *key)
{
    char quoted[80];
    snprintf(quoted, sizeof quoted, "\"%s\":", key);
    const char *at = strstr(text, quoted);
    return at ? at + strlen(quoted) : NULL;
}

int bdl_analyze_json_number(const char *text, const char *key, double *out)
{
    const char *at = json_value(text, key);
    return at && sscanf(at, " %lf", out) == 1;
}

int bdl_analyze_json_vec3(const char *text, const char *key, double out[3])
{
    const char *at = json_value(text, key);
    return at && sscanf(at, " [%lf, %lf, %lf]", &out[0], &out[1], &out[2]) == 3;
}

void bdl_analyze_plot(const char *script_path, const char *format, ...)
{
    FILE *f = fopen(script_path, "w");
    if (!f)
        return;
    va_list ap;
    va_start(ap, format);
    vfprintf(f, format, ap);
    va_end(ap);
    fclose(f);
    char cmd[1300];
    snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>&1", script_path);
    if (system(cmd) != 0)
        fprintf(stderr, "warning: gnuplot failed or is missing: no plot\n");
    remove(script_path);
}
