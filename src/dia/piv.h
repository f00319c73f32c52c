// bedlam — particle image velocimetry by multi-pass FFT cross-correlation with window offset
// (Mahajan 2019, ch. 2: one pass of 256 px windows at 50 % overlap, then three of 128 px at
// 75 %), and the solids mass flux per cell from a voidage field and a velocity field.
#ifndef BDL_DIA_PIV_H
#define BDL_DIA_PIV_H

#include "core/error.h"

#define BDL_DIA_PIV_MAX_PASSES 8

typedef struct bdl_dia_piv_pass {
    int window;     ///< interrogation window's side [px] (>= 8)
    double overlap; ///< overlap of neighbouring windows, in [0, 1): the stride is window (1 - it)
} bdl_dia_piv_pass;

typedef struct bdl_dia_piv_def {
    int passes;                                    ///< 1 .. BDL_DIA_PIV_MAX_PASSES
    bdl_dia_piv_pass pass[BDL_DIA_PIV_MAX_PASSES]; ///< in order; each offsets by the one before
    double median_threshold; ///< normalised median test after each pass (Westerweel and Scarano
                             ///< 2005: residual over the neighbours' median residual + 0.1 px):
                             ///< before the last pass, vectors above it are replaced by their
                             ///< neighbours' median; on the last, flagged; 0 off
} bdl_dia_piv_def;

/// Defaults: 256 px at 50 %, then three passes of 128 px at 75 %; median test at 2.
bdl_dia_piv_def bdl_default_piv_def(void);

/// A PIV evaluator for images of one size: FFTW plans for each window size, made once at
/// creation and reused for every window of every image pair. Plans are made in
/// bdl_dia_piv_create, and FFTW's planner is not thread-safe: create (and destroy) evaluators
/// from one thread at a time. One evaluator runs one pair at a time.
typedef struct bdl_dia_piv bdl_dia_piv;

/// BDL_ERR_ARGS when a window is smaller than 8 px or larger than the image, or an overlap is
/// outside [0, 1), or passes is outside 1 .. BDL_DIA_PIV_MAX_PASSES.
bdl_result bdl_dia_piv_create(const bdl_dia_piv_def *def, int width, int height, bdl_dia_piv **piv);
void bdl_dia_piv_destroy(bdl_dia_piv *piv);

/// The last pass's vectors, nx x ny row by row from the top; valid until the next run or the
/// evaluator's destruction.
typedef struct bdl_dia_piv_field {
    int nx, ny;
    const double *u, *v;   ///< window centres [px] (pixel (i, j)'s centre is (i + 0.5, j + 0.5))
    const double *du, *dv; ///< displacement from the first image to the second [px]
    const double *peak;    ///< correlation coefficient at the peak, in [-1, 1]
    const unsigned char *outlier; ///< 1 where the median test flags the (unchanged) vector
} bdl_dia_piv_field;

/// Cross-correlates images a and b (width x height grey values, row 0 at the top). Each pass
/// tiles the image with its windows (centred: the margins left over are split evenly); from the
/// second pass on, the window in b is shifted by the previous pass's displacement at the
/// window's centre (bilinear between that pass's vectors, rounded to whole pixels), so the
/// correlation peak measures only the rest. The peak's position is refined by a three-point
/// Gaussian fit in each direction (a parabola where a neighbour is not positive). A vector is
/// placed at its window's centre in a.
bdl_result bdl_dia_piv_run(bdl_dia_piv *piv, const double *a, const double *b,
                           bdl_dia_piv_field *field);

/// Solids mass flux per cell, flux = density (1 - voidage) velocity (Mahajan 2019, eq. 2.6), for
/// n cells: voidage [-], velocity components in any unit, density [kg/m^3]; the flux is in
/// kg/m^3 times the velocity's unit (kg/(m^2 s) for m/s).
void bdl_dia_mass_flux(const double *voidage, const double *vel_u, const double *vel_v, long n,
                       double density, double *flux_u, double *flux_v);

#endif
