// bedlam — time-averaged solids fields on a grid (see fields.h).
#include "analysis/fields.h"

#include <math.h>
#include <stdlib.h>

/// Cells along one axis are at most this many in n (the count returned is exact).
#define AXIS_CELLS_MAX 1e9

double bdl_fields_grid(const double lo[3], const double hi[3], double cell, int n[3], double h[3])
{
    double cells = 1.0;
    for (int a = 0; a < 3; ++a) {
        const double span = hi[a] - lo[a];
        // A span that is a whole number of cells gives that number, not one less by rounding.
        const double along = fmax(1.0, floor(span / cell + 1e-9));
        n[a] = (int)fmin(along, AXIS_CELLS_MAX);
        h[a] = span / along;
        cells *= along;
    }
    return cells;
}

bdl_result bdl_fields_create(bdl_fields *f, const double lo[3], const double hi[3], double cell,
                             double max_cells)
{
    *f = (bdl_fields){.first = NAN, .last = NAN};
    if (!(cell > 0.0) || !(bdl_fields_grid(lo, hi, cell, f->n, f->h) <= max_cells))
        return BDL_ERR_ARGS;
    for (int a = 0; a < 3; ++a)
        f->lo[a] = lo[a];
    const size_t cells = (size_t)bdl_fields_cells(f);
    f->volume = calloc(cells, sizeof(double));
    f->momentum = calloc(cells * 3, sizeof(double));
    if (!f->volume || !f->momentum) {
        bdl_fields_free(f);
        return BDL_ERR_NOMEM;
    }
    return BDL_OK;
}

void bdl_fields_free(bdl_fields *f)
{
    free(f->volume);
    free(f->momentum);
    f->volume = f->momentum = NULL;
}

long bdl_fields_cells(const bdl_fields *f) { return (long)f->n[0] * f->n[1] * f->n[2]; }

double bdl_fields_volume(double radius, double length)
{
    const double shaft = fmax(0.0, length - 2.0 * radius);
    return 4.0 / 3.0 * BDL_PI * radius * radius * radius + BDL_PI * radius * radius * shaft;
}

double bdl_fields_default_cell(long n, const double *radius)
{
    double sum = 0.0;
    for (long i = 0; i < n; ++i)
        sum += radius[i];
    return n > 0 ? 6.0 * sum / (double)n : NAN;
}

/// The cell holding point x, or -1 outside the grid (and for a non-finite x).
static long cell_of(const bdl_fields *f, const double *x)
{
    long index = 0;
    for (int a = 2; a >= 0; --a) {
        const double c = (x[a] - f->lo[a]) / f->h[a];
        if (!(c >= 0.0 && c < f->n[a]))
            return -1;
        index = index * f->n[a] + (long)c;
    }
    return index;
}

void bdl_fields_add(bdl_fields *f, const bdl_fields_sample *s)
{
    for (long i = 0; i < s->n; ++i) {
        double v = bdl_fields_volume(s->radius[i], s->length ? s->length[i] : 0.0);
        if (s->count)
            v *= s->count[i];
        f->total += v;
        const long c = cell_of(f, s->pos + 3 * i);
        if (c < 0)
            continue;
        f->volume[c] += v;
        for (int a = 0; a < 3; ++a)
            f->momentum[3 * c + a] += v * s->vel[3 * i + a];
        f->deposited += v;
    }
    f->particles += s->n;
    if (f->samples++ == 0)
        f->first = s->time;
    f->last = s->time;
}

void bdl_fields_means(const bdl_fields *f, double *fraction, double *velocity)
{
    const double cell_volume = f->h[0] * f->h[1] * f->h[2];
    const long cells = bdl_fields_cells(f);
    for (long c = 0; c < cells; ++c) {
        fraction[c] = f->volume[c] / (cell_volume * (double)f->samples);
        for (int a = 0; a < 3; ++a)
            velocity[3 * c + a] = f->volume[c] > 0.0 ? f->momentum[3 * c + a] / f->volume[c] : NAN;
    }
}
