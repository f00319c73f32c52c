// bedlam — CSV time series: writer, --resume truncation and a column reader.
#define _POSIX_C_SOURCE 200809L
#include "io/csv.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/file.h"

struct bdl_csv {
    FILE *file;
    int column_count;
    int failed; ///< a write already failed; reported again by close
    int error;  ///< errno of the first failure (ENOSPC: the disk is full)
};

/// Marks the file failed with the errno of the first failure, and sets errno to it.
static bdl_result failure(bdl_csv *csv)
{
    if (!csv->failed) {
        csv->failed = 1;
        csv->error = errno ? errno : EIO;
    }
    errno = csv->error;
    return BDL_ERR_IO;
}

/// Reads one line with getline; returns its length, or -1 at the end of the file.
static long read_line(FILE *file, char **line, size_t *capacity)
{
    ssize_t length = getline(line, capacity, file);
    return (long)length;
}

/// Drops a trailing "\n" or "\r\n" in place and returns the new length.
static long chomp(char *line, long length)
{
    while (length > 0 && (line[length - 1] == '\n' || line[length - 1] == '\r'))
        line[--length] = '\0';
    return length;
}

/// The header line (without newline) for these columns, or NULL when out of memory.
static char *make_header(const char *const *columns, int column_count)
{
    size_t length = 1;
    for (int i = 0; i < column_count; ++i)
        length += strlen(columns[i]) + 1;
    char *header = malloc(length);
    if (!header)
        return NULL;
    header[0] = '\0';
    for (int i = 0; i < column_count; ++i) {
        if (i > 0)
            strcat(header, ",");
        strcat(header, columns[i]);
    }
    return header;
}

/// Scans an existing file for appending: copies its first line into `*first_line` (NULL for an
/// empty file) and sets `*complete_size` to the byte count up to the last newline. Returns 0 if
/// the file is missing, 1 if it was scanned, -1 on a read error or out of memory.
static int scan_existing(const char *path, char **first_line, long *complete_size)
{
    *first_line = NULL;
    *complete_size = 0;
    char why[256];
    errno = 0;
    FILE *file = bdl_open_regular(path, why, sizeof why); // a FIFO here would block
    if (!file)
        return errno == ENOENT ? 0 : -1;
    char *line = NULL;
    size_t capacity = 0;
    long length, lines = 0;
    int status = 1;
    while (status == 1 && (length = read_line(file, &line, &capacity)) >= 0) {
        if (line[length - 1] != '\n')
            break;
        if (lines++ == 0) {
            *first_line = malloc((size_t)length + 1);
            if (*first_line)
                memcpy(*first_line, line, (size_t)length + 1);
            else
                status = -1;
        }
        *complete_size += length;
    }
    if (ferror(file))
        status = -1;
    free(line);
    fclose(file);
    if (*first_line)
        chomp(*first_line, (long)strlen(*first_line));
    return status;
}

/// Prepares an existing file for appending rows. Returns 1 if the header must still be written,
/// 0 if the file continues with a matching header, -1 on failure or a different header.
static int prepare_append(const char *path, const char *header)
{
    char *first_line;
    long complete_size;
    int status = scan_existing(path, &first_line, &complete_size);
    if (status <= 0) {
        free(first_line);
        return status == 0 ? 1 : -1;
    }
    int result = first_line == NULL ? 1 : (strcmp(first_line, header) == 0 ? 0 : -1);
    free(first_line);
    // A crash can leave half a row; cutting it keeps every line parseable.
    if (result >= 0 && truncate(path, (off_t)complete_size) != 0)
        return -1;
    return result;
}

bdl_csv *bdl_csv_open(const char *path, const char *const *columns, int column_count, int append)
{
    if (column_count < 1)
        return NULL;
    char *header = make_header(columns, column_count);
    bdl_csv *csv = calloc(1, sizeof *csv);
    if (!header || !csv) {
        free(header);
        free(csv);
        return NULL;
    }
    int need_header = append ? prepare_append(path, header) : 1;
    csv->column_count = column_count;
    csv->file = need_header >= 0 ? fopen(path, append ? "ab" : "wb") : NULL;
    if (csv->file && need_header == 1 && fprintf(csv->file, "%s\n", header) < 0)
        failure(csv);
    free(header);
    if (!csv->file) {
        free(csv);
        return NULL;
    }
    return csv;
}

/// Prints `value` with the fewest significant digits (15 to 17) that read back exactly.
static void format_number(char *text, size_t size, double value)
{
    if (value == floor(value) && fabs(value) < 1e15) {
        snprintf(text, size, "%.0f", value);
        return;
    }
    for (int digits = 15; digits <= 17; ++digits) {
        snprintf(text, size, "%.*g", digits, value);
        if (strtod(text, NULL) == value)
            return;
    }
}

