// bedlam — FreeType glyph atlas and single-line text layout.
#include "render/font.h"

#include <ft2build.h>
#include FT_FREETYPE_H
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/log.h"

/// Code points beyond printable ASCII that bedlam's overlays use.
static const uint32_t extra_codepoints[] = {
    0x00B0, 0x00B1, 0x00B2, 0x00B3, 0x00B5, 0x00B7, 0x00D7, 0x0393, 0x0394, 0x03B1, 0x03B5,
    0x03B8, 0x03BC, 0x03BD, 0x03C1, 0x03C6, 0x03C9, 0x2013, 0x2014, 0x2026, 0x2192,
};

enum { ASCII_FIRST = 32, ASCII_LAST = 126, ATLAS_WIDTH = 512, PAD = 1 };

typedef struct glyph {
    uint32_t codepoint;
    unsigned index;       ///< FreeType glyph index, for kerning
    int width, height;    ///< bitmap size in pixels
    int left, top;        ///< bitmap offset from the pen: right, and up from the baseline
    int atlas_x, atlas_y; ///< bitmap position in the atlas
    float advance;        ///< pen advance in pixels
} glyph;

struct bdl_font {
    FT_Library library;
    FT_Face face;
    int has_kerning;
    int glyph_count;
    glyph
        glyphs[ASCII_LAST - ASCII_FIRST + 1 + sizeof extra_codepoints / sizeof extra_codepoints[0]];
    uint8_t *atlas;
    int atlas_width, atlas_height;
    float line_height, ascent;
};

const char *bdl_font_default_path(void)
{
    const char *env = getenv("BDL_FONT");
    if (env && *env && access(env, R_OK) == 0)
        return env;
    static const char *const candidates[] = {
        "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
        "/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf",
    };
    for (size_t k = 0; k < sizeof candidates / sizeof candidates[0]; ++k)
        if (access(candidates[k], R_OK) == 0)
            return candidates[k];
    return NULL;
}

static uint32_t codepoint_at(int k)
{
    int ascii = ASCII_LAST - ASCII_FIRST + 1;
    return k < ascii ? (uint32_t)(ASCII_FIRST + k) : extra_codepoints[k - ascii];
}

/// Measures every glyph and places it on shelves of the atlas; returns the atlas height.
static int place_glyphs(bdl_font *f)
{
    int x = 0, y = 0, shelf = 0;
    for (int k = 0; k < f->glyph_count; ++k) {
        glyph *g = &f->glyphs[k];
        g->codepoint = codepoint_at(k);
        g->index = FT_Get_Char_Index(f->face, g->codepoint);
        if (FT_Load_Glyph(f->face, g->index, FT_LOAD_DEFAULT) != 0)
            continue; // left empty: zero size, zero advance
        FT_GlyphSlot slot = f->face->glyph;
        g->width = (int)slot->metrics.width / 64 + 2; // rendering may spill a pixel either side
        g->height = (int)slot->metrics.height / 64 + 2;
        g->advance = (float)slot->advance.x / 64.0f;
        if (x + g->width + PAD > ATLAS_WIDTH) {
            x = 0;
            y += shelf + PAD;
            shelf = 0;
        }
        g->atlas_x = x;
        g->atlas_y = y;
        x += g->width + PAD;
        shelf = g->height > shelf ? g->height : shelf;
    }
    return y + shelf;
}

/// Renders each glyph into its reserved place; the final size replaces the estimate.
static void render_glyphs(bdl_font *f)
{
    for (int k = 0; k < f->glyph_count; ++k) {
        glyph *g = &f->glyphs[k];
        int reserved_w = g->width, reserved_h = g->height;
        g->width = g->height = 0;
        if (FT_Load_Glyph(f->face, g->index, FT_LOAD_RENDER) != 0)
            continue;
        FT_GlyphSlot slot = f->face->glyph;
        const FT_Bitmap *bm = &slot->bitmap;
        int w = (int)bm->width < reserved_w ? (int)bm->width : reserved_w;
        int h = (int)bm->rows < reserved_h ? (int)bm->rows : reserved_h;
        for (int row = 0; row < h; ++row)
            memcpy(f->atlas + (size_t)(g->atlas_y + row) * ATLAS_WIDTH + g->atlas_x,
                   bm->buffer + (ptrdiff_t)row * bm->pitch, (size_t)w);
        g->width = w;
        g->height = h;
        g->left = slot->bitmap_left;
        g->top = slot->bitmap_top;
    }
}

