// bedlam — files: crash-safe writing, output folders, whole-file reads, regular files only.
//
// Output files are written to a temporary sibling ("path.tmp.PID") and renamed over the final
// name only once everything reached the disk, so readers (ParaView, --resume) never see a
// half-written file even if the run is killed or the disk fills up.
#ifndef BDL_FILE_H
#define BDL_FILE_H

#include <stddef.h>
#include <stdio.h>

#include "core/error.h"

/// A file being written atomically. Write through `file` with the usual stdio calls, then call
/// exactly one of bdl_atomic_commit or bdl_atomic_abort.
typedef struct bdl_atomic_file {
    FILE *file;            ///< open for binary writing; NULL once committed or aborted
    char final_path[1024]; ///< the name the file gets on commit
    char temp_path[1040];  ///< "final_path.tmp.PID", in the same folder so rename is atomic
} bdl_atomic_file;

/// Opens "path.tmp.PID" for writing. Returns BDL_ERR_IO if the path is too long (>= 1024 bytes)
/// or the temporary file cannot be created (e.g. the folder does not exist); `af->file` is then
/// NULL and nothing needs to be aborted.
bdl_result bdl_atomic_open(bdl_atomic_file *af, const char *path);

/// bdl_atomic_open, then the first line: `header` and a newline (the column names of a CSV file).
bdl_result bdl_atomic_open_csv(bdl_atomic_file *af, const char *path, const char *header);

/// Flushes, fsyncs and closes the temporary file, then renames it over the final path. Any
/// failure along the way (write error, disk full at flush or close, rename refused) removes the
/// temporary file and returns BDL_ERR_IO with errno of the first failure (ENOSPC for a full
/// disk); the previous content of the final path is then intact.
bdl_result bdl_atomic_commit(bdl_atomic_file *af);

/// Closes and deletes the temporary file, leaving the final path untouched; errno is kept for the
/// caller's message. Safe to call on an already committed or aborted file.
void bdl_atomic_abort(bdl_atomic_file *af);

/// Flushes a stdio stream and fsyncs its file, so that what was written survives a kill or a
/// power cut. BDL_ERR_IO with errno set on failure.
bdl_result bdl_sync_file(FILE *file);

/// "PATH: reason" for a write that failed with `error` (an errno value): a full disk reads
/// "PATH: no space left on device (ENOSPC): the disk is full", others the system's text.
void bdl_describe_write_error(char *out, size_t len, const char *path, int error);

/// Deletes the temporary files ("NAME.tmp.PID") a killed process left in `folder`: those whose
/// process no longer exists. Returns how many were deleted (0 when the folder cannot be read).
int bdl_remove_stale_temporaries(const char *folder);

/// Creates a folder and its missing parents, like `mkdir -p`. Existing folders are fine; returns
/// BDL_ERR_IO (errno set, ENOTDIR when a component is not a folder) on failure.
bdl_result bdl_mkdir_p(const char *path);

/// Makes sure `path` is a folder we can create files in: creates it if needed, then creates and
/// deletes a probe file. On failure returns BDL_ERR_IO and writes a sentence naming the cause
/// (the system's error text) into `why` (`why_len` bytes, always terminated when why_len > 0).
bdl_result bdl_check_writable_dir(const char *path, char *why, size_t why_len);

/// Writes `size` bytes to `path` atomically (see bdl_atomic_open and bdl_atomic_commit).
bdl_result bdl_write_file_atomic(const char *path, const void *data, size_t size);

/// Whether `path` is a regular file (symbolic links followed), asked with stat() before anything
/// opens it: a FIFO blocks its reader until a writer comes, a device such as /dev/zero never
/// ends, and a folder reads as empty. Every reader of input files checks with this first. Returns
/// BDL_OK with the file's size in *size (may be NULL), or BDL_ERR_IO with a phrase that follows
/// the path in `why` ("is not a regular file (a FIFO)", "cannot be read: No such file or
/// directory").
bdl_result bdl_check_regular_file(const char *path, long *size, char *why, size_t why_len);

/// fopen(path, "rb") after bdl_check_regular_file; NULL with the phrase in `why` on failure.
FILE *bdl_open_regular(const char *path, char *why, size_t why_len);

/// Reads a whole regular file into a NUL-terminated, malloc'ed buffer (*length bytes before the
/// NUL); NULL with errno set on failure (EINVAL for a FIFO, a device or a folder: call
/// bdl_check_regular_file first for a message).
char *bdl_read_file(const char *path, size_t *length);

#endif
