// Sun's segregation percentage s_p in diagnostics.csv (eqs. 5.22-5.25 of the thesis): a bed of
// two species laid in layers, the large below and the small above with equal volumes, reads 1;
// the two side by side over the same height read 0; the other way up reads -1/3 (S_p = 1/3); a
// scene of one species has no s_p.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "output/diagnostics.h"
#include "verify/verify.h"

/// A box 20 mm across with a lattice of 4 mm spheres (spacing 5 mm) in x [0, split] and z [lo_l,
/// hi_l] and one of 2 mm spheres (spacing 2.5 mm, eight to each large one) in x [0.02 - split,
/// 0.02] and z [lo_s, hi_s].
static double sp_of(double split, double lo_l, double hi_l, double lo_s, double hi_s)
{
    bdl_world *w = bdl_verify_world(
        "[run]\nend_time = 1\ngravity = 0 0 -9.81\n[domain]\nmin = 0 0 0\nmax = 0.02 0.02 0.08\n"
        "[contact]\nlaw = linear\n"
        "[species large]\ndiameter = 0.004\ndensity = 2500\nstiffness = 1e4\nrestitution = 0.9\n"
        "[species small]\ndiameter = 0.002\ndensity = 2500\nstiffness = 1e4\nrestitution = 0.9\n"
        "[create l]\ntype = lattice\nspecies = large\nspacing = 0.005\n"
        "region_min = 0 0 %g\nregion_max = %g 0.02 %g\n"
        "[create s]\ntype = lattice\nspecies = small\nspacing = 0.0025\n"
        "region_min = %g 0 %g\nregion_max = 0.02 0.02 %g\n",
        lo_l, split, hi_l, 0.02 - split, lo_s, hi_s);
    CHECK(w != NULL);
    if (!w)
        return NAN;
    bdl_diagnostics d;
    bdl_diagnostics_compute(w, 0.0, &d);
    // The same from the positions, written out here.
    double v[2] = {0, 0}, h[2] = {0, 0};
    for (long i = 0; i < w->particles.count; ++i) {
        const int s = w->particles.species[i];
        const double r = w->particles.radius[i], vol = r * r * r;
        v[s] += vol;
        h[s] += vol * w->particles.pos[i].z;
    }
    const double x = v[1] / (v[0] + v[1]), ratio = (h[1] / v[1]) / (h[0] / v[0]);
    const double expect = (ratio - 1.0) / ((2.0 - x) / (1.0 - x) - 1.0);
    printf("large in z [%g, %g], small in [%g, %g]: %ld spheres, small share %.3f, s_p %.4f\n",
           lo_l, hi_l, lo_s, hi_s, w->particles.count, x, d.segregation);
    CHECK_CLOSE(d.segregation, expect, 1e-12);
    bdl_world_destroy(w);
    return d.segregation;
}

int main(void)
{
    // The lattices' sites do not fill their layers symmetrically: within 0.1 of the ideal values.
    CHECK(fabs(sp_of(0.02, 0.0, 0.02, 0.02, 0.04) - 1.0) < 0.1);       // layered, large below
    CHECK(fabs(sp_of(0.01, 0.0, 0.04, 0.0, 0.04)) < 0.1);              // side by side
    CHECK(fabs(sp_of(0.02, 0.02, 0.04, 0.0, 0.02) + 1.0 / 3.0) < 0.1); // upside down
    bdl_world *one = bdl_verify_world(
        "[run]\nend_time = 1\ngravity = 0 0 -9.81\n[domain]\nmin = 0 0 0\nmax = 0.02 0.02 0.08\n"
        "[contact]\nlaw = linear\n"
        "[species large]\ndiameter = 0.004\ndensity = 2500\nstiffness = 1e4\nrestitution = 0.9\n"
        "[create l]\ntype = lattice\nspecies = large\nspacing = 0.005\n"
        "region_min = 0 0 0\nregion_max = 0.02 0.02 0.02\n");
    CHECK(one != NULL);
    if (one) {
        bdl_diagnostics d;
        bdl_diagnostics_compute(one, 0.0, &d);
        CHECK(isnan(d.segregation));
        bdl_world_destroy(one);
    }
    return bdl_test_summary("test_segregation");
}
