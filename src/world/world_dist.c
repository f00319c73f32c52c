// The world on MPI ranks: which scenes can be shared, the division of the box, and the lists
// before each force pass (dist/exchange.h).
#include "world/world.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cfd/gas.h"
#include "couple/coupling.h"

#include "core/comm.h"
#include "core/memory.h"
#include "dist/exchange.h"

/// What a scene has that the ranks cannot share yet; NULL when nothing.
static const char *unshared(const bdl_world *w)
{
    const bdl_scene *s = &w->scene;
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

/// Each particle's touching pairs, from the lists as the division left them (the force pass
/// counts them every step; the particles moved since the last one).
static bdl_result recount_contacts(bdl_world *w)
{
    const bdl_neighbor *nb = &w->neighbor;
    if (w->coordination_capacity < w->particles.capacity) {
        if (!bdl_grow((void **)&w->coordination, w->particles.capacity, 1))
            return BDL_ERR_NOMEM;
        w->coordination_capacity = w->particles.capacity;
    }
    memset(w->coordination, 0, (size_t)w->coordination_capacity);
    for (long i = 0; i < nb->count; ++i)
        for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k)
            if (nb->touching[k]) {
                uint8_t *a = &w->coordination[i], *b = &w->coordination[nb->partner[k]];
                *a = (uint8_t)(*a < 255 ? *a + 1 : 255);
                *b = (uint8_t)(*b < 255 ? *b + 1 : 255);
            }
    return BDL_OK;
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
    // What the world booked so far (a resumed run's) is the first rank's: the ranks' sums.
    if (bdl_comm_rank() > 0) {
        w->wall_work = w->damping_work = w->inserted_energy = w->removed_energy = 0.0;
        w->removed = 0;
        w->removed_mass = 0.0;
        w->neighbor.spring_work_left = 0;
        w->gas_work = 0.0;
        w->particle_drag[0] = w->particle_drag[1] = w->particle_drag[2] = 0.0;
    }
    bdl_decomp d;
    bdl_decomp_init(&d, bdl_comm_rank(), dims, lo, hi, s->periodic, margin);
    if (w->coupling) // the gas is replicated: each rank's deposits are summed over the ranks
        w->coupling->divided = 1;
    bdl_result r = bdl_dist_create(&d, &w->dist);
    if (r == BDL_OK)
        r = bdl_dist_start(w->dist, &w->particles, &w->neighbor, &w->walls);
    if (r == BDL_OK)
        r = recount_contacts(w);
    return r;
}

bdl_result bdl_world_dist_agree(bdl_world *w, bdl_result r)
{
    const bdl_result all = (bdl_result)(int)bdl_comm_max((double)r);
    if (all != BDL_OK && r == BDL_OK)
        snprintf(w->failure, sizeof w->failure,
                 "a step failed on another rank at t = %.6g s (step %ld): %s", w->time, w->step,
                 bdl_result_text(all));
    return all;
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

/// The springs gathered from the ranks given to the mirror's lists (built just now): each listed
/// pair and wall contact that touches on its rank gets its history.
static void restore_springs(bdl_world *m, const bdl_dist_spring *springs, long count)
{
    bdl_neighbor *nb = &m->neighbor;
    const bdl_particles *p = &m->particles;
    if (!nb->history)
        return;
    for (long i = 0; i < nb->count; ++i) {
        for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k) {
            const uint32_t a = p->id[i], b = p->id[nb->partner[k]];
            const bdl_dist_spring key = {a < b ? a : b, a < b ? b : a, -1, 0, {0, 0, 0}, 0.0};
            const bdl_dist_spring *s =
                bsearch(&key, springs, (size_t)count, sizeof *springs, bdl_dist_spring_order);
            nb->touching[k] = s != NULL;
            nb->history[k] = !s ? bdl_v3_zero() : a < b ? s->u : bdl_v3_neg(s->u);
            if (nb->spring_work)
                nb->spring_work[k] = s ? s->work : 0.0;
        }
        for (int32_t k = nb->wall_start[i]; k < nb->wall_start[i + 1]; ++k) {
            const bdl_dist_spring key = {p->id[i], 0, nb->wall_prim[k], 0, {0, 0, 0}, 0.0};
            const bdl_dist_spring *s =
                bsearch(&key, springs, (size_t)count, sizeof *springs, bdl_dist_spring_order);
            nb->wall_touching[k] = s != NULL;
            nb->wall_history[k] = s ? s->u : bdl_v3_zero();
            if (nb->wall_spring_work)
                nb->wall_spring_work[k] = s ? s->work : 0.0;
        }
    }
}

