// bedlam — PNG images through libpng: fast-compressed atomic writes and reads for tests/tools.
#ifndef BDL_PNG_H
#define BDL_PNG_H

#include <stdint.h>

#include "core/error.h"

/// Writes 8-bit RGB (channels 3) or RGBA (channels 4) pixels, rows packed, to `path`
/// atomically (a temporary file renamed into place). With `flip_y` the first row of `pixels`
/// becomes the bottom of the image (OpenGL's read-back order). zlib level 1 with the Sub
/// filter: a 1280x720 frame encodes in tens of milliseconds. BDL_ERR_IO on any failure;
/// the final path is then untouched.
bdl_result bdl_png_write(const char *path, const uint8_t *pixels, int width, int height,
                         int channels, int flip_y);

/// Reads any PNG as 8-bit RGB or RGBA (RGBA when the file has alpha). `*pixels` is malloc'ed,
/// rows top to bottom; free it with free(). BDL_ERR_IO when the file is missing or not a PNG.
bdl_result bdl_png_read(const char *path, uint8_t **pixels, int *width, int *height, int *channels);

#endif
