// bedlam — contact quantities of the world read outside the force pass (diagnostics, contact
// files): a contact's normal force as the law gives it now, and which way is up.
#include "dem/contact_law.h"
#include "dem/rod_force.h"
#include "world/world.h"

int bdl_world_vertical_axis(const bdl_world *w, double *up)
{
    const int axis = bdl_v3_major_axis(w->scene.gravity);
    *up = bdl_v3_comp(w->scene.gravity, axis) > 0.0 ? -1.0 : 1.0;
    return axis;
}

/// The normal force of the law for a contact of geometry g and parameters cp (no history).
static double normal_force(const bdl_world *w, const bdl_contact_params *cp, bdl_contact_geom g)
{
    const bdl_spring none = {bdl_v3_zero(), 0.0};
    return bdl_contact_eval(cp, w->hertz, 0, g, none, w->dt).normal;
}

/// Spheres: the centres' separation, and the relative velocity of the centres (the spins add
/// nothing along the normal).
static int sphere_pair(const bdl_world *w, long i, long j, bdl_world_contact *c)
{
    const bdl_particles *p = &w->particles;
    const bdl_vec3 d = bdl_neighbor_delta(&w->neighbor, p->pos[i], p->pos[j]);
    const double cut = p->radius[i] + p->radius[j], dist = bdl_v3_len(d);
    if (dist >= cut || dist <= 0.0)
        return 0;
    c->overlap = cut - dist;
    c->n = bdl_v3_scale(d, 1.0 / dist);
    c->r_eff = p->radius[i] * p->radius[j] / cut;
    c->point = bdl_v3_madd(p->pos[i], c->n, -(p->radius[i] - 0.5 * c->overlap));
    c->v_c = bdl_v3_sub(bdl_v3_sub(p->vel[i], p->vel[j]),
                        bdl_neighbor_image_velocity(&w->neighbor, p->pos[i], p->pos[j]));
    return 1;
}

/// Rods: the shafts' closest points (as the force pass finds them), the velocity of the contact
/// point with the spins.
static int rod_pair(const bdl_world *w, long i, long j, bdl_world_contact *c)
{
    const bdl_particles *p = &w->particles;
    bdl_rod_contact rc;
    if (!bdl_rod_contact_of(p, &w->neighbor, i, j, &rc))
        return 0;
    c->overlap = rc.overlap;
    c->n = rc.n;
    c->r_eff = p->radius[i] * p->radius[j] / (p->radius[i] + p->radius[j]);
    c->point = bdl_v3_add(p->pos[i], rc.arm_i);
    const bdl_vec3 vj =
        bdl_v3_add(p->vel[j], bdl_neighbor_image_velocity(&w->neighbor, p->pos[i], p->pos[j]));
    c->v_c = bdl_v3_sub(bdl_v3_add(p->vel[i], bdl_v3_cross(p->omega[i], rc.arm_i)),
                        bdl_v3_add(vj, bdl_v3_cross(p->omega[j], rc.arm_j)));
    c->arm_j = rc.arm_j;
    return 1;
}

/// The contact law's input for the touching pair (i, j) of contact c.
static bdl_contact_geom pair_geom(const bdl_world *w, long i, long j, const bdl_world_contact *c)
{
    const bdl_particles *p = &w->particles;
    const double inv_m = p->rods
                             ? bdl_rod_inv_mass_at(p, i, bdl_v3_sub(c->point, p->pos[i]), c->n) +
                                   bdl_rod_inv_mass_at(p, j, c->arm_j, c->n)
                             : p->inv_mass[i] + p->inv_mass[j];
    return (bdl_contact_geom){
        .n = c->n, .overlap = c->overlap, .v_c = c->v_c, .m_eff = 1.0 / inv_m, .r_eff = c->r_eff};
}

static const bdl_contact_params *pair_params(const bdl_world *w, long i, long j)
{
    const int32_t *species = w->particles.species;
    return &w->pair_params[species[i] * w->scene.species_count + species[j]];
}

int bdl_world_pair_contact(const bdl_world *w, long i, long j, bdl_world_contact *c)
{
    const bdl_particles *p = &w->particles;
    if (!(p->rods ? rod_pair(w, i, j, c) : sphere_pair(w, i, j, c)))
        return 0;
    c->normal = normal_force(w, pair_params(w, i, j), pair_geom(w, i, j, c));
    c->prim = -1;
    return 1;
}

