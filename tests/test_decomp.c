// The division of the box between MPI ranks (dist/decomp.h), without MPI: every point has one
// owner and lies in its box; a particle near faces is sent to exactly the ranks across them, at
// its image across a period; the automatic choice balances particles and then cuts least.
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "dist/decomp.h"

static const double lo[3] = {0.0, 0.0, 0.0}, hi[3] = {0.03, 0.02, 0.06};

static int inside(const bdl_decomp *d, bdl_vec3 x)
{
    for (int a = 0; a < 3; ++a) {
        const double v = bdl_v3_comp(x, a);
        if (v < d->sub_lo[a] || v >= d->sub_hi[a])
            return 0;
    }
    return 1;
}

/// Owners: each point of a fine lattice (and points beyond the sides) in exactly one box.
static void owners(void)
{
    const int dims[3] = {3, 2, 2}, periodic[3] = {1, 0, 1};
    bdl_decomp d[12];
    for (int r = 0; r < 12; ++r)
        bdl_decomp_init(&d[r], r, dims, lo, hi, periodic, 0.003);
    int bad = 0;
    for (int k = -2; k < 62; ++k)
        for (int j = 0; j < 20; ++j)
            for (int i = -3; i < 33; ++i) {
                const bdl_vec3 x =
                    bdl_v3(0.001 * i + 0.0005, 0.001 * j + 0.0005, 0.001 * k + 0.0005);
                const int owner = bdl_decomp_owner(&d[0], x);
                const bdl_vec3 w = bdl_decomp_wrap(&d[0], x);
                int holders = 0;
                for (int r = 0; r < 12; ++r)
                    holders += inside(&d[r], w);
                bad += owner < 0 || owner >= 12 || holders != 1 || !inside(&d[owner], w);
            }
    CHECK_MSG(bad == 0, "%d points without exactly one owner", bad);
    // Wrapped: x just below 0 belongs to the last box along x.
    const int c = bdl_decomp_owner(&d[0], bdl_v3(-0.0001, 0.001, 0.001)) % 3;
    CHECK(c == 2);
}

/// Ghosts: the ranks a particle is copied to, and the shift of its image.
static void ghosts(void)
{
    const int dims[3] = {2, 1, 2}, periodic[3] = {1, 1, 0};
    bdl_decomp d;
    bdl_decomp_init(&d, 0, dims, lo, hi, periodic, 0.003); // box x [0, 0.015), z [0, 0.03)
    int ranks[BDL_DECOMP_MAX_TARGETS];
    bdl_vec3 shifts[BDL_DECOMP_MAX_TARGETS];
    // The middle of the box: nobody.
    CHECK(bdl_decomp_ghost_targets(&d, bdl_v3(0.007, 0.01, 0.015), ranks, shifts) == 0);
    // Near the low x face (periodic): rank 1 (x box 1), at its image x + 0.03.
    int n = bdl_decomp_ghost_targets(&d, bdl_v3(0.001, 0.01, 0.015), ranks, shifts);
    CHECK(n == 1 && ranks[0] == 1 && fabs(shifts[0].x - 0.03) < 1e-15);
    // Near the high x face: rank 1, no shift.
    n = bdl_decomp_ghost_targets(&d, bdl_v3(0.014, 0.01, 0.015), ranks, shifts);
    CHECK(n == 1 && ranks[0] == 1 && shifts[0].x == 0.0);
    // Near the low z face (a wall: nobody below) and y (not cut): nobody.
    CHECK(bdl_decomp_ghost_targets(&d, bdl_v3(0.007, 0.0001, 0.001), ranks, shifts) == 0);
    // A corner: low x and high z: x across (rank 1, shifted), z across (rank 2), and the
    // diagonal (rank 3, shifted).
    n = bdl_decomp_ghost_targets(&d, bdl_v3(0.001, 0.01, 0.029), ranks, shifts);
    int seen = 0;
    for (int t = 0; t < n; ++t)
        seen |= (ranks[t] == 1 && shifts[t].x > 0.0) << 0 |
                (ranks[t] == 2 && shifts[t].x == 0.0) << 1 |
                (ranks[t] == 3 && shifts[t].x > 0.0) << 2;
    CHECK_MSG(n == 3 && seen == 7, "corner: %d targets, seen %d", n, seen);
}

/// The automatic choice.
static void choice(void)
{
    const int periodic[3] = {0, 0, 0};
    int dims[3];
    // No particles: the least cut area, the longest axis cut (z, 0.06 m).
    CHECK(bdl_decomp_choose(4, lo, hi, periodic, 0.003, NULL, 0, dims));
    CHECK_MSG(dims[0] == 1 && dims[1] == 1 && dims[2] == 4, "%d %d %d", dims[0], dims[1], dims[2]);
    // A bed in the bottom sixth: cutting z would put it all in one box; x and y share it out.
    bdl_vec3 bed[600];
    for (int i = 0; i < 600; ++i)
        bed[i] = bdl_v3(0.0005 + 0.001 * (i % 30), 0.0005 + 0.001 * ((i / 30) % 20),
                        0.0005 + 0.001 * (i / 600.0));
    CHECK(bdl_decomp_choose(4, lo, hi, periodic, 0.003, bed, 600, dims));
    CHECK_MSG(dims[2] == 1, "%d %d %d", dims[0], dims[1], dims[2]);
    // Too many ranks for boxes 2 margins wide: none.
    CHECK(!bdl_decomp_choose(67, lo, hi, periodic, 0.003, NULL, 0, dims)); // a prime: one axis
    const int thin[3] = {1, 1, 11};
    CHECK(!bdl_decomp_fits(thin, lo, hi, 0.003));
}

int main(void)
{
    owners();
    ghosts();
    choice();
    return bdl_test_summary("test_decomp");
}
