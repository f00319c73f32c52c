// bedlam — crash-safe file writing: temporary sibling, fsync, rename.
#define _POSIX_C_SOURCE 200809L
#include "core/file.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

bdl_result bdl_atomic_open(bdl_atomic_file *af, const char *path)
{
    af->file = NULL;
    af->final_path[0] = '\0';
    af->temp_path[0] = '\0';
    size_t length = strlen(path);
    if (length == 0 || length >= sizeof af->final_path) {
        errno = ENAMETOOLONG;
        return BDL_ERR_IO;
    }
    memcpy(af->final_path, path, length + 1);
    // The PID keeps two processes writing the same output folder from sharing a temporary file.
    int written = snprintf(af->temp_path, sizeof af->temp_path, "%s.tmp.%ld", path, (long)getpid());
    if (written < 0 || (size_t)written >= sizeof af->temp_path) {
        errno = ENAMETOOLONG;
        return BDL_ERR_IO;
    }
    af->file = fopen(af->temp_path, "wb");
    return af->file ? BDL_OK : BDL_ERR_IO;
}

/// Makes the rename itself durable. Some file systems refuse fsync on folders; that only weakens
/// durability after a power cut, never consistency, so failures here are ignored.
static void sync_parent_folder(const char *path)
{
    char folder[1024];
    const char *slash = strrchr(path, '/');
    if (!slash) {
        strcpy(folder, ".");
    } else if (slash == path) {
        strcpy(folder, "/");
    } else {
        size_t length = (size_t)(slash - path);
        memcpy(folder, path, length);
        folder[length] = '\0';
    }
    int fd = open(folder, O_RDONLY);
    if (fd >= 0) {
        fsync(fd);
        close(fd);
    }
}

bdl_result bdl_atomic_open_csv(bdl_atomic_file *af, const char *path, const char *header)
{
    bdl_result r = bdl_atomic_open(af, path);
    if (r == BDL_OK)
        fprintf(af->file, "%s\n", header);
    return r;
}

bdl_result bdl_atomic_commit(bdl_atomic_file *af)
{
    if (!af->file)
        return BDL_ERR_IO;
    FILE *file = af->file;
    af->file = NULL;
    // The first failure's errno is the one reported: a full disk seen by fflush stays ENOSPC
    // whatever fclose and unlink do afterwards.
    int saved = 0;
    if (fflush(file) != 0 || ferror(file))
        saved = errno ? errno : EIO;
    if (!saved && fsync(fileno(file)) != 0)
        saved = errno;
    // fclose can be the first call to see a full disk, so its result matters too.
    if (fclose(file) != 0 && !saved)
        saved = errno;
    if (!saved && rename(af->temp_path, af->final_path) != 0)
        saved = errno;
    if (saved) {
        unlink(af->temp_path);
        errno = saved;
        return BDL_ERR_IO;
    }
    sync_parent_folder(af->final_path);
    return BDL_OK;
}

void bdl_atomic_abort(bdl_atomic_file *af)
{
    if (!af->file)
        return;
    const int saved = errno; // the caller reports the failure that made it abort
    fclose(af->file);
    af->file = NULL;
    unlink(af->temp_path);
    errno = saved;
}

bdl_result bdl_sync_file(FILE *file)
{
    if (fflush(file) != 0 || ferror(file)) {
        if (errno == 0)
            errno = EIO;
        return BDL_ERR_IO;
    }
    return fsync(fileno(file)) == 0 ? BDL_OK : BDL_ERR_IO;
}

void bdl_describe_write_error(char *out, size_t len, const char *path, int error)
{
    if (len == 0)
        return;
    if (error == ENOSPC) {
        snprintf(out, len, "%s: no space left on device (ENOSPC): the disk is full", path);
        return;
    }
    if (error == EDQUOT) {
        snprintf(out, len, "%s: disk quota exceeded (EDQUOT)", path);
        return;
    }
    char text[256];
    if (error == 0 || strerror_r(error, text, sizeof text) != 0)
        snprintf(text, sizeof text, "%s", error == 0 ? "write failed" : "unknown error");
    if (text[0] >= 'A' && text[0] <= 'Z') // a clause after the path, as the two above
        text[0] = (char)(text[0] - 'A' + 'a');
    snprintf(out, len, "%s: %s", path, text);
}

/// Whether `name` is "STEM.tmp.PID" and returns PID, else 0.
static long temporary_pid(const char *name)
{
    const char *tmp = strstr(name, ".tmp.");
    if (!tmp || tmp == name)
        return 0;
    char *end;
    long pid = strtol(tmp + 5, &end, 10);
    return *end == '\0' && end != tmp + 5 && pid > 0 ? pid : 0;
}

int bdl_remove_stale_temporaries(const char *folder)
{
    DIR *dir = opendir(folder);
    if (!dir)
        return 0;
    int removed = 0;
    char path[1300];
    for (struct dirent *e; (e = readdir(dir));) {
        const long pid = temporary_pid(e->d_name);
        // A temporary of a live process is someone's file being written: left alone.
        if (pid == 0 || pid == (long)getpid() || kill((pid_t)pid, 0) == 0 || errno != ESRCH)
            continue;
        snprintf(path, sizeof path, "%s/%s", folder, e->d_name);
        removed += unlink(path) == 0;
    }
    closedir(dir);
    return removed;
}

