// bedlam — parcel verification: hindered settling of a parcel suspension against the model's own
// Richardson-Zaki law (Patankar & Joseph 2001; digest of seed 001, sec. 4.1).
#include <math.h>
#include <stdio.h>

#include "cfd/gas.h"
#include "core/log.h"
#include "verify/verify.h"

/// The column of the settling case: one cell across (no lateral flow: the case isolates the
/// drag, the implicit coupling and the projection from the convection that parcel noise drives
/// in wider columns), `cells` along z, filled to 0.8 of its height at solids fraction phi with
/// `per_cell` parcels per cell on average: at random (seed > 0), or (seed 0) on a cubic lattice
/// of per_cell layers per cell, the parcels' volume set so that the layers hold phi.
static bdl_world *column(int per_cell, int cells, double dt, double phi, int seed)
{
    const double width = 5e-3, height = 0.1, h = height / cells, d = 198e-6;
    double parcel = phi * width * width * h / per_cell;
    char fill[160];
    if (seed > 0) {
        snprintf(fill, sizeof fill, "type = random\nvolume_fraction = %g\n", phi);
    } else {
        const double s = h / per_cell, row = floor((width - d) / s) + 1.0; // as create.c lays it
        parcel = phi * width * width * s / (row * row);
        snprintf(fill, sizeof fill, "type = lattice\nspacing = %.17g\n", s);
    }
    return bdl_verify_world(
        "[run]\nend_time = 100\ndt = %.17g\ngravity = 0 0 -9.81\nseed = %d\n"
        "[domain]\nmin = 0 0 0\nmax = %g %g %g\n"
        "[species heavy]\ndiameter = %g\ndensity = 2990\nparcel_volume = %.17g\n"
        "[create suspension]\n%sspecies = heavy\nregion_min = 0 0 0\nregion_max = %g %g %g\n"
        "[gas]\ndensity = 992\nviscosity = 0.0667\ncells = 1 1 %d\n"
        "[coupling]\ndrag = patankar\n",
        dt, seed > 0 ? seed : 1, width, width, height, d, parcel, fill, width, width, 0.8 * height,
        cells);
}

double bdl_verify_parcel_interface(const bdl_world *w, double level)
{
    const bdl_grid *g = &w->gas->grid;
    const int nz = g->n[2], across = g->n[0] * g->n[1];
    double above = 0.0;
    for (int k = nz - 1; k >= 0; --k) {
        double theta = 0.0;
        for (int j = 0; j < g->n[1]; ++j)
            for (int i = 0; i < g->n[0]; ++i)
                theta += 1.0 - w->gas->eps[bdl_grid_index(g, i, j, k)];
        theta /= across;
        if (theta >= level) {
            const double z = g->origin[2] + (k + 0.5) * g->h[2];
            return k == nz - 1 ? z : z + g->h[2] * (theta - level) / (theta - above);
        }
        above = theta;
    }
    return g->origin[2];
}

double bdl_verify_solids_above(const bdl_world *w, double z)
{
    double v = 0.0;
    for (long i = 0; i < w->particles.count; ++i)
        if (w->particles.pos[i].z > z)
            v += bdl_particle_solids_volume(&w->particles, i);
    return v;
}

bdl_result bdl_verify_parcel_settling(int per_cell, int cells, double dt, double phi, int seed,
                                      bdl_verify_settling *out)
{
    const double d = 198e-6, rho_p = 2990.0, rho = 992.0, mu = 0.0667, g = 9.81;
    const double eps = 1.0 - phi, target = (rho_p - rho) * g;
    out->vt = bdl_verify_implied_slip(BDL_DRAG_PATANKAR, 1.0, d, rho, mu, target, 1.0);
    out->expected =
        eps * bdl_verify_implied_slip(BDL_DRAG_PATANKAR, eps, d, rho, mu, eps * target, 1.0);
    out->re_t = rho * out->vt * d / mu;
    out->n = log(out->expected / out->vt) / log(eps);
    out->steps = 0;
    out->measured = NAN;
    bdl_world *w = column(per_cell, cells, dt, phi, seed);
    if (!w)
        return BDL_ERR_SCENE;
    // The interface by least squares over a window in which it has left its start and is far
    // above the sediment: as the height the solids above a level z_b in the uniform suspension
    // fill at phi, z_b + V(z > z_b) / (phi A) (counted over the parcels themselves, free of the
    // kernel's smearing, which biases a threshold crossing on the grid by a fraction of a cell).
    const double t0 = 5.0, t1 = 35.0, every = 0.25, z_b = 0.03, area = 5e-3 * 5e-3;
    double st = 0.0, sz = 0.0, stt = 0.0, stz = 0.0, next = t0;
    long samples = 0;
    bdl_result r = BDL_OK;
    while (r == BDL_OK && w->time < t1 + 0.5 * dt) {
        r = bdl_world_step(w);
        ++out->steps;
        if (r == BDL_OK && w->time >= next - 0.5 * dt) {
            const double z = z_b + bdl_verify_solids_above(w, z_b) / (phi * area), t = w->time;
            st += t, sz += z, stt += t * t, stz += t * z;
            ++samples;
            next += every;
        }
    }
    if (r != BDL_OK)
        bdl_error("%s", w->failure);
    bdl_world_destroy(w);
    const double n = (double)samples;
    if (r == BDL_OK && samples > 2)
        out->measured = -(n * stz - st * sz) / (n * stt - st * st);
    return r;
}