bdl_vec3 bdl_world_pair_force(const bdl_world *w, long i, int32_t k)
{
    const bdl_particles *p = &w->particles;
    const bdl_neighbor *nb = &w->neighbor;
    const long j = nb->partner[k];
    bdl_world_contact c;
    if (!(p->rods ? rod_pair(w, i, j, &c) : sphere_pair(w, i, j, &c)))
        return bdl_v3_zero();
    bdl_contact_geom g = pair_geom(w, i, j, &c);
    bdl_spring spring = {bdl_v3_zero(), 0.0};
    if (w->friction) {
        if (!p->rods) { // the spins' share of the contact point's velocity (rods have it already)
            const bdl_vec3 arm_i = bdl_v3_sub(c.point, p->pos[i]);
            const bdl_vec3 arm_j = bdl_v3_add(arm_i, bdl_neighbor_delta(nb, p->pos[i], p->pos[j]));
            g.v_c = bdl_v3_add(g.v_c, bdl_v3_sub(bdl_v3_cross(p->omega[i], arm_i),
                                                 bdl_v3_cross(p->omega[j], arm_j)));
        }
        spring = (bdl_spring){nb->history[k], nb->spring_work ? nb->spring_work[k] : 0.0};
    }
    return bdl_contact_eval(pair_params(w, i, j), w->hertz, w->friction, g, spring, w->dt).force;
}

/// Spheres: the wall's gap at the centre; the relative velocity of the centre.
static int sphere_wall(const bdl_world *w, long i, int32_t k, int prim, bdl_world_contact *c)
{
    const bdl_particles *p = &w->particles;
    const double r = p->radius[i];
    const double gap = bdl_wall_gap(&w->walls, prim, p->pos[i], r, &c->n);
    const bdl_neighbor *nb = &w->neighbor;
    if (gap >= 0.0 || !bdl_wall_tri_counted(&w->walls, nb->wall_prim + nb->wall_start[i],
                                            nb->wall_start[i + 1] - nb->wall_start[i],
                                            (int)(k - nb->wall_start[i]), p->pos[i], r))
        return 0;
    c->overlap = -gap;
    c->point = bdl_v3_madd(p->pos[i], c->n, -(r + 0.5 * gap));
    c->v_c = p->vel[i];
    return 1;
}

/// Rods: the stretch of the shaft beyond the wall (as the force pass finds it), the velocity of
/// the contact point with the spin.
static int rod_wall(const bdl_world *w, long i, int prim, bdl_world_contact *c)
{
    const bdl_particles *p = &w->particles;
    bdl_rod_contact rc;
    if (!bdl_rod_wall_contact_of(p, &w->walls, i, prim, &rc))
        return 0;
    c->overlap = rc.overlap;
    c->n = rc.n;
    c->point = bdl_v3_add(p->pos[i], rc.arm_i);
    c->v_c = bdl_v3_add(p->vel[i], bdl_v3_cross(p->omega[i], rc.arm_i));
    return 1;
}

int bdl_world_wall_contact(const bdl_world *w, long i, int32_t k, bdl_world_contact *c)
{
    const bdl_particles *p = &w->particles;
    const int prim = w->neighbor.wall_prim[k], wall = bdl_wall_of(&w->walls, prim);
    if (!(p->rods ? rod_wall(w, i, prim, c) : sphere_wall(w, i, k, prim, c)))
        return 0;
    c->r_eff = bdl_wall_r_eff(&w->walls, prim, p->radius[i]);
    c->v_c = bdl_v3_sub(c->v_c, bdl_wall_velocity_at(&w->walls, wall, c->point));
    const double m_eff =
        p->rods ? 1.0 / bdl_rod_inv_mass_at(p, i, bdl_v3_sub(c->point, p->pos[i]), c->n)
                : 1.0 / p->inv_mass[i];
    const bdl_contact_geom g = {
        .n = c->n, .overlap = c->overlap, .v_c = c->v_c, .m_eff = m_eff, .r_eff = c->r_eff};
    const int ns = w->scene.species_count;
    c->normal = normal_force(w, &w->wall_params[wall * ns + p->species[i]], g);
    c->prim = prim;
    return 1;
}