/// mkdir that accepts an existing folder and reports ENOTDIR for anything else in the way.
static int make_one_folder(const char *path)
{
    if (mkdir(path, 0777) == 0)
        return 0;
    int saved = errno;
    struct stat info;
    if (stat(path, &info) == 0) {
        if (S_ISDIR(info.st_mode))
            return 0;
        errno = ENOTDIR;
        return -1;
    }
    errno = saved;
    return -1;
}

bdl_result bdl_mkdir_p(const char *path)
{
    size_t length = strlen(path);
    if (length == 0) {
        errno = ENOENT;
        return BDL_ERR_IO;
    }
    char *copy = malloc(length + 1);
    if (!copy)
        return BDL_ERR_NOMEM;
    memcpy(copy, path, length + 1);
    int status = 0;
    // Create every prefix ending just before a '/', then the whole path.
    for (size_t i = 1; i < length && status == 0; ++i) {
        if (copy[i] != '/' || copy[i - 1] == '/')
            continue;
        copy[i] = '\0';
        status = make_one_folder(copy);
        copy[i] = '/';
    }
    if (status == 0)
        status = make_one_folder(copy);
    int saved = errno;
    free(copy);
    errno = saved;
    return status == 0 ? BDL_OK : BDL_ERR_IO;
}

static void describe_errno(char *why, size_t why_len, const char *what, const char *path, int error)
{
    if (why_len == 0)
        return;
    char text[256];
    if (strerror_r(error, text, sizeof text) != 0)
        snprintf(text, sizeof text, "error %d", error);
    snprintf(why, why_len, "cannot %s '%s': %s", what, path, text);
}

bdl_result bdl_check_writable_dir(const char *path, char *why, size_t why_len)
{
    if (why_len > 0)
        why[0] = '\0';
    bdl_result r = bdl_mkdir_p(path);
    if (r != BDL_OK) {
        describe_errno(why, why_len, "create the folder", path, errno);
        return r;
    }
    char probe[1200];
    int written = snprintf(probe, sizeof probe, "%s/.bedlam-probe.%ld", path, (long)getpid());
    if (written < 0 || (size_t)written >= sizeof probe) {
        describe_errno(why, why_len, "use the folder", path, ENAMETOOLONG);
        return BDL_ERR_IO;
    }
    int fd = open(probe, O_WRONLY | O_CREAT | O_TRUNC, 0666);
    if (fd < 0) {
        describe_errno(why, why_len, "create a file in the folder", path, errno);
        return BDL_ERR_IO;
    }
    close(fd);
    if (unlink(probe) != 0) {
        describe_errno(why, why_len, "delete a file in the folder", path, errno);
        return BDL_ERR_IO;
    }
    return BDL_OK;
}

bdl_result bdl_write_file_atomic(const char *path, const void *data, size_t size)
{
    bdl_atomic_file af;
    bdl_result r = bdl_atomic_open(&af, path);
    if (r != BDL_OK)
        return r;
    if (size > 0 && fwrite(data, 1, size, af.file) != size) {
        bdl_atomic_abort(&af);
        return BDL_ERR_IO;
    }
    return bdl_atomic_commit(&af);
}

/// What a file that is not regular is, for messages.
static const char *file_kind(mode_t mode)
{
    if (S_ISDIR(mode))
        return "a folder";
    if (S_ISFIFO(mode))
        return "a FIFO";
    if (S_ISCHR(mode))
        return "a character device";
    if (S_ISBLK(mode))
        return "a block device";
    if (S_ISSOCK(mode))
        return "a socket";
    return "not a file";
}

bdl_result bdl_check_regular_file(const char *path, long *size, char *why, size_t why_len)
{
    struct stat st;
    if (stat(path, &st) != 0) {
        snprintf(why, why_len, "cannot be read: %s", strerror(errno));
        return BDL_ERR_IO;
    }
    if (!S_ISREG(st.st_mode)) {
        snprintf(why, why_len, "is not a regular file (%s)", file_kind(st.st_mode));
        return BDL_ERR_IO;
    }
    if (size)
        *size = (long)st.st_size;
    return BDL_OK;
}

FILE *bdl_open_regular(const char *path, char *why, size_t why_len)
{
    if (bdl_check_regular_file(path, NULL, why, why_len) != BDL_OK)
        return NULL;
    FILE *file = fopen(path, "rb");
    if (!file)
        snprintf(why, why_len, "cannot be read: %s", strerror(errno));
    return file;
}

/// Reads a whole regular file; NULL with errno set on failure. The text is NUL-terminated.
char *bdl_read_file(const char *path, size_t *length)
{
    char why[256];
    errno = 0;
    if (bdl_check_regular_file(path, NULL, why, sizeof why) != BDL_OK) {
        if (errno == 0)
            errno = EINVAL;
        return NULL;
    }
    FILE *file = fopen(path, "rb");
    if (!file)
        return NULL;
    size_t capacity = 1 << 16, used = 0;
    char *text = malloc(capacity);
    while (text) {
        used += fread(text + used, 1, capacity - used - 1, file);
        if (ferror(file) || feof(file))
            break;
        char *grown = realloc(text, capacity * 2);
        if (!grown) {
            free(text);
            text = NULL;
            errno = ENOMEM;
            break;
        }
        text = grown;
        capacity *= 2;
    }
    int failed = !text || ferror(file);
    fclose(file);
    if (failed) {
        free(text);
        if (errno == 0)
            errno = EIO;
        return NULL;
    }
    text[used] = '\0';
    *length = used;
    return text;
}
