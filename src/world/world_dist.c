// The world on MPI ranks: which scenes can be shared, the division of the box, and the lists
// before each force pass (dist/exchange.h).
#include "world/world.h"

#include <stdio.h>

#include "core/comm.h"
#include "dist/exchange.h"

/// What a scene has that the ranks cannot share yet; NULL when nothing.
static const char *unshared(const bdl_world *w)
{
    const bdl_scene *s = &w->scene;
    if (s->gas.enabled)
        return "a gas ([gas]): the gas grid is not divided between ranks yet";
    if (s->parcels.enabled || s->solids.enabled || w->particles.parcels)
        return "parcels or a solids phase: only DEM particles are divided between ranks yet";
    if (w->particles.rods)
        return "rods: only spheres are divided between ranks yet";
    if (s->shear_rate != 0.0)
        return "Lees-Edwards boundaries ([domain] shear_rate)";
    for (int c = 0; c < s->create_count; ++c)
        if (s->creates[c].kind == BDL_CREATE_POUR)
            return "pouring ([create] type = pour): particles added during a run";
    return NULL;
}

bdl_result bdl_world_dist_init(bdl_world *w, bdl_scene_error *err)
{
    const bdl_scene *s = &w->scene;
    const int size = bdl_comm_size();
    const char *why = unshared(w);
    if (why) {
        snprintf(err->message, sizeof err->message,
                 "%s: this scene cannot be divided between %d MPI ranks: it has %s (run it on "
                 "one rank)",
                 s->path, size, why);
        return BDL_ERR_SCENE;
    }
    // Every pair a rank's particles can reach before the next rebuild, and a skin more: the
    // partners of a particle that moves over are there already, with their history.
    double skin;
    const double margin = bdl_world_contact_reach(s, &skin) + skin;
    const double lo[3] = {s->domain_min.x, s->domain_min.y, s->domain_min.z};
    const double hi[3] = {s->domain_max.x, s->domain_max.y, s->domain_max.z};
    int dims[3] = {(int)s->decomposition.x, (int)s->decomposition.y, (int)s->decomposition.z};
    const int given = dims[0] + dims[1] + dims[2] > 0;
    if (given && (dims[0] * dims[1] * dims[2] != size || dims[0] != s->decomposition.x ||
                  dims[1] != s->decomposition.y || dims[2] != s->decomposition.z)) {
        snprintf(err->message, sizeof err->message,
                 "%s: [parallel] decomposition = %g %g %g: whole numbers whose product is the "
                 "rank count, %d (or 0 0 0: automatic)",
                 s->path, s->decomposition.x, s->decomposition.y, s->decomposition.z, size);
        return BDL_ERR_SCENE;
    }
    const bdl_particles *p = &w->particles;
    if (given ? !bdl_decomp_fits(dims, lo, hi, margin)
              : !bdl_decomp_choose(size, lo, hi, s->periodic, margin, p->pos, p->count, dims)) {
        snprintf(err->message, sizeof err->message,
                 "%s: the domain cannot be cut into %d boxes%s each at least 2 x %g m (twice the "
                 "ghost margin: the largest particle and two skins) wide: use fewer ranks",
                 s->path, size, given ? " as [parallel] decomposition asks" : "", margin);
        return BDL_ERR_SCENE;
    }
    bdl_decomp d;
    bdl_decomp_init(&d, bdl_comm_rank(), dims, lo, hi, s->periodic, margin);
    bdl_result r = bdl_dist_create(&d, &w->dist);
    if (r == BDL_OK)
        r = bdl_dist_start(w->dist, &w->particles, &w->neighbor, &w->walls);
    return r;
}

bdl_result bdl_world_dist_lists(bdl_world *w, double max_move2)
{
    bdl_particles *p = &w->particles;
    bdl_result r = bdl_dist_refresh(w->dist, p);
    if (r != BDL_OK)
        return r;
    p->count += bdl_dist_ghosts(w->dist);
    const int mine = bdl_neighbor_needs_build(&w->neighbor, p, &w->walls, max_move2);
    p->count = bdl_dist_owned(w->dist);
    if (bdl_dist_any(mine))
        r = bdl_dist_rebuild(w->dist, p, &w->neighbor, &w->walls);
    return r;
}
