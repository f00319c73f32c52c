// bedlam — parcel verification: hindered settling of a parcel suspension against the model's own
// Richardson-Zaki law (Patankar & Joseph 2001; digest of seed 001, sec. 4.1).
#include <math.h>
#include <stdio.h>

#include "cfd/gas.h"
#include "core/log.h"
#include "parcels/parcels.h"
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

// ---- bimodal sedimentation (Davis, Herbolzheimer & Acrivos 1982; the paper's sec. 4.1) ----

/// The paper's column in one cell across: case A (50 cells along it, 9000 parcels per species,
/// dt 0.005 s) or B (60 cells, 18 000, dt 0.004 s), K = 5.
static bdl_world *bimodal_column(int case_b)
{
    const int cells = case_b ? 60 : 50;
    const long count = case_b ? 18000 : 9000;
    const double fill = 0.05 * 0.05 * 1.0;
    return bdl_verify_world(
        "[run]\nend_time = 1000\ndt = %g\ngravity = 0 0 -9.81\nseed = 2\n"
        "[domain]\nmin = 0 0 0\nmax = 0.05 0.05 1.25\n"
        "[species heavy]\ndistribution = uniform\ndiameter = 198e-6\ndiameter_min = 177e-6\n"
        "diameter_max = 219e-6\ndensity = 2990\nparcel_volume = %.17g\n"
        "[species light]\ndistribution = uniform\ndiameter = 137.5e-6\ndiameter_min = 125e-6\n"
        "diameter_max = 150e-6\ndensity = 2440\nparcel_volume = %.17g\n"
        "[create heavy]\ntype = random\nspecies = heavy\ncount = %ld\nregion_min = 0 0 0\n"
        "region_max = 0.05 0.05 1.0\n"
        "[create light]\ntype = random\nspecies = light\ncount = %ld\nregion_min = 0 0 0\n"
        "region_max = 0.05 0.05 1.0\n"
        "[gas]\ndensity = 992\nviscosity = 0.0667\ncells = 1 1 %d\n"
        "[coupling]\ndrag = patankar\n[parcels]\nsubsteps = 5\n",
        case_b ? 0.004 : 0.005, 0.01 * fill / count, 0.03 * fill / count, count, count, cells);
}

/// Solids volume of species s above z [m^3], and the mean vertical velocity of its parcels above
/// z (into *v; NAN when none).
static double species_above(const bdl_world *w, int s, double z, double *v)
{
    double volume = 0.0, sum = 0.0;
    long n = 0;
    for (long i = 0; i < w->particles.count; ++i)
        if (w->particles.species[i] == s && w->particles.pos[i].z > z) {
            volume += bdl_particle_solids_volume(&w->particles, i);
            sum += w->particles.vel[i].z;
            ++n;
        }
    *v = n > 0 ? sum / (double)n : NAN;
    return volume;
}

bdl_result bdl_verify_parcel_bimodal(int case_b, double t_end, bdl_verify_bimodal *out)
{
    *out = (bdl_verify_bimodal){.heavy_front = NAN, .light_zone = NAN};
    bdl_world *w = bimodal_column(case_b);
    if (!w)
        return BDL_ERR_SCENE;
    const double area = 0.05 * 0.05, z_b = 0.5, every = 2.0;
    double st = 0.0, sz = 0.0, stt = 0.0, stz = 0.0, light = 0.0, next = 20.0;
    long samples = 0, light_samples = 0;
    bdl_result r = BDL_OK;
    while (r == BDL_OK && w->time < t_end + 0.5 * w->dt) {
        r = bdl_world_step(w);
        ++out->steps;
        if (r != BDL_OK || w->time < next - 0.5 * w->dt)
            continue;
        next += every;
        // The heavy front: the height the heavy solids above z_b fill at their initial fraction
        // (the mixture below the front keeps it); the top interface moves with the light
        // parcels of the light-only zone above the front (nothing is above the interface).
        double v;
        const double z = z_b + species_above(w, 0, z_b, &v) / (0.01 * area), t = w->time;
        st += t, sz += z, stt += t * t, stz += t * z;
        ++samples;
        species_above(w, 1, z + 0.01, &v);
        if (t >= 0.3 * t_end && isfinite(v)) {
            light += v;
            ++light_samples;
        }
    }
    if (r != BDL_OK)
        bdl_error("%s", w->failure);
    bdl_world_destroy(w);
    const double n = (double)samples;
    if (r == BDL_OK && samples > 2)
        out->heavy_front = -(n * stz - st * sz) / (n * stt - st * st);
    if (r == BDL_OK && light_samples > 0)
        out->light_zone = -light / (double)light_samples;
    return r;
}

// ---- the Boycott effect (Acrivos & Herbolzheimer 1979; the paper's sec. 4.2) ----

/// Height of the crossing of `level` by the solids fraction averaged over cell columns i0..i1 (at
/// j = 0), from the top down, interpolated between cell centres [m].
static double column_interface(const bdl_world *w, int i0, int i1, double level)
{
    const bdl_grid *g = &w->gas->grid;
    double above = 0.0;
    for (int k = g->n[2] - 1; k >= 0; --k) {
        double theta = 0.0;
        for (int i = i0; i <= i1; ++i)
            theta += 1.0 - w->gas->eps[bdl_grid_index(g, i, 0, k)];
        theta /= i1 - i0 + 1;
        if (theta >= level) {
            const double z = g->origin[2] + (k + 0.5) * g->h[2];
            return k == g->n[2] - 1 ? z : z + g->h[2] * (theta - level) / (theta - above);
        }
        above = theta;
    }
    return g->origin[2];
}

