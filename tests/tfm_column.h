// A column or pseudo-2D bed of gas and solids phases for the two-fluid model's tests.
#ifndef BDL_TEST_TFM_COLUMN_H
#define BDL_TEST_TFM_COLUMN_H

#include "cfd/gas.h"
#include "solids/phase.h"

typedef struct column {
    bdl_gas *gas;
    bdl_solids *solids;
} column;

enum { COLUMN_CLOSED = 1, COLUMN_PERIODIC_X = 2 };

/// nx x nz cells of h (one cell of h along y, periodic), gravity along -z; walls on the sides
/// (periodic with COLUMN_PERIODIC_X or one cell across), and below and above either walls
/// (COLUMN_CLOSED) or an inlet of superficial velocity U and an outlet; `count` solids phases.
static inline int column_create_mixture(column *c, int nx, int nz, double h, int flags, double U,
                                        const bdl_solids_def *defs, int count)
{
    bdl_gas_def g = bdl_default_gas_def();
    g.n[0] = nx, g.n[1] = 1, g.n[2] = nz;
    g.hi[0] = nx * h, g.hi[1] = h, g.hi[2] = nz * h;
    g.gravity[2] = -9.81;
    g.pressure_share = 1;
    g.convection = BDL_CONVECTION_SUPERBEE;
    g.tolerance = 1e-10;
    g.max_iterations = 1000;
    g.side[2].type = g.side[3].type = BDL_SIDE_PERIODIC;
    if (nx == 1 || (flags & COLUMN_PERIODIC_X))
        g.side[0].type = g.side[1].type = BDL_SIDE_PERIODIC;
    if (!(flags & COLUMN_CLOSED)) {
        g.side[4].type = BDL_SIDE_INLET;
        g.side[4].inflow = U;
        g.side[5].type = BDL_SIDE_OUTLET;
    }
    if (bdl_gas_create(&g, &c->gas) != BDL_OK)
        return 0;
    return bdl_solids_create_mixture(defs, count, c->gas, &c->solids) == BDL_OK;
}

/// The same with one solids phase.
static inline int column_create(column *c, int nx, int nz, double h, int flags, double U,
                                const bdl_solids_def *sd)
{
    return column_create_mixture(c, nx, nz, h, flags, U, sd, 1);
}

static inline void column_destroy(column *c)
{
    bdl_solids_destroy(c->solids);
    bdl_gas_destroy(c->gas);
}

/// Solids fraction eps in the cell layers [lo, hi) of z, and the gas at rest or at the inflow.
static inline void column_fill(column *c, int lo, int hi, double eps)
{
    const bdl_grid *gr = &c->solids->grid;
    for (int k = lo; k < hi; ++k)
        for (int i = 0; i < gr->n[0]; ++i)
            c->solids->eps[bdl_grid_index(gr, i, 0, k)] = eps;
    bdl_solids_share_voidage(c->solids, c->gas);
}

static inline double cell(const column *c, const double *f, int i, int k)
{
    return f[bdl_grid_index(&c->solids->grid, i, 0, k)];
}

#endif
