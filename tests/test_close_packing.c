// A bed driven past close packing by deposition: 2000 spheres poured fast into a narrow box with
// gas through the floor at half the minimum fluidization velocity. The deposited solids fraction
// of the settled bed passes the cap set here ([coupling] max_solids = 0.55); the voidage the gas
// sees stops at 1 - 0.55, so the drag stays finite, and the run stays stable: no NaN, overlaps
// within the guard, the gas volume balance to the solver's tolerance.
#include <math.h>
#include <stdio.h>

#include "cfd/gas.h"
#include "check.h"
#include "couple/coupling.h"
#include "scene_util.h"
#include "output/diagnostics.h"

int main(void)
{
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 1\ndt_fraction = 0.05\ngravity = 0 0 -9.81\nseed = 8\n"
        "[domain]\nmin = 0 0 0\nmax = 0.02 0.02 0.1\n"
        "[contact]\nlaw = linear\n"
        "[species glass]\ndiameter = 0.002\ndensity = 2500\nstiffness = 2000\nrestitution = 0.3\n"
        "friction = 0.5\n"
        "[wall box]\ntype = box\nmin = 0 0 0\nmax = 0.02 0.02 0.1\n"
        "[create pour]\ntype = pour\nspecies = glass\ncount = 2000\nrate = 20000\n"
        "region_min = 0 0 0.06\nregion_max = 0.02 0.02 0.1\n"
        "[gas]\ncells = 4 4 20\nzmin = inlet\nzmax = outlet\ninlet_velocity = 0.5\n"
        "[coupling]\ndrag = gidaspow\nmax_solids = 0.55\n");
    CHECK(w != NULL && w->gas != NULL);
    if (!w || !w->gas)
        return bdl_test_summary("test_close_packing");
    const double floor_eps = 1.0 - w->coupling->def.max_solids;
    double lowest = 1.0, worst_overlap = 0.0, worst_volume = 0.0;
    int finite = 1;
    while (w->time < 0.3) {
        if (bdl_world_step(w) != BDL_OK) {
            CHECK_MSG(0, "step failed at t = %g", w->time);
            break;
        }
        if (w->step % 200)
            continue;
        const bdl_grid *g = &w->gas->grid;
        for (int k = 0; k < g->n[2]; ++k)
            for (int j = 0; j < g->n[1]; ++j)
                for (int i = 0; i < g->n[0]; ++i)
                    lowest = fmin(lowest, w->gas->eps[bdl_grid_index(g, i, j, k)]);
        bdl_diagnostics d;
        bdl_diagnostics_compute(w, 0.0, &d);
        finite = finite && isfinite(d.kinetic_energy) && isfinite(d.pressure_drop);
        worst_overlap = fmax(worst_overlap, d.max_overlap_ratio);
        worst_volume = fmax(worst_volume, d.gas_volume_imbalance);
    }
    printf("%ld particles poured by %.2f s: lowest voidage %.3f (cap %.3f), largest overlap %.3g, "
           "gas volume imbalance <= %.1e\n",
           w->particles.count, w->time, lowest, floor_eps, worst_overlap, worst_volume);
    CHECK(w->particles.count == 2000);
    CHECK(finite);
    // The cap is reached (the bed is past it) and never passed.
    CHECK_MSG(fabs(lowest - floor_eps) < 1e-12, "lowest voidage %g, cap %g", lowest, floor_eps);
    CHECK_MSG(worst_overlap < w->scene.guards.max_overlap, "overlap %g", worst_overlap);
    CHECK(worst_volume < 1e-7);
    bdl_world_destroy(w);
    return bdl_test_summary("test_close_packing");
}
