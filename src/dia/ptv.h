// bedlam — particle tracking velocimetry by nearest-neighbour linking of detected centroids
// between consecutive frames (Mahajan 2019, ch. 2, after Adrian and Westerweel 2011), and the
// 2D coordination number of the tracked particles.
#ifndef BDL_DIA_PTV_H
#define BDL_DIA_PTV_H

#include "core/error.h"

/// Tracks found by bdl_dia_ptv_link. Track t's points are point[start[t] .. start[t + 1]), one
/// per frame from first_frame[t] on, as indices into the points given.
typedef struct bdl_dia_tracks {
    long count;        ///< tracks kept
    long *first_frame; ///< per track
    long *start;       ///< count + 1 offsets into point
    long *point;       ///< the tracks' points, track after track, frame by frame
    long *track;       ///< per point given: its track, -1 when its track was too short
} bdl_dia_tracks;

/// Links the points of consecutive frames: frame f holds the points frame_start[f] ..
/// frame_start[f + 1] - 1 of (u, v) [px] (frames + 1 offsets). Between two frames every pair
/// closer than max_displacement [px] is a candidate; the candidates are taken in order of
/// distance (ties by the points' order) and a pair is linked when neither point is linked yet
/// on that side, so a conflict goes to the smallest displacement; a point left unlinked starts
/// a new track. Tracks of fewer than min_length frames are dropped. BDL_ERR_ARGS when
/// max_displacement <= 0 or frames < 1.
bdl_result bdl_dia_ptv_link(const double *u, const double *v, const long *frame_start, long frames,
                            double max_displacement, long min_length, bdl_dia_tracks *tracks);
void bdl_dia_tracks_free(bdl_dia_tracks *tracks);

/// 2D coordination number: for each of n points, the number of other points closer than
/// `radius` [px]. With bounds (u0, v0, u1, v1: the bed's part of the image), the count is
/// divided by the fraction of the disc of that radius that lies inside them (the thesis's wall
/// correction); NULL: not corrected. cn gets n values.
bdl_result bdl_dia_coordination_2d(const double *u, const double *v, long n, double radius,
                                   const double *bounds, double *cn);

/// Area of the disc of centre (u, v) and radius r inside the rectangle bounds (u0, v0, u1, v1),
/// by the midpoint rule over 512 strips (error below 10^-4 of the disc).
double bdl_dia_disc_in_rect(double u, double v, double r, const double *bounds);

#endif
