// DEM divided between MPI ranks (dist/exchange.h) against the same scene whole on one rank: run
// under mpirun with 1, 2 and 4 ranks (tests/mpi.cmake), every rank also runs the whole scene as
// the reference: a periodic bed, a closed box, particles leaving through a face, a layer sliding
// through the borders with lasting contacts, a vibrating container, a turning drum and a
// fluidized bed. After the steps rank 0 gathers the particles: none lost or
// duplicated (the ids one by one), the same positions within 1e-10 of the box and velocities within
// 1e-8 of their scale. Frictional contacts slide across the borders, so a contact history lost or
// turned the wrong way at a migration shows at once (a force off by its tangential part).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "core/comm.h"
#include "dist/exchange.h"
#include "scene/scene.h"
#include "world/world.h"

static int rank;

/// The largest difference of two states, sorted by id (the whole one is sorted here).
static void compare(const char *path, bdl_world *whole, const bdl_dist_gathered *g, long steps)
{
    const bdl_particles *p = &whole->particles;
    CHECK_MSG(g->count == p->count, "%s: %ld particles divided, %ld whole", path, g->count,
              p->count);
    if (p->count < whole->particles.capacity && whole->removed > 0)
        printf("%s: %ld particles left the box (whole run)\n", path, whole->removed);
    // The whole world's particles by id (ids below next_id, each once; some may have left).
    const long ids = (long)p->next_id;
    long *at = malloc((size_t)(ids > 0 ? ids : 1) * sizeof *at);
    for (long i = 0; i < ids; ++i)
        at[i] = -1;
    for (long i = 0; i < p->count; ++i)
        if (p->id[i] < (uint32_t)ids)
            at[p->id[i]] = i;
    const bdl_vec3 box = bdl_v3_sub(whole->scene.domain_max, whole->scene.domain_min);
    const double size = fmax(box.x, fmax(box.y, box.z));
    double dx = 0.0, dv = 0.0, vmax = 0.0;
    int same_ids = 1;
    for (long k = 0; k < g->count && g->count == p->count; ++k) {
        if (g->id[k] >= (uint32_t)ids || at[g->id[k]] < 0 || (k > 0 && g->id[k] <= g->id[k - 1])) {
            same_ids = 0;
            continue;
        }
        const long i = at[g->id[k]];
        bdl_vec3 d = bdl_v3_sub(g->pos[k], p->pos[i]);
        // A period apart is the same place.
        for (int a = 0; a < 3; ++a)
            if (whole->scene.periodic[a]) {
                const double len = bdl_v3_comp(box, a), c = bdl_v3_comp(d, a);
                bdl_v3_set_comp(&d, a, c - len * round(c / len));
            }
        dx = fmax(dx, bdl_v3_len(d) / size);
        dv = fmax(dv, bdl_v3_len(bdl_v3_sub(g->vel[k], p->vel[i])));
        vmax = fmax(vmax, bdl_v3_len(p->vel[i]));
    }
    CHECK_MSG(same_ids, "%s: the ids are not each particle once", path);
    printf("%s, %ld steps on %d ranks: positions within %.1e of the box, velocities within %.1e "
           "m/s (largest speed %.2f m/s)\n",
           path, steps, bdl_comm_size(), dx, dv, vmax);
    CHECK_MSG(dx < 1e-10, "%s: positions differ by %g of the box", path, dx);
    CHECK_MSG(dv < 1e-8 * fmax(vmax, 1.0), "%s: velocities differ by %g m/s", path, dv);
    free(at);
}

static void run_case(const char *path, long steps, int moves)
{
    static bdl_scene scene;
    static bdl_scene_error err;
    CHECK(bdl_scene_load(path, NULL, 0, &scene, &err) == BDL_OK);
    bdl_world *whole = NULL, *divided = NULL;
    CHECK_MSG(bdl_world_create_whole(&scene, &whole, &err) == BDL_OK, "%s", err.message);
    CHECK_MSG(bdl_world_create(&scene, &divided, &err) == BDL_OK, "%s", err.message);
    if (!whole || !divided)
        return;
    for (long s = 0; s < steps; ++s) {
        CHECK(bdl_world_step(whole) == BDL_OK);
        CHECK(bdl_world_step(divided) == BDL_OK);
    }
    // The load of each rank, and what moved between them.
    double counts[2] = {(double)divided->particles.count,
                        divided->dist ? (double)bdl_dist_migrated(divided->dist) : 0.0};
    const double most = bdl_comm_max(counts[0]);
    bdl_comm_sum(counts, 2);
    if (rank == 0 && divided->dist)
        printf("%s: particles per rank %.0f at most, %.1f on average (max/mean %.2f); %.0f "
               "moved between ranks; %ld rebuilds\n",
               path, most, counts[0] / bdl_comm_size(), most / (counts[0] / bdl_comm_size()),
               counts[1], bdl_dist_rebuilds(divided->dist));
    bdl_dist_gathered g;
    if (divided->dist) {
        CHECK(bdl_dist_gather(&divided->particles, 0, &g) == BDL_OK);
        if (rank == 0) {
            CHECK(!moves || counts[1] > 0.0); // the case moved particles across borders
            compare(path, whole, &g, steps);
        }
        bdl_dist_gathered_free(&g);
    }
    // The whole state on rank 0 (what a checkpoint of a divided run holds), then it stepped
    // whole beside the divided run: the same continuation, so the springs (and with a gas its
    // fields) came over with the particles.
    bdl_world *mirror = NULL;
    if (rank == 0)
        CHECK(bdl_world_create_whole(&scene, &mirror, &err) == BDL_OK);
    if (divided->dist) {
        CHECK(bdl_world_dist_mirror(divided, mirror, 0) == BDL_OK);
        for (long s = 0; s < steps / 2; ++s) {
            CHECK(bdl_world_step(divided) == BDL_OK);
            if (mirror)
                CHECK(bdl_world_step(mirror) == BDL_OK);
        }
        CHECK(bdl_dist_gather(&divided->particles, 0, &g) == BDL_OK);
        if (rank == 0 && mirror) {
            printf("continued whole from the gathered state: ");
            compare(path, mirror, &g, steps / 2);
        }
        bdl_dist_gathered_free(&g);
    }
    bdl_world_destroy(mirror);
    bdl_world_destroy(whole);
    bdl_world_destroy(divided);
}

int main(int argc, char **argv)
{
    bdl_comm_init(&argc, &argv);
    rank = bdl_comm_rank();
    run_case("scenes/mpi_periodic_bed.ini", 1000, 1);
    run_case("scenes/mpi_closed_gas.ini", 1000, 1);
    run_case("scenes/mpi_outflow.ini", 1000, 1); // particles removed on the rank that owns them
    // Lasting contacts crossing the borders: springs that must come with their particles.
    run_case("scenes/mpi_sliding_layer.ini", 1000, 1);
    // Walls that move: a vibrating container, a turning cylinder (slow: few cross in 1000 steps).
    run_case("../scenes/vibrated_bed.ini", 1000, 0);
    run_case("../scenes/rotating_drum.ini", 1000, 0);
    // A gas (replicated on every rank, the particles' deposits summed over the ranks).
    run_case("../scenes/fluidized_bed.ini", 1000, 0);
    // Every rank's checks count: the exit code is the worst.
    double failed = bdl_test_failures;
    failed = bdl_comm_max(failed);
    bdl_test_failures = (int)failed;
    const int code = rank == 0 ? bdl_test_summary("test_mpi_dem") : (failed > 0.0);
    bdl_comm_finalize();
    return code;
}
