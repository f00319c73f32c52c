// The velocity-Verlet integrator (the scheme: integrate.h). The force pass between the two half
// kicks, which also applies the closing one, is contact_force.c.
#include "dem/integrate.h"

#include <omp.h>

#include "dem/contact_force.h" // BDL_PARALLEL_MIN

double bdl_dem_kick_drift(bdl_particles *p, bdl_vec3 gravity, double h, double dt)
{
    long n = p->count;
    double max2 = 0.0;
    // Each thread sweeps its share of the particles backwards: the force pass that follows
    // starts at the low end of the same share, so the state it reads first is what this pass
    // touched last and is still in the caches (docs/performance.md, "Memory").
#pragma omp parallel reduction(max : max2) if (n >= BDL_PARALLEL_MIN)
    {
        long t = omp_get_thread_num(), threads = omp_get_num_threads();
        long lo = n * t / threads, hi = n * (t + 1) / threads;
        for (long i = hi - 1; i >= lo; --i) {
            double im = p->inv_mass[i];
            bdl_vec3 g = p->fluid_accel ? bdl_v3_add(gravity, p->fluid_accel[i]) : gravity;
            bdl_vec3 v = bdl_v3_madd(bdl_v3_madd(p->vel[i], g, h), p->load[i].force, h * im);
            p->vel[i] = v;
            p->omega[i] =
                bdl_v3_madd(p->omega[i], p->load[i].torque, h * bdl_particle_inv_inertia(p, i));
            p->load[i] = (bdl_wrench){bdl_v3_zero(), bdl_v3_zero()}; // for the force pass
            bdl_vec3 x = bdl_v3_madd(p->pos[i], v, dt);
            p->pos[i] = x;
            double d2 = bdl_v3_len2(bdl_v3_sub(x, p->pos_at_build[i]));
            if (d2 > max2)
                max2 = d2;
        }
    }
    return max2;
}

double bdl_dem_wall_power(const bdl_particles *p, const bdl_neighbor *nb, const bdl_walls *walls)
{
    int moving = 0;
    for (int w = 0; w < walls->wall_count; ++w)
        moving |= walls->motion[w] != BDL_MOTION_NONE;
    if (!moving)
        return 0.0;
    // Serial in list order: the result is the same for any thread count.
    double power = 0.0;
    long entries = nb->wall_start ? nb->wall_start[p->count] : 0;
    for (long k = 0; k < entries; ++k) {
        if (!nb->wall_touching[k])
            continue;
        int wall = walls->prims[nb->wall_prim[k]].wall;
        power += bdl_v3_dot(nb->wall_force[k], walls->velocity[wall]);
    }
    return power;
}
