// bedlam — colour maps generated along paths in OKLab.
#include "render/colormap.h"

#include <math.h>
#include <pthread.h>

#include "core/vec3.h"

static double srgb_to_linear(double c)
{
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

static double linear_to_srgb(double c)
{
    return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}

/// OKLab -> linear sRGB (Ottosson's matrices).
static void linear_from_oklab(const double lab[3], double rgb[3])
{
    double l = lab[0] + 0.3963377774 * lab[1] + 0.2158037573 * lab[2];
    double m = lab[0] - 0.1055613458 * lab[1] - 0.0638541728 * lab[2];
    double s = lab[0] - 0.0894841775 * lab[1] - 1.2914855480 * lab[2];
    l = l * l * l;
    m = m * m * m;
    s = s * s * s;
    rgb[0] = 4.0767416621 * l - 3.3077115913 * m + 0.2309699292 * s;
    rgb[1] = -1.2684380046 * l + 2.6097574011 * m - 0.3413193965 * s;
    rgb[2] = -0.0041960863 * l - 0.7034186147 * m + 1.7076147010 * s;
}

void bdl_oklab_from_srgb(const float rgb[3], float lab[3])
{
    double r = srgb_to_linear(rgb[0]), g = srgb_to_linear(rgb[1]), b = srgb_to_linear(rgb[2]);
    double l = cbrt(0.4122214708 * r + 0.5363325363 * g + 0.0514459929 * b);
    double m = cbrt(0.2119034982 * r + 0.6806995451 * g + 0.1073969566 * b);
    double s = cbrt(0.0883024619 * r + 0.2817188376 * g + 0.6299787005 * b);
    lab[0] = (float)(0.2104542553 * l + 0.7936177850 * m - 0.0040720468 * s);
    lab[1] = (float)(1.9779984951 * l - 2.4285922050 * m + 0.4505937099 * s);
    lab[2] = (float)(0.0259040371 * l + 0.7827717662 * m - 0.8086757660 * s);
}

void bdl_srgb_from_oklab(const float lab[3], float rgb[3])
{
    double in[3] = {lab[0], lab[1], lab[2]}, lin[3];
    linear_from_oklab(in, lin);
    for (int k = 0; k < 3; ++k)
        rgb[k] = (float)(lin[k] < 0.0 ? -linear_to_srgb(-lin[k]) : linear_to_srgb(lin[k]));
}

static int in_gamut(double L, double chroma, double hue)
{
    double lab[3] = {L, chroma * cos(hue), chroma * sin(hue)}, lin[3];
    linear_from_oklab(lab, lin);
    const double eps = 1e-9;
    return lin[0] >= -eps && lin[0] <= 1.0 + eps && lin[1] >= -eps && lin[1] <= 1.0 + eps &&
           lin[2] >= -eps && lin[2] <= 1.0 + eps;
}

/// The largest chroma at lightness L and hue (radians) that sRGB can show, by bisection.
static double max_chroma(double L, double hue)
{
    double lo = 0.0, hi = 0.5;
    for (int it = 0; it < 40; ++it) {
        double mid = 0.5 * (lo + hi);
        if (in_gamut(L, mid, hue))
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/// sRGB of the colour at (L, chroma, hue in degrees), chroma reduced to stay inside the gamut.
static void lch_color(double L, double chroma, double hue_deg, float rgb[3])
{
    double hue = hue_deg * BDL_PI / 180.0;
    double c = fmin(chroma, 0.97 * max_chroma(L, hue));
    double lab[3] = {L, c * cos(hue), c * sin(hue)}, lin[3];
    linear_from_oklab(lab, lin);
    for (int k = 0; k < 3; ++k)
        rgb[k] = (float)linear_to_srgb(fmin(fmax(lin[k], 0.0), 1.0));
}

static void sequential(double t, float rgb[3])
{
    // Lightness linear in t; hue turns from violet (280 deg) through teal to yellow (100 deg).
    lch_color(0.30 + 0.63 * t, 0.13, 280.0 - 180.0 * t, rgb);
}

static void diverging(double t, float rgb[3])
{
    double u = 2.0 * t - 1.0, a = fabs(u);
    lch_color(0.95 - 0.47 * a, 0.16 * a, u < 0.0 ? 255.0 : 30.0, rgb);
}

static void cyclic(double t, float rgb[3])
{
    // Chroma 0.11 is inside the sRGB gamut at every hue at this lightness (the least is 0.122,
    // at hue 200 deg), so the circle is not flattened anywhere.
    lch_color(0.72, 0.11, fmod(30.0 + 360.0 * t, 360.0), rgb);
}

static float tables[BDL_CMAP_KINDS][BDL_COLORMAP_SIZE][3];
static pthread_once_t tables_once = PTHREAD_ONCE_INIT;

static void build_tables(void)
{
    for (int i = 0; i < BDL_COLORMAP_SIZE; ++i) {
        double t = (double)i / (BDL_COLORMAP_SIZE - 1);
        sequential(t, tables[BDL_CMAP_SEQUENTIAL][i]);
        diverging(t, tables[BDL_CMAP_DIVERGING][i]);
        cyclic(t, tables[BDL_CMAP_CYCLIC][i]);
    }
}

void bdl_colormap_table(bdl_colormap_kind kind, uint8_t rgb[BDL_COLORMAP_SIZE][3])
{
    pthread_once(&tables_once, build_tables);
    for (int i = 0; i < BDL_COLORMAP_SIZE; ++i)
        for (int k = 0; k < 3; ++k)
            rgb[i][k] = (uint8_t)lrintf(255.0f * tables[kind][i][k]);
}

void bdl_colormap_eval(bdl_colormap_kind kind, double t, float rgb[3])
{
    pthread_once(&tables_once, build_tables);
    if (!(t > 0.0))
        t = 0.0;
    if (t > 1.0)
        t = 1.0;
    double x = t * (BDL_COLORMAP_SIZE - 1);
    int i = (int)x;
    if (i > BDL_COLORMAP_SIZE - 2)
        i = BDL_COLORMAP_SIZE - 2;
    float f = (float)(x - i);
    for (int k = 0; k < 3; ++k)
        rgb[k] = tables[kind][i][k] + f * (tables[kind][i + 1][k] - tables[kind][i][k]);
}

void bdl_colormap_missing(float rgb[3]) { lch_color(0.55, 0.0, 0.0, rgb); }

void bdl_category_color(int index, float rgb[3])
{
    if (index < 0)
        index = -index;
    // Golden-angle hue steps: any few consecutive categories are far apart on the hue circle.
    lch_color(0.70, 0.13, fmod(30.0 + 137.50776 * index, 360.0), rgb);
}
