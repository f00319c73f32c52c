// bedlam — text from a real font: FreeType rasterises the glyphs once into a coverage atlas,
// and layout turns a UTF-8 string into textured quads in pixel coordinates (y down).
#ifndef BDL_FONT_H
#define BDL_FONT_H

#include <stdint.h>

typedef struct bdl_font bdl_font;

/// One glyph on screen: pixel rectangle (x0, y0)-(x1, y1), y down, and its atlas texture
/// coordinates (u, v in [0, 1], v = 0 at the atlas' first row).
typedef struct bdl_glyph_quad {
    float x0, y0, x1, y1;
    float u0, v0, u1, v1;
} bdl_glyph_quad;

/// The font to use: $BDL_FONT when set, otherwise DejaVu Sans (Debian's fonts-dejavu-core),
/// otherwise DejaVu Sans Mono; NULL when none of them is readable.
const char *bdl_font_default_path(void);

/// Loads a TrueType/OpenType font at `pixel_size` px and rasterises printable ASCII plus the
/// symbols bedlam prints (degree, superscripts, plus-minus, times, Greek letters used for
/// physical quantities). Returns NULL, with a warning logged, when the file cannot be read.
bdl_font *bdl_font_load(const char *path, int pixel_size);
void bdl_font_destroy(bdl_font *font);

/// The coverage atlas: one byte per texel (0 = empty, 255 = fully inside a glyph), row-major,
/// *width x *height, first row at v = 0.
const uint8_t *bdl_font_atlas(const bdl_font *font, int *width, int *height);

/// Lays out UTF-8 `text` on one line starting at pen position x with the baseline at y.
/// Writes at most `max` quads (spaces produce none) and returns how many were written.
/// Characters the atlas lacks are drawn as '?'.
int bdl_font_layout(const bdl_font *font, const char *text, float x, float y_baseline,
                    bdl_glyph_quad *out, int max);

/// The advance width of `text` in pixels, kerning included.
float bdl_font_text_width(const bdl_font *font, const char *text);

/// Distance between baselines of consecutive lines, in pixels.
float bdl_font_line_height(const bdl_font *font);

/// Height of the tallest glyphs above the baseline, in pixels.
float bdl_font_ascent(const bdl_font *font);

#endif
