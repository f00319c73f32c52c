// Sizes that must not overflow and files that must be regular: the overflow-checked arithmetic
// of core/memory.h at and around SIZE_MAX, bdl_grow refusing a count whose bytes do not fit,
// the machine's physical memory, and bdl_check_regular_file on a file, a folder, a device and a
// FIFO (stat only: the FIFO is never opened, so the test cannot block on it).
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "core/file.h"
#include "core/memory.h"

static void test_arithmetic(void)
{
    size_t out = 7;
    CHECK(bdl_size_mul(3, 5, &out) && out == 15);
    CHECK(bdl_size_mul(0, SIZE_MAX, &out) && out == 0);
    CHECK(bdl_size_mul(SIZE_MAX, 1, &out) && out == SIZE_MAX);
    const size_t half = SIZE_MAX / 2 + 1; // 2^63 on a 64-bit machine
    out = 7;
    CHECK(!bdl_size_mul(half, 2, &out) && out == 7); // untouched on overflow
    CHECK(bdl_size_mul(half - 1, 2, &out) && out == SIZE_MAX - 1);
    // 4096^3 cells of 8 bytes fit; the count of 1e12 particles times a kilobyte fits; a count
    // of 2^62 times 8 bytes does not.
    CHECK(bdl_size_mul3(4096, 4096, 4096, &out) && out == (size_t)1 << 36);
    CHECK(!bdl_size_mul3((size_t)1 << 62, 4, 2, &out));
    CHECK(!bdl_size_mul3(2, (size_t)1 << 62, 4, &out));
    CHECK(bdl_size_add(SIZE_MAX - 1, 1, &out) && out == SIZE_MAX);
    out = 7;
    CHECK(!bdl_size_add(SIZE_MAX, 1, &out) && out == 7);
    CHECK(!bdl_size_add(half, half, &out));
}

static void test_grow(void)
{
    double *p = NULL;
    CHECK(bdl_grow((void **)&p, 10, sizeof *p) && p != NULL);
    for (int k = 0; k < 10; ++k)
        p[k] = k;
    double *kept = p;
    // LONG_MAX elements of 8 bytes: the byte count overflows, the array is left as it was.
    CHECK(!bdl_grow((void **)&p, 0x7fffffffffffffffL, sizeof *p));
    CHECK(p == kept && p[9] == 9.0);
    free(p);
}

static void test_memory(void)
{
    const double bytes = bdl_physical_memory();
    CHECK_MSG(bytes > 1e8 && bytes < 1e16, "physical memory %g bytes", bytes);
}

static void test_regular(void)
{
    char dir[] = "/tmp/bdl_sizes_XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    char file[64], fifo[64], why[256];
    snprintf(file, sizeof file, "%s/file.csv", dir);
    snprintf(fifo, sizeof fifo, "%s/fifo", dir);
    FILE *f = fopen(file, "w");
    CHECK(f != NULL);
    if (f) {
        fputs("x,y,z\n", f);
        fclose(f);
    }
    CHECK(mkfifo(fifo, 0600) == 0);
    long size = -1;
    CHECK(bdl_check_regular_file(file, &size, why, sizeof why) == BDL_OK && size == 6);
    CHECK(bdl_check_regular_file(fifo, NULL, why, sizeof why) == BDL_ERR_IO);
    CHECK_MSG(strcmp(why, "is not a regular file (a FIFO)") == 0, "%s", why);
    CHECK(bdl_check_regular_file(dir, NULL, why, sizeof why) == BDL_ERR_IO);
    CHECK_MSG(strcmp(why, "is not a regular file (a folder)") == 0, "%s", why);
    CHECK(bdl_check_regular_file("/dev/zero", NULL, why, sizeof why) == BDL_ERR_IO);
    CHECK_MSG(strcmp(why, "is not a regular file (a character device)") == 0, "%s", why);
    CHECK(bdl_check_regular_file("/nonexistent/x", NULL, why, sizeof why) == BDL_ERR_IO);
    CHECK_MSG(strstr(why, "cannot be read: ") == why, "%s", why);
    // The openers refuse the same files without opening them.
    CHECK(bdl_open_regular(fifo, why, sizeof why) == NULL);
    size_t length = 0;
    CHECK(bdl_read_file("/dev/zero", &length) == NULL);
    char *text = bdl_read_file(file, &length);
    CHECK(text && length == 6 && strcmp(text, "x,y,z\n") == 0);
    free(text);
    unlink(fifo);
    unlink(file);
    rmdir(dir);
}

int main(void)
{
    test_arithmetic();
    test_grow();
    test_memory();
    test_regular();
    return bdl_test_summary("test_sizes");
}
