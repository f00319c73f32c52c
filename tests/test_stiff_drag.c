// Particles whose drag relaxation time is a hundred times shorter than the time step: the drag is
// backward Euler on the particle side, so they settle at the drag law's terminal velocity from the
// first steps, without the growing oscillation an explicit drag would give (|1 - dt/tau| = 96).
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "scene_util.h"

int main(void)
{
    const double d = 1e-6, rho_p = 1000.0, rho = 1.2, mu = 1.8e-5, g = 9.81, dt = 3e-4;
    const double tau = rho_p * d * d / (18.0 * mu);             // Stokes relaxation time
    const double v_t = (rho_p - rho) * d * d * g / (18.0 * mu); // Stokes terminal velocity
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 1\ndt = %g\ngravity = 0 0 -9.81\nseed = 4\n"
        "[domain]\nmin = 0 0 0\nmax = 0.01 0.01 0.01\n"
        "[contact]\nlaw = linear\n"
        "[species dust]\ndiameter = %g\ndensity = %g\nstiffness = 3e-11\nrestitution = 0.5\n"
        "friction = 0\n"
        "[wall box]\ntype = box\nmin = 0 0 0\nmax = 0.01 0.01 0.01\n"
        "[create cloud]\ntype = random\nspecies = dust\ncount = 20\nregion_min = 0.002 0.002 "
        "0.004\nregion_max = 0.008 0.008 0.009\n"
        "[gas]\ncells = 4 4 4\ndensity = %g\nviscosity = %g\ndt = %g\n"
        "[coupling]\ndrag = stokes\n",
        dt, d, rho_p, rho, mu, dt);
    CHECK(w != NULL && w->gas != NULL);
    if (!w)
        return bdl_test_summary("test_stiff_drag");
    printf("dt %.2g s, relaxation time %.3g s: dt / tau = %.0f; terminal velocity %.4g m/s\n", dt,
           tau, dt / tau, v_t);
    CHECK(dt / tau > 90.0);
    double worst = 0.0;
    int finite = 1;
    for (int step = 1; step <= 200; ++step) {
        if (bdl_world_step(w) != BDL_OK) {
            CHECK_MSG(0, "step %d failed", step);
            break;
        }
        for (long i = 0; i < w->particles.count; ++i) {
            const bdl_vec3 v = w->particles.vel[i];
            finite = finite && isfinite(v.x) && isfinite(v.y) && isfinite(v.z);
            if (step > 3) // from the fourth step on: at terminal velocity
                worst = fmax(worst, fabs(-v.z - v_t) / v_t);
        }
    }
    printf("20 particles over 200 steps: settling velocity within %.2g %% of Stokes' terminal "
           "velocity from the fourth step on\n",
           100.0 * worst);
    CHECK(finite);
    CHECK_MSG(worst < 0.01, "settling velocity off by %g", worst);
    bdl_world_destroy(w);
    return bdl_test_summary("test_stiff_drag");
}
