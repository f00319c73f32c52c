// bedlam — image analysis for DIA: thresholds, 2D solids fraction per image cell, the 2D-to-3D
// calibration fits, and particle detection in images (for checking PIV truth).
#ifndef BDL_DIA_ANALYSIS_H
#define BDL_DIA_ANALYSIS_H

#include "core/error.h"

/// Binary mask of particle pixels: 1 where the pixel belongs to a particle. `bright_particles`:
/// front-lit (particles above the threshold) or back-lit (below). `window` > 0 selects the
/// adaptive method: a pixel is compared with the mean of the (2 window + 1)^2 square around it
/// plus `offset` (bright) or minus it (dark), where that window is not uniform; elsewhere with
/// the global Otsu level. `window` = 0: the global Otsu level everywhere.
void bdl_dia_threshold(const double *img, int w, int h, int bright_particles, int window,
                       double offset, unsigned char *mask);

/// Fraction of particle pixels in each of nx x ny image cells (row by row from the top); a pixel
/// belongs to the cell its centre falls in.
void bdl_dia_cell_fractions(const unsigned char *mask, int w, int h, int nx, int ny,
                            double *fraction);

typedef enum bdl_dia_model {
    BDL_DIA_MODEL_RATIONAL = 0, ///< f3D = A f2D / (B - f2D)  (Mahajan 2019)
    BDL_DIA_MODEL_POWER,        ///< f3D = a f2D^b
    BDL_DIA_MODEL_COUNT
} bdl_dia_model;

extern const char *const bdl_dia_model_names[BDL_DIA_MODEL_COUNT];

typedef struct bdl_dia_fit {
    bdl_dia_model model;
    double p[2];    ///< A, B (rational) or a, b (power)
    double r2;      ///< coefficient of determination
    double rms;     ///< root-mean-square residual in f3D
    double max_abs; ///< largest |residual|
    long n;         ///< points used
    int converged;  ///< the least-squares iteration converged
} bdl_dia_fit;

/// Least-squares fit of f3D against f2D (n points). Rational: Levenberg-Marquardt from A = 0.05,
/// B just above the largest f2D; points need f2D < B. Power: least squares in log space first,
/// then refined on f3D.
bdl_dia_fit bdl_dia_fit_model(bdl_dia_model model, const double *f2d, const double *f3d, long n);
/// The fitted f3D at f2D, capped at `cap` (the rational model's pole is never reached: above the
/// f2D where the cap is reached the cap is returned).
double bdl_dia_fit_apply(const bdl_dia_fit *fit, double f2d, double cap);
/// The f2D at which the fit reaches f3D = cap (NAN when it never does on [0, 1]).
double bdl_dia_fit_cap_f2d(const bdl_dia_fit *fit, double cap);

/// A connected blob of particle pixels (4-connectivity) and its centroid [px].
typedef struct bdl_dia_blob {
    double u, v;
    long pixels;
} bdl_dia_blob;
/// Finds the blobs of a mask (at most `max` are returned; *count gets how many there are). With
/// `img`, centroids are weighted by the grey level's distance from the background (the mean of
/// the pixels outside the mask) over the blob grown by one pixel, which takes in the partly
/// covered edge pixels: sub-pixel accurate. Without, by pixel count.
bdl_result bdl_dia_blobs(const unsigned char *mask, const double *img, int w, int h,
                         bdl_dia_blob *blobs, long max, long *count);

#endif
