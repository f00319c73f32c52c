// bedlam — bed height as the level of the steepest row-averaged gradient (Mahajan 2019, ch. 2):
// no threshold, the same definition for a camera image and for a simulated density field.
#ifndef BDL_DIA_BED_HEIGHT_H
#define BDL_DIA_BED_HEIGHT_H

/// Which way the profile steps at the bed's surface, read from the top row down.
typedef enum bdl_dia_polarity {
    BDL_DIA_RISES_INTO_BED = 1,  ///< front-lit images, particle density or solids fraction
    BDL_DIA_FALLS_INTO_BED = -1, ///< back-lit images (dark silhouettes on a light panel)
    BDL_DIA_EITHER_WAY = 0       ///< the largest |gradient|
} bdl_dia_polarity;

/// Mean of each row of a w x h field (row 0 at the top).
void bdl_dia_row_means(const double *field, int w, int h, double *profile);

/// The level of the steepest step of a profile of n rows (row 0 at the top): the profile is
/// smoothed by a Gaussian of `smooth` rows (0: not smoothed), differenced between adjacent rows
/// (the difference of rows k and k + 1 belongs to their shared edge, level k + 1), and the
/// largest difference in the direction `polarity` is refined by a parabola through it and its
/// two neighbours. Returns the level in rows from the top edge (row k spans [k, k + 1)), or NAN
/// when n < 3 or the profile has no step that way.
double bdl_dia_profile_step(const double *profile, int n, double smooth, bdl_dia_polarity polarity);

/// Bed surface in an image (w x h grey values, row 0 at the top): bdl_dia_row_means then
/// bdl_dia_profile_step. In pixels from the top edge; the bed height above the image's bottom
/// edge is h minus it. NAN when w or h is 0 or there is no step.
double bdl_dia_bed_level_image(const double *img, int w, int h, double smooth,
                               bdl_dia_polarity polarity);

/// The same definition on a field of particle density or solids fraction given as ny rows of nx
/// cells from the top (rises into the bed): in cells from the top edge. Putting the simulation
/// through this and the camera's images through bdl_dia_bed_level_image measures both the
/// same way.
double bdl_dia_bed_level_field(const double *field, int nx, int ny, double smooth);

#endif
