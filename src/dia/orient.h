// bedlam — orientation of rods lying parallel to the front wall, from an image (Mahajan 2019,
// ch. 2): adaptive threshold, blobs labelled and kept by area, and each blob's angle as the one
// of largest aspect ratio over rotated axes; and the coalignment of the detected rods.
//
// Angles are in degrees in the image, 0 = upright (the rod's axis along the image's vertical), +90
// = horizontal, positive when the rod's upper end leans to the right (clockwise from up as the
// image is seen), in (-90, 90]. This is the convention of the thesis's orientation PDFs (0°
// standing, ±90° lying). The angle from the image's +x axis, counter-clockwise with y up, is 90°
// minus it.
#ifndef BDL_DIA_ORIENT_H
#define BDL_DIA_ORIENT_H

#include <stdint.h>

#include "core/error.h"

/// Labels the 4-connected blobs of a mask: label[k] = 1..count for particle pixels (in the order
/// their first pixel is met, row by row from the top), 0 for background.
bdl_result bdl_dia_label(const unsigned char *mask, int w, int h, int32_t *label, long *count);

/// How a blob's angle is found.
typedef enum bdl_dia_angle_method {
    BDL_DIA_ANGLE_ASPECT = 0, ///< the thesis's: largest aspect ratio over rotated axes
    BDL_DIA_ANGLE_MOMENTS     ///< the principal axis of the pixels' second moments
} bdl_dia_angle_method;

typedef struct bdl_dia_orient_def {
    int bright_particles; ///< front-lit (1) or back-lit (0)
    int window;           ///< adaptive threshold's half window [px] (dia/analysis.h); 0: Otsu
    double offset;        ///< adaptive threshold's offset, grey levels in [0, 1]
    long min_area;        ///< blobs of fewer pixels are dropped (noise, rods seen end-on) [px]
    long max_area;        ///< blobs of more pixels are dropped (touching rods) [px]
    double min_aspect;    ///< blobs less elongated than this are dropped (rods not in the wall's
                          ///< plane, fragments); 1: none
    double step;          ///< angle step of the rotated axes [deg]
    bdl_dia_angle_method method; ///< the angle of largest aspect ratio (the thesis's method),
                                 ///< or the principal axis; the aspect is taken at that angle
} bdl_dia_orient_def;

/// Defaults: front-lit, window 15 px, offset 0.05, areas 20 to 10^5 px, min_aspect 1, step 0.5°,
/// the thesis's method.
bdl_dia_orient_def bdl_default_orient_def(void);

/// A detected rod.
typedef struct bdl_dia_rod {
    double u, v;   ///< centroid of its pixels [px] (pixel (i, j)'s centre is (i + 0.5, j + 0.5))
    double angle;  ///< [deg], 0 upright, +-90 horizontal, positive leaning right (above)
    long area;     ///< pixels
    double aspect; ///< extent along / extent across at that angle
    double length; ///< extent along the axis [px] (pixel footprints included)
    double width;  ///< extent across [px]
} bdl_dia_rod;

/// Measures one set of pixels (centres (x + 0.5, y + 0.5) of the n pixels xs, ys): rotates the
/// axes through 180° in steps of `step` degrees, and at each angle takes the extents of the
/// pixels along and across (each pixel counted with its square's footprint on the axis); the
/// angle is the one of the largest ratio, refined by a parabola through it and its neighbours.
bdl_dia_rod bdl_dia_measure_rod(const int *xs, const int *ys, long n, double step);

/// The angle of the principal axis of n pixels (the eigenvector of the larger eigenvalue of their
/// coordinates' covariance), in the convention above.
double bdl_dia_principal_angle(const int *xs, const int *ys, long n);

/// Threshold (bdl_dia_threshold), label, keep blobs with min_area <= area <= max_area and
/// aspect >= min_aspect, measure them. At most `max` rods are written; *count gets how many
/// passed.
bdl_result bdl_dia_detect_rods(const double *img, int w, int h, const bdl_dia_orient_def *def,
                               bdl_dia_rod *rods, long max, long *count);

/// Coalignment C(r) = 2 <cos^2(alpha_i - alpha_j)> - 1 (Mahajan 2019, eq. 2.5) of rods at (u, v)
/// with angles in degrees, in `bins` bins of centre distance r over [0, r_max): c[b] gets the
/// mean over the ordered pairs (i, j), i != j, whose reference rod i lies in x_min <= u_i < x_max
/// (a zone by wall distance; -INFINITY, INFINITY for all), its partner anywhere; pairs[b] the
/// number of them; r_mean[b] (may be NULL) their mean distance (c[b], r_mean[b] = NAN when no
/// pair). Sums run in a fixed order. BDL_ERR_ARGS when r_max <= 0 or bins < 1.
bdl_result bdl_dia_coalignment(const double *u, const double *v, const double *angle, long n,
                               double r_max, int bins, double x_min, double x_max, double *c,
                               long *pairs, double *r_mean);

/// Fit of C(r) ~ amplitude exp(-r / xi) to the bins whose distance r[b] (bdl_dia_coalignment's
/// r_mean, or the bins' centres) is at or beyond r_min and whose C is positive: least squares of
/// ln C against r, each bin weighted by pairs C^2 (the inverse of the variance of its ln C when
/// its C is a mean over that many pairs). With `fix_amplitude` the amplitude is 1 and only xi is
/// fitted. Returns xi (in r's units; NAN with fewer than two usable bins, or none with
/// fix_amplitude, or when C does not decay) and the amplitude in *amplitude (may be NULL).
double bdl_dia_coalignment_fit(const double *r, const double *c, const long *pairs, int bins,
                               double r_min, int fix_amplitude, double *amplitude);

#endif