/// The mean solids fraction of model A's sediment holding a solids height h_s (solids volume
/// per area) under the acceleration g_n: in the 1-D balance d tau / dz = (rho_p - rho) g_n theta
/// the stress at the floor is tau_b = (rho_p - rho) g_n h_s, and the sediment's height H = int_0^
/// tau_b d tau / ((rho_p - rho) g_n theta(tau)), taken with tau = tau_b s^3 (theta ~ tau^(1/3) at
/// the top) by the midpoint rule, theta(tau) by bisection of the model's tau(theta).
static double sediment_fraction(const bdl_parcels_def *def, double weight, double h_s)
{
    const double tau_b = weight * h_s;
    const int n = 4000;
    double height = 0.0;
    for (int k = 0; k < n; ++k) {
        const double s = (k + 0.5) / n, tau = tau_b * s * s * s;
        double lo = 0.0, hi = def->close_packing;
        for (int it = 0; it < 60; ++it) {
            const double mid = 0.5 * (lo + hi);
            *(bdl_parcels_stress(def, mid) < tau ? &lo : &hi) = mid;
        }
        height += 3.0 * tau_b * s * s / (weight * 0.5 * (lo + hi)) / n;
    }
    return h_s / height;
}

bdl_result bdl_verify_parcel_boycott(int vertical, double t_end, bdl_verify_boycott *out)
{
    const double d = 136e-6, rho_p = 2420.0, rho = 992.0, mu = 0.0667, phi = 0.1, eps = 0.9;
    const double angle = vertical ? 0.0 : 35.0 * BDL_PI / 180.0, b = 0.05, y0 = 0.5233;
    *out = (bdl_verify_boycott){.worst = NAN, .worst_pnk = NAN, .speed_200 = NAN};
    out->v0 = eps * bdl_verify_implied_slip(BDL_DRAG_PATANKAR, eps, d, rho, mu,
                                            eps * (rho_p - rho) * 9.81, 1.0);
    bdl_world *w = bdl_verify_world(
        "[run]\nend_time = 2000\ndt = 0.005\ngravity = %.17g 0 %.17g\nseed = 4\n"
        "[domain]\nmin = 0 0 0\nmax = 0.05 0.0015625 0.6\n"
        "[species glass]\ndistribution = uniform\ndiameter = 136e-6\ndiameter_min = 130e-6\n"
        "diameter_max = 142e-6\ndensity = 2420\nparcel_volume = 2.2573e-10\n"
        "[create suspension]\ntype = random\nspecies = glass\ncount = 18111\n"
        "region_min = 0 0 0\nregion_max = 0.05 0.0015625 %g\n"
        "[gas]\ndensity = 992\nviscosity = 0.0667\ncells = 32 1 72\n"
        "[coupling]\ndrag = patankar\n[parcels]\ngas_substeps = 8\n",
        -9.81 * sin(angle), -9.81 * cos(angle), y0);
    if (!w)
        return BDL_ERR_SCENE;
    const double s = sin(angle), c = cos(angle), span = vertical ? 0.0 : b / (s * c);
    out->speed_200_pnk =
        vertical ? out->v0 : (y0 + span) * (1.0 - exp(-out->v0 * 200.0 * s / b)) / 200.0;
    // With the sediment: the suspension S = (y - r y0) / (1 - r) above it, r = phi / theta_sed.
    out->theta_sed = sediment_fraction(&w->parcels->def, (rho_p - rho) * 9.81 * c, phi * y0);
    const double r_sed = phi / out->theta_sed, span_sed = span * (1.0 - r_sed);
    const double rate_sed = vertical ? 0.0 : out->v0 * s / (b * (1.0 - r_sed));
    const int mid = w->gas->grid.n[0] / 2;
    double next = 20.0;
    bdl_result r = BDL_OK;
    while (r == BDL_OK && w->time < t_end + 0.5 * w->dt) {
        r = bdl_world_step(w);
        ++out->steps;
        if (r != BDL_OK || w->time < next - 0.5 * w->dt ||
            out->samples == BDL_VERIFY_BOYCOTT_SAMPLES)
            continue;
        next += 20.0;
        const int k = out->samples++;
        out->t[k] = w->time;
        out->y[k] = column_interface(w, mid - 1, mid, 0.5 * phi);
        out->y_pnk[k] = vertical ? y0 - out->v0 * w->time
                                 : (y0 + span) * exp(-out->v0 * w->time * s / b) - span;
        out->y_sed[k] = vertical ? y0 - out->v0 * w->time
                                 : r_sed * y0 - span_sed +
                                       (y0 * (1.0 - r_sed) + span_sed) * exp(-rate_sed * w->time);
        out->y_sed[k] = fmax(out->y_sed[k], r_sed * y0); // all settled
        if (w->time > 100.0 - 0.5 * w->dt) {
            const double e = fabs(out->y[k] / out->y_sed[k] - 1.0);
            out->worst = isnan(out->worst) ? e : fmax(out->worst, e);
        }
        if (w->time > 100.0 - 0.5 * w->dt && w->time < 500.0 + 0.5 * w->dt) {
            const double e = fabs(out->y[k] / out->y_pnk[k] - 1.0);
            out->worst_pnk = isnan(out->worst_pnk) ? e : fmax(out->worst_pnk, e);
        }
        if (fabs(w->time - 200.0) < 0.5 * w->dt)
            out->speed_200 = (y0 - out->y[k]) / 200.0;
    }
    if (r != BDL_OK)
        bdl_error("%s", w->failure);
    bdl_world_destroy(w);
    return r;
}
