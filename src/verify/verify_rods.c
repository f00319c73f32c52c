// bedlam — rod verification: the thesis's small bed of rods, packed under gravity.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "analysis/granular.h"
#include "core/log.h"
#include "dem/species.h"
#include "verify/verify.h"

/// The bed of scenes/rod_bed_packed.ini (Mahajan 2019, table 4.1, small set-up) without its
/// outputs; `%g` is the time step as a fraction of the shortest contact time.
static const char rod_bed[] =
    "[run]\nend_time = 10\ndt_fraction = %g\ngravity = 0 0 -9.81\nseed = 3\n"
    "[domain]\nmin = 0 0 0\nmax = 0.1 0.014 0.5\n"
    "[contact]\nlaw = linear\nrolling = constant\nskin = 0.3\n"
    "[species rod]\nshape = rod\ndiameter = 1.5e-3\nlength = 6e-3\ndensity = 1395\n"
    "stiffness = 6000\nrestitution = 0.43\nfriction = 0.46\nrolling_friction = 0.025\n"
    "[wall box]\ntype = box\nmin = 0 0 0\nmax = 0.1 0.014 0.5\nfriction = 0.33\n"
    "[create bed]\ntype = random\nspecies = rod\ncount = 8070\n"
    "region_min = 0 0 0\nregion_max = 0.1 0.014 0.45\n";

/// Kinetic energy per particle over m g d (m and d of the first particle; the bed has one size):
/// the bed is at rest when this is small.
static double kinetic_per_mgd(const bdl_world *w)
{
    const bdl_particles *p = &w->particles;
    double e = 0.0;
    for (long i = 0; i < p->count; ++i)
        e += 0.5 * bdl_v3_len2(p->vel[i]) / p->inv_mass[i];
    const double m = 1.0 / p->inv_mass[0], g = bdl_v3_len(w->scene.gravity);
    return e / ((double)p->count * m * g * 2.0 * p->radius[0]);
}

/// The packed bed's surface, orientation order and tilt histogram (see verify.h).
static bdl_result measure(const bdl_world *w, bdl_verify_rod_bed *out)
{
    const bdl_particles *p = &w->particles;
    const long n = p->count;
    double *lo = malloc((size_t)n * sizeof *lo), *hi = malloc((size_t)n * sizeof *hi);
    double *vol = malloc((size_t)n * sizeof *vol);
    bdl_result r = BDL_ERR_NOMEM;
    if (lo && hi && vol) {
        const bdl_species_def *s = &w->scene.species[0];
        bdl_orientation_sums axes = {0};
        for (long i = 0; i < n; ++i) {
            const bdl_vec3 e = bdl_particle_half_axis(p, i);
            lo[i] = p->pos[i].z - fabs(e.z) - p->radius[i];
            hi[i] = p->pos[i].z + fabs(e.z) + p->radius[i];
            vol[i] = bdl_species_volume(s, 2.0 * p->radius[i]);
            const bdl_vec3 u = bdl_q_axis_z(p->orient[i]);
            bdl_orientation_add(&axes, u, bdl_v3(0, 0, 1));
            // Angle of the axis to the horizontal, in 10-degree bins.
            const double tilt = asin(fmin(1.0, fabs(u.z))) * 180.0 / 3.14159265358979323846;
            const int bin = (int)(tilt / 10.0);
            out->tilt[bin < BDL_VERIFY_TILT_BINS ? bin : BDL_VERIFY_TILT_BINS - 1] += 1.0 / n;
        }
        const bdl_vec3 span = bdl_v3_sub(w->scene.domain_max, w->scene.domain_min);
        bdl_bed_surface b;
        r = bdl_bed_surface_of(lo, hi, vol, n, span.x * span.y, 0.5e-3, &b);
        out->height = b.height;
        out->bulk = b.bulk;
        out->vertical_cos = bdl_orientation_vertical(&axes);
        out->order = bdl_orientation_order(&axes);
    }
    free(lo);
    free(hi);
    free(vol);
    return r;
}

bdl_result bdl_verify_rod_bed_run(double dt_fraction, bdl_verify_rod_bed *out)
{
    *out = (bdl_verify_rod_bed){0};
    bdl_world *w = bdl_verify_world(rod_bed, dt_fraction);
    if (!w)
        return BDL_ERR_SCENE;
    // Fall for 0.4 s (the top rods land after 0.3 s), then settle until the kinetic energy has
    // died down to 1e-6 m g d per rod, checked every 0.02 s, for at most 3 s in all.
    bdl_result r = BDL_OK;
    const long check = (long)ceil(0.02 / w->dt), most = (long)ceil(3.0 / w->dt);
    for (long s = 0; r == BDL_OK && s < most; ++s) {
        if ((r = bdl_world_step(w)) != BDL_OK)
            bdl_error("%s", w->failure);
        if (w->time > 0.4 && w->step % check == 0 && kinetic_per_mgd(w) < 1e-6)
            break;
    }
    out->steps = w->step;
    out->time = w->time;
    out->kinetic = kinetic_per_mgd(w);
    if (r == BDL_OK)
        r = measure(w, out);
    bdl_world_destroy(w);
    return r;
}
