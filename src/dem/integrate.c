// The velocity-Verlet integrator (the scheme: integrate.h). The force pass between the two half
// kicks, which also applies the closing one, is contact_force.c.
#include "dem/integrate.h"

#include <math.h>
#include <omp.h>

#include "core/parallel.h"
#include "dem/rigid.h"
#include "dem/rod_force.h"

/// Kick and drift of the spheres lo..hi-1, swept backwards; returns the largest squared
/// displacement since the lists were built.
static double kick_drift_range(bdl_particles *p, bdl_vec3 gravity, double h, double dt, long lo,
                               long hi)
{
    double max2 = 0.0;
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
    return max2;
}

double bdl_dem_kick_drift(bdl_particles *p, bdl_vec3 gravity, double h, double dt)
{
    const long n = p->count;
    // Small systems stay out of the OpenMP runtime altogether (core/parallel.h).
    if (n < BDL_PARALLEL_MIN)
        return kick_drift_range(p, gravity, h, dt, 0, n);
    double max2 = 0.0;
    // Each thread sweeps its share of the particles backwards: the force pass that follows
    // starts at the low end of the same share, so the state it reads first is what this pass
    // touched last and is still in the caches (docs/performance.md, "Memory").
#pragma omp parallel reduction(max : max2)
    {
        const long t = omp_get_thread_num(), threads = omp_get_num_threads();
        max2 = kick_drift_range(p, gravity, h, dt, n * t / threads, n * (t + 1) / threads);
    }
    return max2;
}

/// Kick, rotation and drift of rod-scene particle i; returns its largest squared tip
/// displacement since the lists were built.
static double kick_drift_rod(bdl_particles *p, long i, bdl_vec3 gravity, double h, double dt)
{
    const bdl_wrench load = p->load[i];
    const bdl_vec3 g = p->fluid_accel ? bdl_v3_add(gravity, p->fluid_accel[i]) : gravity;
    bdl_vec3 v = bdl_v3_madd(bdl_v3_madd(p->vel[i], g, h), load.force, h * p->inv_mass[i]);
    const bdl_vec3 L = bdl_v3_madd(p->ang_mom[i], load.torque, h);
    p->vel[i] = v;
    p->ang_mom[i] = L;
    const bdl_vec3 inv = p->inv_inertia[i];
    bdl_particle_set_orient(
        p, i, bdl_rigid_rotate_axisymmetric(p->orient[i], p->axis[i], L, inv.x, inv.z, dt));
    p->omega[i] = bdl_particle_omega(p, i, L);
    p->load[i] = (bdl_wrench){bdl_v3_zero(), bdl_v3_zero()}; // for the force pass
    p->pos[i] = bdl_v3_madd(p->pos[i], v, dt);
    return bdl_particle_move2(p, i);
}

double bdl_dem_kick_drift_rods(bdl_particles *p, bdl_vec3 gravity, double h, double dt)
{
    const long n = p->count;
    double max2 = 0.0;
    if (n < BDL_PARALLEL_MIN) {
        for (long i = 0; i < n; ++i)
            max2 = fmax(max2, kick_drift_rod(p, i, gravity, h, dt));
        return max2;
    }
#pragma omp parallel for schedule(static) reduction(max : max2)
    for (long i = 0; i < n; ++i) {
        const double d2 = kick_drift_rod(p, i, gravity, h, dt);
        if (d2 > max2)
            max2 = d2;
    }
    return max2;
}

/// Where contact k of particle i touches its wall (the middle of the overlap; with rods where
/// the force pass puts it).
static bdl_vec3 wall_contact_point(const bdl_particles *p, const bdl_walls *walls, long i, int prim)
{
    if (p->rods) {
        bdl_rod_contact rc;
        return bdl_rod_wall_contact_of(p, walls, i, prim, &rc) ? bdl_v3_add(p->pos[i], rc.arm_i)
                                                               : p->pos[i];
    }
    bdl_vec3 n;
    const double gap = bdl_wall_gap(walls, prim, p->pos[i], p->radius[i], &n);
    return bdl_v3_madd(p->pos[i], n, -(p->radius[i] + 0.5 * gap));
}

double bdl_dem_wall_power(const bdl_particles *p, const bdl_neighbor *nb, const bdl_walls *walls)
{
    int moving = 0;
    for (int w = 0; w < walls->wall_count; ++w)
        moving |= walls->motion[w] != BDL_MOTION_NONE;
    if (!moving || !nb->wall_start)
        return 0.0;
    // Serial in list order: the result is the same for any thread count.
    double power = 0.0;
    for (long i = 0; i < p->count; ++i)
        for (int32_t k = nb->wall_start[i]; k < nb->wall_start[i + 1]; ++k) {
            if (!nb->wall_touching[k])
                continue;
            const int prim = nb->wall_prim[k], wall = bdl_wall_of(walls, prim);
            const bdl_vec3 v =
                walls->motion[wall] == BDL_MOTION_ROTATE
                    ? bdl_wall_velocity_at(walls, wall, wall_contact_point(p, walls, i, prim))
                    : walls->velocity[wall];
            power += bdl_v3_dot(nb->wall_force[k], v);
        }
    return power;
}
