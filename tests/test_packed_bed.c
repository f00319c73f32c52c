// A packed bed below minimum fluidization: the pressure gradient through its interior follows the
// Ergun equation at the bed's local voidage, at three superficial velocities.
#include <math.h>
#include <stdio.h>

#include "cfd/gas.h"
#include "check.h"
#include "scene_util.h"
#include "sim/loop.h"

/// Ergun: -dp/dz = 150 (1-e)^2 mu U / (e^3 d^2) + 1.75 (1-e) rho U^2 / (e^3 d).
static double ergun(double eps, double U, double d, double rho, double mu)
{
    double phi = 1.0 - eps;
    return 150.0 * phi * phi * mu * U / (eps * eps * eps * d * d) +
           1.75 * phi * rho * U * U / (eps * eps * eps * d);
}

static void run_until(bdl_world *w, double t)
{
    while (w->time < t)
        if (bdl_world_step(w) != BDL_OK) {
            CHECK_MSG(0, "step failed at t = %g", w->time);
            return;
        }
}

int main(void)
{
    const double d = 0.002, rho = 1.2, mu = 1.8e-5, U0 = 0.3;
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 1\ndt_fraction = 0.05\ngravity = 0 0 -9.81\nseed = 5\n"
        "[domain]\nmin = 0 0 0\nmax = 0.02 0.02 0.1\nperiodic = x y\n"
        "[contact]\nlaw = linear\n"
        "[species glass]\ndiameter = 0.002\ndensity = 2500\nstiffness = 1000\n"
        "restitution = 0.3\nfriction = 0.5\nbackground_damping = 20\n"
        "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"
        "[create bed]\ntype = random\nspecies = glass\ncount = 1400\nregion_min = 0 0 0\n"
        "region_max = 0.02 0.02 0.075\n"
        "[gas]\ncells = 5 5 25\nzmin = inlet\nzmax = outlet\ninlet_velocity = %g\n"
        "[coupling]\ndrag = ergun\n",
        U0);
    CHECK(w != NULL && w->gas != NULL);
    if (!w)
        return bdl_test_summary("test_packed_bed");
    const bdl_grid *g = &w->gas->grid;
    const double velocities[3] = {0.3, 0.6, 0.9}; // U_mf of these beads is about 1.1 m/s
    double t = 0.3;                               // settle first
    printf("   U [m/s]  layers  mean eps  -dp/dz measured / Ergun\n");
    for (int v = 0; v < 3; ++v) {
        bdl_world_set_parameter(w, "gas.inlet_scale", velocities[v] / U0);
        run_until(w, t);
        t += 0.08;
        // Layers well inside the bed: between a quarter and three quarters of its height.
        double top = 0.0;
        for (long i = 0; i < w->particles.count; ++i)
            top = fmax(top, w->particles.pos[i].z);
        int lo = (int)(0.25 * top / g->h[2]), hi = (int)(0.75 * top / g->h[2]);
        double ratio = 0.0, eps_mean = 0.0;
        int layers = 0;
        for (int k = lo; k < hi; ++k) {
            double dp = 0.0, eps = 0.0;
            for (int j = 0; j < g->n[1]; ++j)
                for (int i = 0; i < g->n[0]; ++i) {
                    long a = bdl_grid_index(g, i, j, k), b = bdl_grid_index(g, i, j, k + 1);
                    dp += w->gas->p[a] - w->gas->p[b];
                    eps += 0.5 * (w->gas->eps[a] + w->gas->eps[b]);
                }
            dp /= g->n[0] * g->n[1];
            eps /= g->n[0] * g->n[1];
            // The gas's own weight (rho g) is not drag.
            double gradient = dp / g->h[2] - rho * 9.81;
            ratio += gradient / ergun(eps, velocities[v], d, rho, mu);
            eps_mean += eps;
            ++layers;
        }
        ratio /= layers;
        eps_mean /= layers;
        printf("   %.1f      %d       %.3f     %.4f\n", velocities[v], layers, eps_mean, ratio);
        CHECK_MSG(fabs(ratio - 1.0) < 0.03, "U = %g: pressure gradient %.4f of Ergun",
                  velocities[v], ratio);
    }
    bdl_world_destroy(w);
    return bdl_test_summary("test_packed_bed");
}
