// bedlam — the rods' angles as a camera at the front wall of a pseudo-2D bed sees them (Mahajan
// 2019, ch. 2 and 4): the histogram of the in-plane angle near the front and back walls and in
// the bulk, and its average over rows of a time series into a PDF.
//
// The camera looks along +y at the x-z plane with z up, so +x is to its right. A rod's axis u is
// projected onto that plane and its angle measured from the vertical,
//
//     theta = atan2(u_x, u_z)  folded into (-90°, 90°]  (an axis is a line: u and -u are one rod),
//
// 0° upright, ±90° lying, positive when the upper end leans to +x: the convention of the
// thesis's orientation PDFs and of the synthetic camera's measurement (dia/orient.h). An axis
// along y projects to a point; its angle is taken as 0°. For axes spread evenly over all
// directions theta is uniform over (-90°, 90°] (the projection is symmetric about y).
//
// Near-wall rods have their centre within one rod length L_p = 2 (half_length + radius) of the
// front or back wall (the y extremes); the others are the bulk. Counts are integers and the sums
// run in index order, so the histogram does not depend on the thread count.
#ifndef BDL_ROD_ANGLES_H
#define BDL_ROD_ANGLES_H

#include "core/vec3.h"

/// Bins of the in-plane angle over [-90°, 90°] in orientation.csv (5° each).
#define BDL_ROD_ANGLE_BINS 36

/// The zones of the histogram.
enum { BDL_ROD_ZONE_WALL = 0, BDL_ROD_ZONE_BULK = 1, BDL_ROD_ZONES = 2 };

/// The in-plane angle theta of axis u [deg] in (-90, 90] (above).
double bdl_rod_plane_angle(bdl_vec3 u);

/// The bin of angle a [deg] among `bins` equal bins over [-90, 90]: floor((a + 90) / width),
/// 90° itself in the last bin.
int bdl_rod_angle_bin(double a, int bins);

/// The rods of a state, borrowed: particles with half_length 0 (spheres) are left out.
typedef struct bdl_rod_set {
    long count;
    const bdl_vec3 *pos;          ///< centres [m]
    const bdl_vec3 *axis;         ///< unit axes
    const double *half_length;    ///< half the shaft [m]
    const double *radius;         ///< [m]
    double wall_front, wall_back; ///< y of the front and back walls [m]
} bdl_rod_set;

/// One instant's histogram per zone.
typedef struct bdl_rod_histogram {
    long count[BDL_ROD_ZONES][BDL_ROD_ANGLE_BINS]; ///< rods per bin of the in-plane angle
    long rods[BDL_ROD_ZONES];                      ///< rods in the zone
    double abs_cos[BDL_ROD_ZONES]; ///< mean |u_z|: |cos| of the 3D angle to the vertical; NAN
                                   ///< for an empty zone
} bdl_rod_histogram;

/// The histogram of the rods of `set`.
void bdl_rod_histogram_of(const bdl_rod_set *set, bdl_rod_histogram *h);

/// A time series of histograms of `bins` bins (as orientation.csv holds them), borrowed.
typedef struct bdl_rod_angle_series {
    long rows;
    int bins;
    const double *time;                   ///< [rows] [s]
    const double *count[BDL_ROD_ZONES];   ///< [rows * bins]: row r's bin b at r * bins + b
    const double *abs_cos[BDL_ROD_ZONES]; ///< [rows]: the row's mean |cos| (NAN: no rods)
} bdl_rod_angle_series;

/// Of the rows in [first, end) whose time lies in [from, to]: how many, the rods counted over
/// them per zone, and the rod-weighted mean |cos| per zone (NAN without rods).
typedef struct bdl_rod_angle_average {
    long rows;
    double rods[BDL_ROD_ZONES];
    double abs_cos[BDL_ROD_ZONES];
} bdl_rod_angle_average;

/// Pools those rows' histograms into the PDF of each zone, pdf[z][b] in 1/deg: the counts over
/// the rods counted and the bin width, so that the sum of pdf times the width is 1 (every bin NAN
/// for a zone without rods).
bdl_rod_angle_average bdl_rod_angle_pdf(const bdl_rod_angle_series *s, long first, long end,
                                        double from, double to, double *const pdf[BDL_ROD_ZONES]);

#endif
