// bedlam — comma-separated time series (diagnostics.csv) and a small reader for tests and
// analysis.
//
// One header line of column names, then one line of numbers per row. Numbers are printed with
// the fewest digits that read back to the same double, so the file is both readable and exact.
// Column names must not contain commas, quotes or line breaks.
#ifndef BDL_CSV_H
#define BDL_CSV_H

#include "core/error.h"

/// An open CSV file being appended to row by row.
typedef struct bdl_csv bdl_csv;

/// Opens `path` for rows of `column_count` numbers. Without `append` the file is replaced and
/// the header written. With `append` an existing file with exactly this header is continued
/// (an unfinished last line, left by a crash, is cut off first); a missing or empty file gets
/// the header. Returns NULL if the file cannot be opened, memory is short, or when appending to a
/// file whose header differs: replacing it then is the caller's decision.
bdl_csv *bdl_csv_open(const char *path, const char *const *columns, int column_count, int append);

/// Writes one row: `values` holds column_count numbers. Integral values below 1e15 in magnitude
/// print as plain integers; others with up to 17 significant digits, enough to read back exactly.
bdl_result bdl_csv_row(bdl_csv *csv, const double *values);

/// Pushes buffered rows to the operating system, so another program reading the file sees them.
bdl_result bdl_csv_flush(bdl_csv *csv);

/// Pushes buffered rows to the disk (flush and fsync), so that they survive a kill -9 or a power
/// cut: a run calls it before every checkpoint. NULL is allowed.
bdl_result bdl_csv_sync(bdl_csv *csv);

/// Flushes and closes the file and frees `csv` (NULL is allowed). Returns BDL_ERR_IO if a row
/// could not be written (e.g. disk full), including one still buffered.
///
/// Every function here that returns BDL_ERR_IO leaves errno at the first failure's value
/// (ENOSPC for a full disk), for the caller's message.
bdl_result bdl_csv_close(bdl_csv *csv);

/// For --resume: rewrites `path` atomically keeping the header and the complete rows whose first
/// column (time [s]) is <= t_keep [s]. A missing file is not an error (nothing to keep).
bdl_result bdl_csv_truncate_after(const char *path, double t_keep);

/// Reads the column named `column` into `out` (at most `max` values, in row order) and returns
/// how many were stored; with `out` NULL returns the number of rows. Fields that are missing or
/// not numbers read as NaN; a last row without its newline and with fewer fields than the header
/// (cut off when its run was killed) is left out. Returns -1 if the file cannot be read or has no
/// such column.
long bdl_csv_read_column(const char *path, const char *column, double *out, long max);

#endif
