// bedlam analyze dia — what the chain against the truth (analyze_dia.c) shares with the
// coalignment by wall zone and the solids mass flux (analyze_dia_flux.c): the camera, the CSV
// tables, and the accumulators that pool those two over the frames. Internal to the dia analysis.
#ifndef BDL_ANALYZE_DIA_H
#define BDL_ANALYZE_DIA_H

#include "app/analyze.h"
#include "core/error.h"
#include "core/vec3.h"
#include "dia/analysis.h"
#include "dia/piv.h"

/// What the analysis needs of camera.json.
typedef struct dia_camera {
    int width, height, cells[2];
    int back_lit; ///< lighting = back: dark particles on a bright background
    double pixel_size, pair_dt;
    bdl_vec3 position, right, down, forward;
} dia_camera;

/// A CSV file's columns, read whole (NULL where a column is missing).
typedef struct dia_table {
    long rows;
    double *col[12];
} dia_table;

/// The columns of a cells table as analyze_dia.c reads them (frame_NNNNNN_cells.csv).
enum {
    DIA_U0,
    DIA_V0,
    DIA_U1,
    DIA_V1,
    DIA_AREA,    ///< area_fraction
    DIA_DEPTH,   ///< solids_depth: the true solids fraction over the bed's depth
    DIA_VISIBLE, ///< visible_particles
    DIA_DU,      ///< du, dv: true mean velocity of the visible particles [px/s]
    DIA_DV,
    DIA_LAYER ///< solids_layer: over the first particle layer
};

/// Height above the floor (z = 0 along -down) of image row level v [m].
static inline double dia_row_height(const dia_camera *cam, double v)
{
    return -bdl_v3_dot(cam->position, cam->down) - (v - 0.5 * cam->height) * cam->pixel_size;
}

/// The mean displacement (*du, *dv) [px] of the PIV vectors not flagged as outliers whose window
/// centre lies in u0 <= u < u1, v0 <= v < v1; returns how many there are (0: none, *du, *dv 0).
long dia_piv_cell_mean(const bdl_dia_piv_field *f, double u0, double v0, double u1, double v1,
                       double *du, double *dv);

enum { DIA_ZONES = 3, DIA_COALIGN_BINS = 20 };

/// Coalignment C(r) over 0 .. 5 rod lengths by zone of the reference rod's distance from the
/// nearer side wall (< 2, 2-6, > 6 L_p; the walls are the image's left and right edges), pooled
/// over frames: per bin the sums of pairs x C and pairs x distance, and the pairs. Index 0 of
/// the first dimension: the detected rods; 1: the true wall rods.
typedef struct dia_coalign {
    double lp; ///< rod length [px] (the last frame's)
    double c_sum[2][DIA_ZONES][DIA_COALIGN_BINS], r_sum[2][DIA_ZONES][DIA_COALIGN_BINS];
    long pairs[2][DIA_ZONES][DIA_COALIGN_BINS];
} dia_coalign;

/// Adds one frame's rods (pixel centres, angles in degrees) to the sums of set `truth` (0 or 1);
/// lp: rod length [px], width: the image's width [px].
void dia_coalign_add(dia_coalign *z, int truth, const double *u, const double *v,
                     const double *angle, long n, double lp, int width);
/// The pooled C(r), mean distance r [px] and pairs of one set and zone (NAN where no pair), and
/// the coalignment length fitted to it (C = exp(-r / xi)), in rod lengths (NAN: none).
double dia_coalign_zone(const dia_coalign *z, int truth, int zone, double *c, double *r,
                        long *pairs);
/// Prints the lengths per zone and writes OUT/coalignment.csv.
bdl_result dia_coalign_report(const dia_coalign *z, const char *out);

/// A fit of bedlam calibrate (its fit.json) and how its f2D was measured.
typedef struct dia_flux_fit {
    bdl_dia_fit fit; ///< the rational model f3D = A f2D / (B - f2D)
    double cap, offset;
    int adaptive, window; ///< the threshold: adaptive (window, offset) or Otsu
    int layer;            ///< the fit's truth was solids_layer (else solids_depth)
    int normalise;        ///< f2D scaled to the solids the truth puts in the image
} dia_flux_fit;

/// Reads a calibrate fit.json; BDL_ERR_ARGS (printed) when it is not one.
bdl_result dia_flux_read_fit(const char *path, dia_flux_fit *fit);

/// The vertical solids mass flux per image cell from the images (calibrated voidage and PIV) and
/// from the truth, summed over the double frames.
typedef struct dia_flux {
    dia_flux_fit fit;
    double density; ///< of the particles [kg/m^3]
    long cells;     ///< per-cell arrays below: 0 until the first frame
    int nx, ny;
    double *image_sum, *truth_sum;      ///< sums of the upward flux over frames [kg/(m^2 s)]
    long *frames;                       ///< frames with data per cell
    double *x, *z;                      ///< cell centres [m]: along the image's right, height
    long used, no_particles, no_vector; ///< cell-frames with data, skipped for either reason
    double f3d_image, f3d_truth, w_image, w_truth; ///< sums over the cell-frames used
} dia_flux;

/// With --fit: checks --density and reads the fit into a new *fx (NULL without --fit).
bdl_result dia_flux_open(const bdl_analyze_opts *o, dia_flux **fx);
/// Adds one double frame: `img` its first image, f its PIV field, cells its truth.
bdl_result dia_flux_add(dia_flux *fx, const dia_camera *cam, const double *img,
                        const bdl_dia_piv_field *f, const dia_table *cells);
/// Prints the time-mean profile at the row nearest `height` [m] and the error figures, writes
/// OUT/mass_flux.csv.
bdl_result dia_flux_report(const dia_flux *fx, double height, const char *out);
void dia_flux_free(dia_flux *fx);

#endif
