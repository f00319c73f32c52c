// Duration of an elastic Hertz contact against Hertz theory (Johnson, Contact Mechanics, 1985):
//
//   t_c = 2.87 (m*^2 / (R* E*^2 v))^(1/5)     (the constant is 2.868...)
//
// e = 1 (no damping), gravity off. A sphere hits a plane of the same material (m* = m, R* = r,
// E* = E/(2(1 - nu^2))) at 0.1 and 1 m/s, and two equal spheres collide head-on at relative speed
// 0.1 and 1 m/s (m* = m/2, R* = r/2, same E*). The contact starts and ends between steps: both
// instants are found by linear interpolation of the gap between the two steps that bracket them
// (dt = t_c/1000, so the interpolation error is far below the tolerance), and the duration must
// agree with the formula within 2 %. The rebound speed must equal the impact speed (e = 1).
#include <math.h>
#include <omp.h>
#include <stdio.h>

#include "check.h"
#include "scene_util.h"

#define PI 3.14159265358979323846

static const double diameter = 0.01, density = 7800.0, youngs = 2.0e11, poisson = 0.3;

static double hertz_time(double m_eff, double r_eff, double e_star, double v)
{
    return 2.87 * pow(m_eff * m_eff / (r_eff * e_star * e_star * v), 0.2);
}

/// Measures the contact duration. `pair` = 0: sphere on a plane (gap = z - r); 1: two spheres
/// approaching along x at +-v/2 (gap = distance - 2 r). Returns the duration; `rebound` gets the
/// relative separation speed after the contact divided by v.
static double measure(int pair, double v, double t_ref, double *rebound)
{
    double r = 0.5 * diameter;
    double dt = t_ref / 1000.0;
    double gap0 = 3.3 * v * dt; // contact starts 0.3 of a step into the 4th step
    bdl_world *w;
    if (!pair) {
        double z0 = r + gap0;
        w = bdl_test_world(
            "[run]\nend_time = 1\ndt = %.17g\ngravity = 0 0 0\n"
            "[domain]\nmin = -0.02 -0.02 -0.01\nmax = 0.02 0.02 0.05\n"
            "[contact]\nlaw = hertz\n"
            "[species steel]\ndiameter = %.17g\ndensity = %.17g\nyoungs_modulus = %.17g\n"
            "poisson_ratio = %.17g\nrestitution = 1\n"
            "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"
            "[create ball]\ntype = lattice\ncount = 1\nvelocity = 0 0 %.17g\n"
            "region_min = %.17g %.17g %.17g\nregion_max = %.17g %.17g %.17g\n",
            dt, diameter, density, youngs, poisson, -v, -r, -r, z0 - r, r + diameter, r + diameter,
            z0 + 2.0 * r);
    } else {
        double x0 = r + 0.5 * gap0; // centres at -x0 and +x0
        w = bdl_test_world(
            "[run]\nend_time = 1\ndt = %.17g\ngravity = 0 0 0\n"
            "[domain]\nmin = -0.05 -0.02 -0.02\nmax = 0.05 0.02 0.02\n"
            "[contact]\nlaw = hertz\n"
            "[species steel]\ndiameter = %.17g\ndensity = %.17g\nyoungs_modulus = %.17g\n"
            "poisson_ratio = %.17g\nrestitution = 1\n"
            "[create left]\ntype = lattice\ncount = 1\nvelocity = %.17g 0 0\n"
            "region_min = %.17g %.17g %.17g\nregion_max = %.17g %.17g %.17g\n"
            "[create right]\ntype = lattice\ncount = 1\nvelocity = %.17g 0 0\n"
            "region_min = %.17g %.17g %.17g\nregion_max = %.17g %.17g %.17g\n",
            dt, diameter, density, youngs, poisson, 0.5 * v, -x0 - r, -r, -r, -x0 + 2.0 * r,
            r + diameter, r + diameter, -0.5 * v, x0 - r, -r, -r, x0 + 2.0 * r, r + diameter,
            r + diameter);
    }
    double prev_gap = gap0, t_start = -1.0, t_end = -1.0, t_prev = 0.0;
    long max_steps = 10 + (long)(3.0 * t_ref / dt);
    for (long s = 0; s < max_steps && t_end < 0.0; ++s) {
        bdl_world_step(w);
        const bdl_particles *p = &w->particles;
        double gap;
        if (!pair) {
            gap = p->pos[0].z - r;
            *rebound = p->vel[0].z / v;
        } else {
            long a = bdl_test_find(w, 0), b = bdl_test_find(w, 1);
            gap = bdl_v3_len(bdl_v3_sub(p->pos[b], p->pos[a])) - 2.0 * r;
            *rebound = (p->vel[b].x - p->vel[a].x) / v;
        }
        if (t_start < 0.0 && gap < 0.0)
            t_start = t_prev + dt * prev_gap / (prev_gap - gap);
        else if (t_start >= 0.0 && gap >= 0.0)
            t_end = t_prev + dt * prev_gap / (prev_gap - gap);
        prev_gap = gap;
        t_prev = w->time;
    }
    bdl_world_destroy(w);
    return t_start >= 0.0 && t_end >= 0.0 ? t_end - t_start : -1.0;
}

int main(void)
{
    omp_set_num_threads(1);
    double r = 0.5 * diameter;
    double m = density * PI / 6.0 * diameter * diameter * diameter;
    double e_star = youngs / (2.0 * (1.0 - poisson * poisson));
    printf("Hertz contact duration, e = 1 (dt = t_c/1000, start and end interpolated)\n\n");
    printf("| contact | v (m/s) | t_c theory (s) | t_c measured (s) | rel. error | rebound/impact "
           "speed |\n");
    printf("|---|---|---|---|---|---|\n");
    for (int pair = 0; pair <= 1; ++pair)
        for (int iv = 0; iv < 2; ++iv) {
            double v = iv == 0 ? 0.1 : 1.0;
            double m_eff = pair ? 0.5 * m : m, r_eff = pair ? 0.5 * r : r;
            double ref = hertz_time(m_eff, r_eff, e_star, v);
            double rebound = 0.0;
            double tc = measure(pair, v, ref, &rebound);
            printf("| %s | %.1f | %.5e | %.5e | %.2e | %.6f |\n",
                   pair ? "sphere-sphere" : "sphere-wall", v, ref, tc, fabs(tc - ref) / ref,
                   rebound);
            CHECK_CLOSE(tc, ref, 0.02);
            CHECK_CLOSE(rebound, 1.0, 1e-3);
        }
    return bdl_test_summary("test_hertz_duration");
}
