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

/// Reads any PNG as grey values in [0, 1], raw (no gamma conversion): 8- or 16-bit grey as
/// stored; colour images as the mean of red, green and blue; alpha ignored. `*values` is
/// malloc'ed, rows top to bottom; `*bits` gets the file's bit depth. BDL_ERR_IO on failure.
bdl_result bdl_png_read_gray(const char *path, double **values, int *width, int *height, int *bits);

#endif
