// bedlam — particles between MPI ranks: ownership, migration, ghosts (builds with MPI only).
//
// Each rank keeps the particles it owns (their centres in its box, dist/decomp.h) in slots
// [0, owned) of its bdl_particles, and copies of its neighbours' particles within the margin of
// its box (ghosts) in the slots after them, [owned, owned + ghosts): p->count is `owned`
// between steps, so that everything that walks the particles (integration, energies, outputs)
// sees only this rank's; the force pass alone runs over both (p->count raised to the sum).
//
// At a rebuild of the neighbour lists (every rank rebuilds when any needs to, so the ranks keep
// in step), particles whose centres left the box move to the rank that owns them now, with every
// per-particle array the table in dem/particles.c lists and the springs of their touching
// contacts. Then each rank sorts its own, sends copies of those near its faces to the ranks
// across them (at their images across a period), and builds its lists over its own particles and
// the ghosts. A pair of two ghosts is listed too: its spring evolves on every rank that holds both
// exactly as on the owner's, from the rebuild where both came into the margin — but if they came
// in touching, that copy began late, which is why a particle that moves over brings its springs
// (they replace the copies). Springs are found again by the particles' stable ids.
//
// Between rebuilds the set of ghosts is fixed; after the opening kick and drift of each step
// their positions, velocities and spins are sent again (bdl_dist_refresh). Forces on ghosts
// are computed and thrown away: each rank's own particles get the whole of theirs.
//
// The exchanges use MPI_Alltoall(v) over all ranks: simple and exact, but its cost grows with
// the rank count (docs/parallel.md).
#ifndef BDL_EXCHANGE_H
#define BDL_EXCHANGE_H

#include <stdint.h>

#include "core/error.h"
#include "dem/neighbor.h"
#include "dem/particles.h"
#include "dem/walls.h"
#include "dist/decomp.h"

typedef struct bdl_dist bdl_dist;

/// This rank's part in the division `d`. BDL_ERR_NOMEM, or BDL_ERR_ARGS in a build without MPI.
bdl_result bdl_dist_create(const bdl_decomp *d, bdl_dist **out);
void bdl_dist_destroy(bdl_dist *dd);

const bdl_decomp *bdl_dist_decomp(const bdl_dist *dd);
long bdl_dist_owned(const bdl_dist *dd);
long bdl_dist_ghosts(const bdl_dist *dd);
long bdl_dist_migrated(const bdl_dist *dd); ///< particles this rank sent away, since the start
long bdl_dist_rebuilds(const bdl_dist *dd);

/// Collective, at the start of a run: every rank holds all p->count particles, with lists built
/// for them (their contact history). Each keeps those in its box, takes its ghosts and builds
/// its lists; p->count becomes `owned`.
bdl_result bdl_dist_start(bdl_dist *dd, bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls);

/// Collective: 1 when `mine` is 1 on any rank.
int bdl_dist_any(int mine);

/// Collective: migration, new ghosts and new lists (see above). p->count is `owned` before and
/// after.
bdl_result bdl_dist_rebuild(bdl_dist *dd, bdl_particles *p, bdl_neighbor *nb,
                            const bdl_walls *walls);

/// Removes the own particles with drop[i] set (p->count becomes the new `owned`); the lists are
/// then stale: the next force pass must rebuild them (a max_move2 of infinity does).
bdl_result bdl_dist_remove(bdl_dist *dd, bdl_particles *p, const uint8_t *drop);

/// Collective: the ghosts' positions, velocities and spins from their owners.
bdl_result bdl_dist_refresh(bdl_dist *dd, bdl_particles *p);

/// Every rank's particles, on one rank, in the order of their ids.
typedef struct bdl_dist_gathered {
    long count;
    uint32_t *id;
    bdl_vec3 *pos, *vel, *omega;
} bdl_dist_gathered;

/// Collective: every rank's own particles, whole (every array of the table) and in the order
/// of their ids, into `out` on rank `root` (its count set; reserved as needed), with their
/// `coordination` (one byte each, local order) into `coordination_out` (room for them all).
bdl_result bdl_dist_gather_whole(const bdl_particles *p, const uint8_t *coordination, int root,
                                 bdl_particles *out, uint8_t *coordination_out);

/// A contact's spring: between the particles of ids a < b (u as seen from a), or, with wall >= 0,
/// between particle a and that wall primitive.
typedef struct bdl_dist_spring {
    uint32_t a, b;
    int32_t wall;
    int32_t pad;
    bdl_vec3 u;
    double work; ///< the work it holds (Hertz-Mindlin)
} bdl_dist_spring;

/// Collective: the springs of every touching contact of every rank's own particles (each once)
/// on rank `root`, sorted by (a, b, wall); *out is malloc'ed there (NULL elsewhere).
bdl_result bdl_dist_gather_springs(const bdl_neighbor *nb, const bdl_particles *p, long owned,
                                   int root, bdl_dist_spring **out, long *count);

/// Orders springs by (a, b, wall), for bsearch.
int bdl_dist_spring_order(const void *x, const void *y);

/// Collective: the owned particles of every rank on rank `root` (out->count 0 elsewhere).
bdl_result bdl_dist_gather(const bdl_particles *p, int root, bdl_dist_gathered *out);
void bdl_dist_gathered_free(bdl_dist_gathered *g);

#endif
