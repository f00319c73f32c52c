// bedlam — particle storage: a permutation moves every per-particle quantity with its particle,
// force and torque (stored side by side in one record) and the gas's arrays included; a new
// particle starts at rest with no load; the byte count covers every array.
#include "check.h"
#include "dem/particles.h"

#include <stdlib.h>

int main(void)
{
    enum { N = 7 };
    bdl_particles p = {0};
    p.fluid = 1;
    CHECK(bdl_particles_reserve(&p, N) == BDL_OK);
    for (int k = 0; k < N; ++k) {
        bdl_particles_add(&p, bdl_v3(k, 10 + k, 20 + k), bdl_v3(-k, 0, 0), 0.001 * (k + 1), 1000.0,
                          k % 3);
        CHECK(p.omega[k].x == 0 && p.omega[k].y == 0 && p.omega[k].z == 0);
        CHECK(p.load[k].force.x == 0 && p.load[k].torque.z == 0);
        CHECK(p.fluid_accel[k].y == 0 && p.drag_accel[k].z == 0 && p.vel_mark[k].x == -k);
        p.omega[k] = bdl_v3(0, k, 0);
        p.load[k] = (bdl_wrench){bdl_v3(100 + k, 0, 1), bdl_v3(0, 200 + k, 2)};
        p.fluid_accel[k] = bdl_v3(0, 0, 300 + k);
        p.drag_accel[k] = bdl_v3(400 + k, 0, 0);
    }
    // pos, vel, omega, pos_at_build, the gas's three: vectors; load: two; radius and inverse
    // mass; species and id.
    const long per_particle = 7 * sizeof(bdl_vec3) + sizeof(bdl_wrench) + 2 * sizeof(double) +
                              sizeof(int32_t) + sizeof(uint32_t);
    CHECK(bdl_particles_bytes(&p) == N * per_particle);
    const int32_t perm[N] = {3, 6, 0, 5, 1, 4, 2}; // new slot k holds old particle perm[k]
    void *scratch = malloc(N * sizeof(bdl_vec3));
    bdl_particles_permute(&p, perm, scratch);
    for (int k = 0; k < N; ++k) {
        int old = perm[k];
        CHECK(p.id[k] == (uint32_t)old);
        CHECK(p.pos[k].x == old && p.pos[k].y == 10 + old && p.pos[k].z == 20 + old);
        CHECK(p.vel[k].x == -old);
        CHECK(p.omega[k].y == old);
        CHECK(p.species[k] == old % 3);
        CHECK(p.radius[k] == 0.001 * (old + 1));
        CHECK(p.load[k].force.x == 100 + old && p.load[k].force.z == 1);
        CHECK(p.load[k].torque.y == 200 + old && p.load[k].torque.z == 2);
        CHECK(p.fluid_accel[k].z == 300 + old && p.drag_accel[k].x == 400 + old);
        CHECK(p.vel_mark[k].x == -old);
    }
    free(scratch);
    bdl_particles_free(&p);
    return bdl_test_summary("test_particles");
}
