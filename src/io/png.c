// bedlam — PNG writing with libpng's full API (for the compression settings) and reading with
// its simplified API.
#include "io/png.h"

#include <png.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>

#include "core/file.h"

/// Encodes into an open stream. Everything libpng touches after setjmp is either volatile or
/// set before it, so a longjmp back here is well defined.
static int encode(FILE *file, const uint8_t *pixels, int width, int height, int channels,
                  int flip_y)
{
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    if (!png)
        return 0;
    png_infop info = png_create_info_struct(png);
    if (!info) {
        png_destroy_write_struct(&png, NULL);
        return 0;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return 0;
    }
    png_init_io(png, file);
    png_set_compression_level(png, 1);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
    png_set_IHDR(png, info, (png_uint_32)width, (png_uint_32)height, 8,
                 channels == 4 ? PNG_COLOR_TYPE_RGBA : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_BASE, PNG_FILTER_TYPE_BASE);
    png_write_info(png, info);
    const size_t stride = (size_t)width * (size_t)channels;
    for (int y = 0; y < height; ++y) {
        int row = flip_y ? height - 1 - y : y;
        png_write_row(png, (png_const_bytep)(pixels + (size_t)row * stride));
    }
    png_write_end(png, NULL);
    png_destroy_write_struct(&png, &info);
    return 1;
}

bdl_result bdl_png_write(const char *path, const uint8_t *pixels, int width, int height,
                         int channels, int flip_y)
{
    if (!pixels || width <= 0 || height <= 0 || (channels != 3 && channels != 4))
        return BDL_ERR_IO;
    bdl_atomic_file af;
    if (bdl_atomic_open(&af, path) != BDL_OK)
        return BDL_ERR_IO;
    if (!encode(af.file, pixels, width, height, channels, flip_y)) {
        bdl_atomic_abort(&af);
        return BDL_ERR_IO;
    }
    return bdl_atomic_commit(&af);
}

bdl_result bdl_png_read(const char *path, uint8_t **pixels, int *width, int *height, int *channels)
{
    png_image image;
    memset(&image, 0, sizeof image);
    image.version = PNG_IMAGE_VERSION;
    *pixels = NULL;
    if (!png_image_begin_read_from_file(&image, path))
        return BDL_ERR_IO;
    int alpha = (image.format & PNG_FORMAT_FLAG_ALPHA) != 0;
    image.format = alpha ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB;
    uint8_t *buffer = malloc(PNG_IMAGE_SIZE(image));
    if (!buffer) {
        png_image_free(&image);
        return BDL_ERR_NOMEM;
    }
    if (!png_image_finish_read(&image, NULL, buffer, 0, NULL)) {
        free(buffer);
        png_image_free(&image);
        return BDL_ERR_IO;
    }
    *pixels = buffer;
    *width = (int)image.width;
    *height = (int)image.height;
    *channels = alpha ? 4 : 3;
    return BDL_OK;
}

/// Buffers of a grey read, in memory so that a longjmp from libpng finds them (locals assigned
/// after setjmp would be indeterminate).
typedef struct gray_read {
    png_bytep *rows;
    png_bytep data;
    double *out;
} gray_read;

bdl_result bdl_png_read_gray(const char *path, double **values, int *width, int *height, int *bits)
{
    *values = NULL;
    char why[256];
    FILE *f = bdl_open_regular(path, why, sizeof why);
    gray_read *g = calloc(1, sizeof *g);
    png_structp png =
        f && g ? png_create_read_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL) : NULL;
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!png || !info || setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, NULL);
        if (g) {
            free(g->rows);
            free(g->data);
            free(g->out);
        }
        free(g);
        if (f)
            fclose(f);
        return BDL_ERR_IO;
    }
    png_init_io(png, f);
    png_read_info(png, info);
    int color = png_get_color_type(png, info), depth = png_get_bit_depth(png, info);
    if (color == PNG_COLOR_TYPE_PALETTE)
        png_set_palette_to_rgb(png);
    if (color == PNG_COLOR_TYPE_GRAY && depth < 8)
        png_set_expand_gray_1_2_4_to_8(png);
    if (color & PNG_COLOR_MASK_ALPHA)
        png_set_strip_alpha(png);
    png_read_update_info(png, info);
    const int w = (int)png_get_image_width(png, info), h = (int)png_get_image_height(png, info);
    const int channels = png_get_channels(png, info), d = png_get_bit_depth(png, info);
    const size_t rowbytes = png_get_rowbytes(png, info);
    g->rows = malloc((size_t)h * sizeof(png_bytep));
    g->out = malloc((size_t)w * (size_t)h * sizeof(double));
    g->data = malloc(rowbytes * (size_t)h);
    if (!g->rows || !g->out || !g->data)
        png_longjmp(png, 1);
    for (int y = 0; y < h; ++y)
        g->rows[y] = g->data + (size_t)y * rowbytes;
    png_read_image(png, g->rows);
    const double full = d == 16 ? 65535.0 : 255.0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double sum = 0.0;
            for (int c = 0; c < channels; ++c) {
                size_t k = (size_t)x * channels + c;
                sum += d == 16 ? (double)((g->rows[y][2 * k] << 8) | g->rows[y][2 * k + 1])
                               : (double)g->rows[y][k];
            }
            g->out[(size_t)y * w + x] = sum / (channels * full);
        }
    *values = g->out;
    *width = w, *height = h, *bits = depth;
    free(g->data);
    free(g->rows);
    free(g);
    png_destroy_read_struct(&png, &info, NULL);
    fclose(f);
    return BDL_OK;
}