bdl_result bdl_csv_row(bdl_csv *csv, const double *values)
{
    char text[64];
    for (int i = 0; i < csv->column_count; ++i) {
        format_number(text, sizeof text, values[i]);
        if (fputs(text, csv->file) < 0 ||
            fputc(i + 1 < csv->column_count ? ',' : '\n', csv->file) == EOF)
            failure(csv);
    }
    return csv->failed ? failure(csv) : BDL_OK;
}

bdl_result bdl_csv_flush(bdl_csv *csv)
{
    if (fflush(csv->file) != 0)
        failure(csv);
    return csv->failed ? failure(csv) : BDL_OK;
}

bdl_result bdl_csv_sync(bdl_csv *csv)
{
    if (!csv)
        return BDL_OK;
    if (!csv->failed && bdl_sync_file(csv->file) != BDL_OK)
        failure(csv);
    return csv->failed ? failure(csv) : BDL_OK;
}

bdl_result bdl_csv_close(bdl_csv *csv)
{
    if (!csv)
        return BDL_OK;
    if (fflush(csv->file) != 0 || ferror(csv->file))
        failure(csv);
    if (fclose(csv->file) != 0)
        failure(csv);
    const int failed = csv->failed, error = csv->error;
    free(csv);
    errno = error;
    return failed ? BDL_ERR_IO : BDL_OK;
}

/// Whether a complete data line starts with a time <= t_keep.
static int keep_row(const char *line, double t_keep)
{
    char *end;
    double time = strtod(line, &end);
    return end != line && (*end == ',' || *end == '\n' || *end == '\r') && time <= t_keep;
}

/// Copies the header and the rows to keep from `in` to `out`. Returns 0 on a read error.
static int copy_kept_rows(FILE *in, FILE *out, double t_keep)
{
    char *line = NULL;
    size_t capacity = 0;
    long length, lines = 0;
    while ((length = read_line(in, &line, &capacity)) >= 0) {
        // An unfinished last line is a row cut by a crash: never keep it.
        if (line[length - 1] != '\n')
            break;
        if (lines++ == 0 || keep_row(line, t_keep))
            fwrite(line, 1, (size_t)length, out);
    }
    free(line);
    return !ferror(in);
}

bdl_result bdl_csv_truncate_after(const char *path, double t_keep)
{
    char why[256];
    errno = 0;
    FILE *in = bdl_open_regular(path, why, sizeof why);
    if (!in)
        return errno == ENOENT ? BDL_OK : BDL_ERR_IO;
    bdl_atomic_file af;
    bdl_result r = bdl_atomic_open(&af, path);
    if (r != BDL_OK) {
        fclose(in);
        return r;
    }
    int ok = copy_kept_rows(in, af.file, t_keep);
    fclose(in);
    if (!ok) {
        bdl_atomic_abort(&af);
        return BDL_ERR_IO;
    }
    return bdl_atomic_commit(&af);
}

/// Index of `column` in a header line (newline already removed), or -1.
static int find_column(char *header, const char *column)
{
    int index = 0;
    for (char *field = header;; ++index) {
        char *comma = strchr(field, ',');
        size_t length = comma ? (size_t)(comma - field) : strlen(field);
        if (length == strlen(column) && strncmp(field, column, length) == 0)
            return index;
        if (!comma)
            return -1;
        field = comma + 1;
    }
}

static int count_fields(const char *line)
{
    int n = 1;
    for (const char *c = strchr(line, ','); c; c = strchr(c + 1, ','))
        ++n;
    return n;
}

/// The number in field `index` of a data line, or NaN if it is missing or not a number.
static double field_value(const char *line, int index)
{
    for (int i = 0; i < index; ++i) {
        line = strchr(line, ',');
        if (!line)
            return (double)NAN;
        ++line;
    }
    char *end;
    double value = strtod(line, &end);
    return end != line && (*end == ',' || *end == '\0') ? value : (double)NAN;
}

long bdl_csv_read_column(const char *path, const char *column, double *out, long max)
{
    char why[256];
    FILE *file = bdl_open_regular(path, why, sizeof why);
    if (!file)
        return -1;
    char *line = NULL;
    size_t capacity = 0;
    long length = read_line(file, &line, &capacity);
    int index = -1, fields = 0;
    if (length >= 0) {
        chomp(line, length);
        fields = count_fields(line);
        index = find_column(line, column);
    }
    long count = 0;
    while (index >= 0 && (out == NULL || count < max) &&
           (length = read_line(file, &line, &capacity)) >= 0) {
        const int complete = length > 0 && line[length - 1] == '\n';
        if (chomp(line, length) == 0)
            continue; // blank lines, e.g. at the end of a hand-edited file
        if (!complete && count_fields(line) < fields)
            break; // the last row, cut off when its run was killed while writing it
        if (out)
            out[count] = field_value(line, index);
        ++count;
    }
    int failed = index < 0 || ferror(file);
    free(line);
    fclose(file);
    return failed ? -1 : count;
}
