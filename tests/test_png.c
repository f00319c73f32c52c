// PNG files: exact round trips (RGB, RGBA, flipped rows), atomic failure, bad input.
#define _POSIX_C_SOURCE 200809L
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "io/png.h"

static uint8_t *pattern(int w, int h, int channels)
{
    uint8_t *p = malloc((size_t)w * h * channels);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c)
                p[((size_t)y * w + x) * channels + c] = (uint8_t)(x * 7 + y * 13 + c * 61 + x * y);
    return p;
}

static void round_trip(const char *folder, int channels, int flip)
{
    const int w = 97, h = 41; // odd sizes catch stride mistakes
    char path[256];
    snprintf(path, sizeof path, "%s/image_%d_%d.png", folder, channels, flip);
    uint8_t *src = pattern(w, h, channels);
    CHECK(bdl_png_write(path, src, w, h, channels, flip) == BDL_OK);
    uint8_t *back = NULL;
    int bw = 0, bh = 0, bc = 0;
    CHECK(bdl_png_read(path, &back, &bw, &bh, &bc) == BDL_OK);
    CHECK(bw == w && bh == h && bc == channels);
    if (back && bw == w && bh == h && bc == channels) {
        size_t stride = (size_t)w * channels;
        int rows_equal = 0;
        for (int y = 0; y < h; ++y) {
            int from = flip ? h - 1 - y : y;
            rows_equal += memcmp(back + y * stride, src + from * stride, stride) == 0;
        }
        CHECK_MSG(rows_equal == h, "%d of %d rows equal (channels %d, flip %d)", rows_equal, h,
                  channels, flip);
    }
    free(back);
    free(src);
}

int main(void)
{
    char folder[] = "/tmp/bedlam_test_png_XXXXXX";
    if (!mkdtemp(folder))
        return 1;
    for (int channels = 3; channels <= 4; ++channels)
        for (int flip = 0; flip <= 1; ++flip)
            round_trip(folder, channels, flip);

    // A smooth 1280x720 frame compresses well below its raw size at the fast setting.
    uint8_t *frame = malloc(1280 * 720 * 3);
    for (int i = 0; i < 1280 * 720; ++i) {
        frame[3 * i] = (uint8_t)(i % 1280 / 5);
        frame[3 * i + 1] = (uint8_t)(i / 1280 / 3);
        frame[3 * i + 2] = 40;
    }
    char path[256];
    snprintf(path, sizeof path, "%s/frame.png", folder);
    CHECK(bdl_png_write(path, frame, 1280, 720, 3, 0) == BDL_OK);
    struct stat info;
    CHECK(stat(path, &info) == 0 && info.st_size > 0 && info.st_size < 1280 * 720 * 3 / 10);
    free(frame);

    // Failures: a missing folder, bad arguments, a file that is not a PNG.
    uint8_t one[4] = {1, 2, 3, 4};
    CHECK(bdl_png_write("/nonexistent/folder/x.png", one, 1, 1, 3, 0) == BDL_ERR_IO);
    snprintf(path, sizeof path, "%s/bad.png", folder);
    CHECK(bdl_png_write(path, one, 1, 1, 2, 0) == BDL_ERR_IO);
    CHECK(bdl_png_write(path, one, 0, 1, 3, 0) == BDL_ERR_IO);
    CHECK(access(path, F_OK) != 0);
    FILE *f = fopen(path, "wb");
    fputs("not a png", f);
    fclose(f);
    uint8_t *pixels = (uint8_t *)1;
    int w, h, c;
    CHECK(bdl_png_read(path, &pixels, &w, &h, &c) == BDL_ERR_IO && pixels == NULL);
    CHECK(bdl_png_read("/nonexistent.png", &pixels, &w, &h, &c) == BDL_ERR_IO);

    char command[128];
    snprintf(command, sizeof command, "rm -rf '%s'", folder);
    if (system(command) != 0)
        fprintf(stderr, "could not remove %s\n", folder);
    return bdl_test_summary("test_png");
}
