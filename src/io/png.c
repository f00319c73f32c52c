// bedlam — PNG writing with libpng's full API (for the compression settings) and reading with
// its simplified API.
#include "io/png.h"

#include <png.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>

#include "io/atomic_file.h"

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