/// The gas's state and schedule, the same on every rank, into the mirror.
static void mirror_gas(const bdl_world *w, bdl_world *m)
{
    const bdl_gas *g = w->gas;
    bdl_gas *h = m->gas;
    const size_t cells = (size_t)g->grid.size * sizeof(double);
    m->gas_every = w->gas_every;
    m->gas_next = w->gas_next;
    m->gas_steps = w->gas_steps;
    m->gas_stable = w->gas_stable;
    m->gas_inflow_raised = w->gas_inflow_raised;
    memcpy(m->gas_drag, w->gas_drag, sizeof m->gas_drag);
    h->time = g->time;
    h->steps = g->steps;
    h->last_solve = g->last_solve;
    h->mass_imbalance = g->mass_imbalance;
    for (int a = 0; a < 3; ++a)
        memcpy(h->u[a], g->u[a], cells);
    memcpy(h->p, g->p, cells);
    memcpy(h->eps, g->eps, cells);
    memcpy(h->eps_old, g->eps_old, cells);
}

/// Collective: the mirror's clock, walls and the energy it books, from the divided world (the
/// sums over the ranks); m is NULL but on the mirror's rank.
static void mirror_counters(const bdl_world *w, bdl_world *m)
{
    double sums[10] = {w->wall_work,       w->damping_work,     w->inserted_energy,
                       w->removed_energy,  (double)w->removed,  w->removed_mass,
                       w->gas_work,        w->particle_drag[0], w->particle_drag[1],
                       w->particle_drag[2]};
    bdl_comm_sum(sums, 10);
    const bdl_exact_sum left = bdl_comm_sum_exact(w->neighbor.spring_work_left);
    if (!m)
        return;
    m->neighbor.spring_work_left = left;
    m->wall_work = sums[0];
    m->damping_work = sums[1];
    m->inserted_energy = sums[2];
    m->removed_energy = sums[3];
    m->removed = (long)sums[4];
    m->removed_mass = sums[5];
    m->gas_work = sums[6];
    for (int a = 0; a < 3; ++a)
        m->particle_drag[a] = sums[7 + a];
    if (w->gas && m->gas) // the gas, the same on every rank
        mirror_gas(w, m);
    m->time = w->time;
    m->step = w->step;
    m->dt = w->dt;
    m->live = w->live;
    for (int k = 0; k < BDL_MAX_WALLS; ++k) {
        m->walls.angle[k] = w->walls.angle[k];
        m->walls.turned[k] = w->walls.turned[k];
        m->walls.spin[k] = w->walls.spin[k];
    }
    bdl_walls_update(&m->walls, m->time);
}

bdl_result bdl_world_dist_mirror(bdl_world *w, bdl_world *mirror, int root)
{
    const int here = bdl_comm_rank() == root;
    bdl_particles *mp = here ? &mirror->particles : NULL;
    uint8_t *coordination = NULL;
    double total = (double)w->particles.count; // what the first rank will hold
    bdl_comm_sum(&total, 1);
    if (here && !(coordination = malloc((size_t)total + 1)))
        bdl_comm_abort("out of memory for the whole state on the first rank");
    bdl_result r = bdl_dist_gather_whole(&w->particles, w->coordination, root, mp, coordination);
    bdl_dist_spring *springs = NULL;
    long count = 0;
    if (r == BDL_OK)
        r = bdl_dist_gather_springs(&w->neighbor, &w->particles, bdl_dist_owned(w->dist), root,
                                    &springs, &count);
    mirror_counters(w, here ? mirror : NULL);
    if (r == BDL_OK && here) {
        // Lists for the state (the pairs' springs restored), the coordination in their order.
        r = bdl_neighbor_build(&mirror->neighbor, mp, &mirror->walls, NULL);
        if (r == BDL_OK && mirror->coordination_capacity >= mp->count)
            for (long i = 0; i < mp->count; ++i)
                mirror->coordination[i] = coordination[mirror->neighbor.perm[i]];
        if (r == BDL_OK)
            restore_springs(mirror, springs, count);
    }
    free(springs);
    free(coordination);
    return r;
}
