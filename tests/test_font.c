// Text from a real font: glyph metrics, layout geometry, atlas coverage and UTF-8 handling.
// Skips (exit 77) when no font is installed.
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "check.h"
#include "render/font.h"

/// Sum of atlas coverage under a glyph quad.
static double coverage(const uint8_t *atlas, int w, int h, const bdl_glyph_quad *q)
{
    double sum = 0.0;
    for (int y = (int)lrintf(q->v0 * h); y < (int)lrintf(q->v1 * h); ++y)
        for (int x = (int)lrintf(q->u0 * w); x < (int)lrintf(q->u1 * w); ++x)
            sum += atlas[(size_t)y * w + x];
    return sum / 255.0;
}

int main(void)
{
    const char *path = bdl_font_default_path();
    if (!path) {
        printf("test_font: no font installed (fonts-dejavu-core); skipped\n");
        return 77;
    }
    const int px = 20;
    bdl_font *f = bdl_font_load(path, px);
    CHECK(f != NULL);
    if (!f)
        return bdl_test_summary("test_font");

    int w, h;
    const uint8_t *atlas = bdl_font_atlas(f, &w, &h);
    CHECK(w > 0 && h > 0 && h < 4096);

    // Vertical metrics of a 20 px font.
    CHECK(bdl_font_ascent(f) > 0.7f * px && bdl_font_ascent(f) <= 1.2f * px);
    CHECK(bdl_font_line_height(f) >= 1.0f * px && bdl_font_line_height(f) < 1.6f * px);

    // "H": one quad, standing on the baseline, cap height about 0.73 em, full coverage along
    // its stems.
    bdl_glyph_quad q[64];
    int n = bdl_font_layout(f, "H", 10.0f, 50.0f, q, 64);
    CHECK(n == 1);
    CHECK(fabsf(q[0].y1 - 50.0f) <= 1.0f);
    float cap = q[0].y1 - q[0].y0;
    CHECK_MSG(cap > 0.6f * px && cap < 0.85f * px, "cap height %g px", cap);
    CHECK(q[0].x0 >= 10.0f && q[0].x0 < 14.0f);
    CHECK(q[0].u0 >= 0.0f && q[0].u1 <= 1.0f && q[0].v0 >= 0.0f && q[0].v1 <= 1.0f);
    CHECK(q[0].u1 > q[0].u0 && q[0].v1 > q[0].v0);
    double ink_h = coverage(atlas, w, h, &q[0]);
    // Two stems and a bar, each about 2 px thick in a 20 px font: 30 to 80 px of ink.
    CHECK_MSG(ink_h > 30.0 && ink_h < 80.0, "ink of H %g", ink_h);

    // "g" descends below the baseline, "x" does not reach cap height.
    n = bdl_font_layout(f, "g", 0.0f, 50.0f, q, 64);
    CHECK(n == 1 && q[0].y1 > 52.0f);
    n = bdl_font_layout(f, "x", 0.0f, 50.0f, q, 64);
    CHECK(n == 1 && q[0].y1 - q[0].y0 < cap - 2.0f);

    // Spaces advance the pen but draw nothing; widths add up; wide letters are wider.
    n = bdl_font_layout(f, "a b", 0.0f, 50.0f, q, 64);
    CHECK(n == 2);
    CHECK(q[1].x0 > q[0].x1 + 0.2f * px);
    CHECK(bdl_font_text_width(f, "WWW") > bdl_font_text_width(f, "iii") * 2.0f);
    float ab = bdl_font_text_width(f, "AB"), a = bdl_font_text_width(f, "A"),
          b = bdl_font_text_width(f, "B");
    CHECK(fabsf(ab - (a + b)) <= 2.0f); // at most a kerning pair apart
    CHECK(bdl_font_text_width(f, "") == 0.0f);

    // Layout writes at most `max` quads.
    n = bdl_font_layout(f, "abcdef", 0.0f, 50.0f, q, 3);
    CHECK(n == 3);

    // UTF-8: degree sign and Greek letters are in the atlas; an unknown code point becomes '?'.
    n = bdl_font_layout(f, "90\xC2\xB0 \xCE\x93 \xCF\x86", 0.0f, 50.0f, q, 64);
    CHECK(n == 5);
    bdl_glyph_quad unknown, question;
    CHECK(bdl_font_layout(f, "\xE4\xB8\x80", 0.0f, 50.0f, &unknown, 1) == 1); // U+4E00
    CHECK(bdl_font_layout(f, "?", 0.0f, 50.0f, &question, 1) == 1);
    CHECK(memcmp(&unknown, &question, sizeof unknown) == 0);
    // A truncated sequence does not read past the end.
    CHECK(bdl_font_layout(f, "a\xCE", 0.0f, 50.0f, q, 64) == 2);

    bdl_font_destroy(f);
    CHECK(bdl_font_load("/nonexistent/font.ttf", px) == NULL);
    return bdl_test_summary("test_font");
}