bdl_font *bdl_font_load(const char *path, int pixel_size)
{
    bdl_font *f = calloc(1, sizeof *f);
    if (!f)
        return NULL;
    if (FT_Init_FreeType(&f->library) != 0) {
        free(f);
        return NULL;
    }
    if (!path || FT_New_Face(f->library, path, 0, &f->face) != 0 ||
        FT_Set_Pixel_Sizes(f->face, 0, (FT_UInt)pixel_size) != 0) {
        bdl_warn("font: cannot load '%s'; text overlays are left out", path ? path : "");
        if (f->face)
            FT_Done_Face(f->face);
        FT_Done_FreeType(f->library);
        free(f);
        return NULL;
    }
    f->has_kerning = FT_HAS_KERNING(f->face) ? 1 : 0;
    f->glyph_count = (int)(sizeof f->glyphs / sizeof f->glyphs[0]);
    f->atlas_width = ATLAS_WIDTH;
    f->atlas_height = place_glyphs(f);
    f->atlas = calloc((size_t)f->atlas_width * (size_t)f->atlas_height, 1);
    if (!f->atlas) {
        bdl_font_destroy(f);
        return NULL;
    }
    render_glyphs(f);
    f->line_height = (float)f->face->size->metrics.height / 64.0f;
    f->ascent = (float)f->face->size->metrics.ascender / 64.0f;
    return f;
}

void bdl_font_destroy(bdl_font *font)
{
    if (!font)
        return;
    free(font->atlas);
    if (font->face)
        FT_Done_Face(font->face);
    FT_Done_FreeType(font->library);
    free(font);
}

const uint8_t *bdl_font_atlas(const bdl_font *font, int *width, int *height)
{
    *width = font->atlas_width;
    *height = font->atlas_height;
    return font->atlas;
}

/// Decodes one UTF-8 sequence at *s and advances past it; malformed bytes give U+FFFD.
static uint32_t next_codepoint(const char **s)
{
    const unsigned char *p = (const unsigned char *)*s;
    uint32_t c = p[0];
    int extra = c < 0x80             ? 0
                : (c & 0xE0) == 0xC0 ? 1
                : (c & 0xF0) == 0xE0 ? 2
                : (c & 0xF8) == 0xF0 ? 3
                                     : -1;
    if (extra < 0) {
        *s += 1;
        return 0xFFFD;
    }
    if (extra > 0)
        c &= 0x3Fu >> extra;
    for (int k = 1; k <= extra; ++k) {
        if ((p[k] & 0xC0) != 0x80) {
            *s += k;
            return 0xFFFD;
        }
        c = (c << 6) | (p[k] & 0x3Fu);
    }
    *s += 1 + extra;
    return c;
}

static const glyph *find_glyph(const bdl_font *f, uint32_t c)
{
    if (c >= ASCII_FIRST && c <= ASCII_LAST)
        return &f->glyphs[c - ASCII_FIRST];
    for (int k = ASCII_LAST - ASCII_FIRST + 1; k < f->glyph_count; ++k)
        if (f->glyphs[k].codepoint == c)
            return &f->glyphs[k];
    return &f->glyphs['?' - ASCII_FIRST];
}

static float kerning(const bdl_font *f, const glyph *prev, const glyph *g)
{
    if (!f->has_kerning || !prev)
        return 0.0f;
    FT_Vector k;
    if (FT_Get_Kerning(f->face, prev->index, g->index, FT_KERNING_DEFAULT, &k) != 0)
        return 0.0f;
    return (float)k.x / 64.0f;
}

int bdl_font_layout(const bdl_font *font, const char *text, float x, float y_baseline,
                    bdl_glyph_quad *out, int max)
{
    int n = 0;
    const glyph *prev = NULL;
    const float iw = 1.0f / (float)font->atlas_width, ih = 1.0f / (float)font->atlas_height;
    while (*text) {
        const glyph *g = find_glyph(font, next_codepoint(&text));
        x += kerning(font, prev, g);
        if (g->width > 0 && g->height > 0 && n < max) {
            bdl_glyph_quad *q = &out[n++];
            q->x0 = x + (float)g->left;
            q->y0 = y_baseline - (float)g->top;
            q->x1 = q->x0 + (float)g->width;
            q->y1 = q->y0 + (float)g->height;
            q->u0 = (float)g->atlas_x * iw;
            q->v0 = (float)g->atlas_y * ih;
            q->u1 = (float)(g->atlas_x + g->width) * iw;
            q->v1 = (float)(g->atlas_y + g->height) * ih;
        }
        x += g->advance;
        prev = g;
    }
    return n;
}

float bdl_font_text_width(const bdl_font *font, const char *text)
{
    float x = 0.0f;
    const glyph *prev = NULL;
    while (*text) {
        const glyph *g = find_glyph(font, next_codepoint(&text));
        x += kerning(font, prev, g) + g->advance;
        prev = g;
    }
    return x;
}

float bdl_font_line_height(const bdl_font *font) { return font->line_height; }

float bdl_font_ascent(const bdl_font *font) { return font->ascent; }
