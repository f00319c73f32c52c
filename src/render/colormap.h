// bedlam — perceptually uniform colour maps, built in OKLab.
//
// The maps are generated, not tabulated from elsewhere: a path through OKLab (Ottosson 2020)
// with lightness linear in the mapped value, so equal steps in the value look like equal steps
// in colour. The sequential map runs dark violet -> blue -> teal -> green -> yellow (the look
// of viridis); the diverging map runs blue -> near-white -> red with the same lightness on both
// sides of the middle, for signed fields such as a velocity component. The cyclic map turns once
// round the hue circle at constant lightness and chroma, so its two ends are the same colour: for
// angles that wrap round (a rod's azimuth), and its hue reads the same under the lighting's
// shading.
#ifndef BDL_COLORMAP_H
#define BDL_COLORMAP_H

#include <stdint.h>

typedef enum bdl_colormap_kind {
    BDL_CMAP_SEQUENTIAL, ///< lightness 0.30 -> 0.93, for magnitudes (speed, voidage)
    BDL_CMAP_DIVERGING,  ///< blue -> white -> red, symmetric lightness, for signed values
    BDL_CMAP_CYCLIC,     ///< every hue at lightness 0.72 and chroma 0.11, for angles
    BDL_CMAP_KINDS
} bdl_colormap_kind;

#define BDL_COLORMAP_SIZE 256

/// The map sampled at BDL_COLORMAP_SIZE equally spaced values, as 8-bit sRGB (for a texture).
void bdl_colormap_table(bdl_colormap_kind kind, uint8_t rgb[BDL_COLORMAP_SIZE][3]);

/// The map at t in [0, 1] (clamped; NaN gives 0) as sRGB in [0, 1]: linear interpolation of the
/// table, so the CPU and a GPU texture lookup of the table agree.
void bdl_colormap_eval(bdl_colormap_kind kind, double t, float rgb[3]);

/// The colour of a particle that has no value of the field shown (a sphere's tilt): a neutral
/// grey (OKLab lightness 0.55, no chroma), which no map uses.
void bdl_colormap_missing(float rgb[3]);

/// A colour for category `index` (species): hues a golden angle apart at equal lightness, so
/// neighbouring indices differ strongly and no category stands out by brightness.
void bdl_category_color(int index, float rgb[3]);

/// OKLab coordinates (L, a, b) of an sRGB colour in [0, 1].
void bdl_oklab_from_srgb(const float rgb[3], float lab[3]);

/// sRGB in [0, 1] of OKLab (L, a, b); out-of-gamut values are returned unclamped.
void bdl_srgb_from_oklab(const float lab[3], float rgb[3]);

#endif
