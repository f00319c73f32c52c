// Static overlaps in a column of spheres (MFiX DEM03-style static check:
// stacked, compressed particles).
//
// Five equal spheres stand in a perfectly aligned vertical column on a plane under gravity
// (frictionless, damped by a low restitution and background damping, so it comes to rest). At
// rest the contact below the k-th sphere from the top carries k m g:
//   linear: delta_k = k m g / k_n                          (the wall contact likewise, k = 5)
//   Hertz:  delta_k = (k m g / ((4/3) E* sqrt(R*)))^(2/3),  E* = E/(2(1 - nu^2)),
//           R* = r/2 between spheres, R* = r against the wall (same material).
// Velocity Verlet's fixed point is exact force balance, so once the motion has died the overlaps
// must match within 0.1 % (we run until the kinetic energy is below 1e-12 of m g r per sphere;
// the residual vibration is then far below 1e-4 of the overlaps). The spheres must also stay
// aligned: no lateral force arises.
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "scene_util.h"

#define PI 3.14159265358979323846
#define N  5

static const double diameter = 0.01, density = 2500.0, g = 9.81;
static const double stiffness = 1.0e4, youngs = 1.0e8, poisson = 0.3;

static int by_height(const void *a, const void *b)
{
    double za = ((const bdl_vec3 *)a)->z, zb = ((const bdl_vec3 *)b)->z;
    return (za > zb) - (za < zb);
}

static void column(int hertz)
{
    double r = 0.5 * diameter, m = density * PI / 6.0 * diameter * diameter * diameter;
    // The lattice stacks the spheres 1.0001 d apart from z = r: they drop by 1e-4 d and settle.
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 10\ndt_fraction = 0.02\ngravity = 0 0 %.17g\n"
        "[domain]\nmin = -0.02 -0.02 -0.01\nmax = 0.02 0.02 0.1\n"
        "[contact]\nlaw = %s\n"
        "[species ball]\ndiameter = %.17g\ndensity = %.17g\n%s = %.17g\npoisson_ratio = %.17g\n"
        "restitution = 0.3\nfriction = 0\nbackground_damping = 20\n"
        "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"
        "[create column]\ntype = lattice\ncount = %d\n"
        "region_min = %.17g %.17g 0\nregion_max = %.17g %.17g %.17g\n",
        -g, hertz ? "hertz" : "linear", diameter, density, hertz ? "youngs_modulus" : "stiffness",
        hertz ? youngs : stiffness, poisson, N, -r, -r, r + diameter, r + diameter, 5.5 * diameter);
    CHECK(w->particles.count == N);
    double ke = INFINITY, t_max = 5.0;
    long steps = 0;
    while (w->time < t_max) {
        bdl_world_step(w);
        ++steps;
        if (steps % 100)
            continue;
        ke = 0.0;
        for (long i = 0; i < w->particles.count; ++i)
            ke += 0.5 * bdl_v3_len2(w->particles.vel[i]) / w->particles.inv_mass[i];
        if (ke < 1e-12 * N * m * g * r && w->time > 0.2)
            break;
    }
    CHECK_MSG(ke < 1e-12 * N * m * g * r, "column not at rest after %g s (KE = %g J)", w->time, ke);

    bdl_vec3 x[N];
    for (int i = 0; i < N; ++i)
        x[i] = w->particles.pos[i];
    qsort(x, N, sizeof x[0], by_height); // x[0] is the bottom sphere
    double es = youngs / (2.0 * (1.0 - poisson * poisson));
    printf("| %s | contact | load (m g) | overlap measured (m) | theory (m) | rel. error |\n",
           hertz ? "hertz" : "linear");
    printf("|---|---|---|---|---|---|\n");
    double lateral = 0.0;
    for (int c = 0; c < N; ++c) {
        // Contact c: c = 0 is sphere 0 on the wall; c >= 1 is sphere c on sphere c - 1. It carries
        // the N - c spheres above it, including sphere c itself.
        int load = N - c;
        double overlap = c == 0 ? r - x[0].z : 2.0 * r - (x[c].z - x[c - 1].z);
        double f = load * m * g, theory;
        if (hertz) {
            double r_eff = c == 0 ? r : 0.5 * r;
            theory = pow(f / ((4.0 / 3.0) * es * sqrt(r_eff)), 2.0 / 3.0);
        } else {
            theory = f / stiffness;
        }
        printf("| | %s | %d | %.6e | %.6e | %.1e |\n", c == 0 ? "wall - bottom" : "sphere - sphere",
               load, overlap, theory, fabs(overlap - theory) / theory);
        CHECK_CLOSE(overlap, theory, 1e-3);
        lateral = fmax(lateral, fmax(fabs(x[c].x - x[0].x), fabs(x[c].y - x[0].y)));
    }
    printf("\nsettled after %.3f s (%ld steps, dt = t_c/%.0f); largest lateral offset %.1e m\n\n",
           w->time, steps, 1.0 / w->contact_time_dt_ratio, lateral);
    CHECK(lateral < 1e-12);
    bdl_world_destroy(w);
}

int main(void)
{
    omp_set_num_threads(1);
    printf("Static column of %d spheres on a plane: overlaps at rest\n\n", N);
    column(0);
    column(1);
    return bdl_test_summary("test_column");
}
