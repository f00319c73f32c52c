// bedlam — contact quantities of the world read outside the force pass (diagnostics, contact
// files): a contact's normal force as the law gives it now, and which way is up.
#include "dem/contact_law.h"
#include "world/world.h"

int bdl_world_vertical_axis(const bdl_world *w, double *up)
{
    const int axis = bdl_v3_major_axis(w->scene.gravity);
    *up = bdl_v3_comp(w->scene.gravity, axis) > 0.0 ? -1.0 : 1.0;
    return axis;
}

double bdl_world_pair_normal_force(const bdl_world *w, long i, long j, bdl_vec3 d, double dist)
{
    const bdl_particles *p = &w->particles;
    const double cut = p->radius[i] + p->radius[j];
    bdl_contact_geom g = {
        .n = bdl_v3_scale(d, 1.0 / dist),
        .overlap = cut - dist,
        .v_c = bdl_v3_sub(p->vel[i], p->vel[j]), // the spins add nothing along n
        .m_eff = 1.0 / (p->inv_mass[i] + p->inv_mass[j]),
        .r_eff = p->radius[i] * p->radius[j] / cut,
    };
    const int ns = w->scene.species_count;
    const bdl_contact_params *cp = &w->pair_params[p->species[i] * ns + p->species[j]];
    return bdl_contact_eval(cp, w->hertz, 0, g, bdl_v3_zero(), w->dt).normal;
}

double bdl_world_wall_normal_force(const bdl_world *w, long i, int prim, bdl_vec3 n, double gap)
{
    const bdl_particles *p = &w->particles;
    const int wall = w->walls.prims[prim].wall;
    bdl_contact_geom g = {
        .n = n,
        .overlap = -gap,
        .v_c = bdl_v3_sub(p->vel[i], w->walls.velocity[wall]),
        .m_eff = 1.0 / p->inv_mass[i],
        .r_eff = bdl_wall_r_eff(&w->walls, prim, p->radius[i]),
    };
    const bdl_contact_params *cp = &w->wall_params[wall * w->scene.species_count + p->species[i]];
    return bdl_contact_eval(cp, w->hertz, 0, g, bdl_v3_zero(), w->dt).normal;
}
