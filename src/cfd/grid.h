// bedlam — the uniform staggered (MAC) grid of the gas solver.
//
// nx x ny x nz cells of size hx x hy x hz from `origin`. Scalars (pressure, voidage) live at cell
// centres; the velocity component along axis a lives on the faces normal to a (face i of axis a
// is the low face of cell i, at origin_a + i h_a). Every field, scalar or face, is stored in one
// padded layout with BDL_GRID_GHOST ghost layers on each side and one extra plane on the high
// side, so cell (i, j, k) and the low faces of that cell share one index:
//     index = (k + G) * sz + (j + G) * sy + (i + G),   -G <= i < nx + G + 1, ...
// A periodic y or z axis of one cell (the depth of a two-dimensional bed) is flat: its stride is
// 0 and it has no padding, so every ghost, image and face along it is the cell itself, as the
// period makes them (a sixth of the memory and of every whole-array loop in such a bed).
#ifndef BDL_GRID_H
#define BDL_GRID_H

#include <stddef.h>

#define BDL_GRID_GHOST 2

/// Loops over fewer cells than this run on one thread: below it, waking a team costs more than
/// the loop (a pseudo-2D bed has a few thousand cells).
#define BDL_GRID_PARALLEL_MIN 16384

typedef struct bdl_grid {
    int n[3];         ///< cells per axis
    double h[3];      ///< cell size per axis [m]
    double origin[3]; ///< low corner of the domain [m]
    int periodic[3];  ///< periodic axes
    long stride[3];   ///< index step per axis in the padded layout (1, sy, sz; 0 if flat)
    long size;        ///< padded array length
} bdl_grid;

/// Whether axis a of n cells, periodic or not, is flat (stride 0, no padding): a periodic y or z
/// of one cell.
static inline int bdl_grid_flat(int a, int n, int periodic) { return a > 0 && periodic && n == 1; }

/// Sets up a grid of n cells spanning lo..hi. Returns 0 when a count is below 1.
int bdl_grid_init(bdl_grid *g, const int n[3], const double lo[3], const double hi[3],
                  const int periodic[3]);

/// Index of cell (i, j, k) — or of the low faces of that cell.
static inline long bdl_grid_index(const bdl_grid *g, int i, int j, int k)
{
    return (long)(k + BDL_GRID_GHOST) * g->stride[2] + (long)(j + BDL_GRID_GHOST) * g->stride[1] +
           (i + BDL_GRID_GHOST);
}

/// The lowest and highest padded coordinates along axis a: -G and n + G, 0 and 0 if it is flat.
static inline int bdl_grid_pad_lo(const bdl_grid *g, int a)
{
    return g->stride[a] == 0 ? 0 : -BDL_GRID_GHOST;
}
static inline int bdl_grid_pad_hi(const bdl_grid *g, int a)
{
    return g->stride[a] == 0 ? 0 : g->n[a] + BDL_GRID_GHOST;
}

/// The ghost planes of f along the periodic axis a from their images (the whole planes, ghosts of
/// the other axes included); `faces`: f lives on the faces normal to a, and its plane n, the
/// image of plane 0, is filled too.
void bdl_grid_wrap_axis(const bdl_grid *g, double *f, int a, int faces);

/// The cell (or low faces) of padded index idx: ix[a] from -G to n[a] + G (0 along a flat axis).
void bdl_grid_position(const bdl_grid *g, long idx, int ix[3]);

/// Runs the statements given for every padded position (index `idx`) whose coordinate along
/// `axis` is `at`: a plane of cells or faces, ghosts included (each position once).
#define BDL_GRID_FOR_PLANE(gr, axis, at, ...)                                                      \
    do {                                                                                           \
        const int b_ = ((axis) + 1) % 3, c_ = ((axis) + 2) % 3;                                    \
        for (int jc_ = bdl_grid_pad_lo(gr, c_); jc_ <= bdl_grid_pad_hi(gr, c_); ++jc_)             \
            for (int jb_ = bdl_grid_pad_lo(gr, b_); jb_ <= bdl_grid_pad_hi(gr, b_); ++jb_) {       \
                int ix_[3];                                                                        \
                ix_[axis] = (at);                                                                  \
                ix_[b_] = jb_;                                                                     \
                ix_[c_] = jc_;                                                                     \
                const long idx = bdl_grid_index(gr, ix_[0], ix_[1], ix_[2]);                       \
                __VA_ARGS__;                                                                       \
            }                                                                                      \
    } while (0)

/// A zeroed padded array; NULL when out of memory.
double *bdl_grid_alloc(const bdl_grid *g);

/// Copies periodic images into the ghost layers of a cell-centred field on every periodic axis.
void bdl_grid_wrap_cells(const bdl_grid *g, double *f);

/// The same on the periodic axes with more than one cell only, for stencils that skip the axes of
/// one cell (across a period of one cell the neighbour is the cell itself: no difference).
void bdl_grid_wrap_cells_wide(const bdl_grid *g, double *f);

/// Fills the ghost layers of a cell-centred field: periodic images on periodic axes, the
/// nearest cell's value (zero gradient) on the others.
void bdl_grid_extend_cells(const bdl_grid *g, double *f);

/// Copies the whole padded plane at index `from` along axis a onto the one at `to` (ghosts of
/// the other axes included): rows along x at a time unless a is x.
void bdl_grid_copy_plane(const bdl_grid *g, double *f, int a, int to, int from);

/// Mean of a cell field over the layer of cells m normal to axis a.
double bdl_grid_layer_mean(const bdl_grid *g, const double *field, int a, int m);

#endif
