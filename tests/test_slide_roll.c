// Sliding to rolling of a sphere on a plane (MFiX DEM04-style verification).
//
// A sphere resting on a frictional plane under gravity is given a horizontal velocity v0 without
// spin. While it slides, Coulomb friction mu m g decelerates it and spins it up:
//   v(t) = v0 - mu g t,   r w(t) = (5/2) mu g t,   slip s = v - r w = v0 - (7/2) mu g t,
// so slip stops at t_s = 2 v0 / (7 mu g) and the sphere then rolls at v = 5 v0 / 7.
//
// Measurement: the slip velocity of the contact point, s = v_x - a w_y with the solver's lever
// arm a = r - delta/2, is sampled every step; a least-squares line is FITTED to the sliding phase
// (samples with 0.2 v0 < s < 0.8 v0, well after the normal transient) and its zero is t_s. (A zero
// crossing is not used: once the slip is small the tangential spring takes over, and with the
// tangential dashpot used here the stick transient is overdamped, so s creeps to zero without a
// clean crossing.) The rolling speed is read at 2 t_s, when the stick transient has died. Both
// within 1 %. Coulomb's law is also checked directly: while the contact slides (s > 0.05 v0) the
// friction force on the sphere must never point along the slip.
//
// The normal transient (the sphere starts at zero overlap) does not bias t_s: the friction
// impulse is mu times the normal impulse, and the normal impulse up to t equals m g t + m v_z(t),
// which is m g t once the (low-restitution, stiff) contact has settled after a few contact times.
#include <math.h>
#include <omp.h>
#include <stdio.h>

#include "check.h"
#include "scene_util.h"

static const double diameter = 0.01, density = 2500.0, g = 9.81;

typedef struct slide_result {
    double t_fit;       ///< zero of the fitted sliding-phase slip line [s]
    long forward;       ///< sliding steps where the friction force points along the slip
    double max_forward; ///< largest such force over mu F_n [-]
    double v_roll;      ///< v_x at 2 t_s [s]
    double slip_end;    ///< |slip| at 2 t_s [m/s]
} slide_result;

static slide_result slide(int hertz, double mu, double v0)
{
    double r = 0.5 * diameter;
    double ts = 2.0 * v0 / (7.0 * mu * g);
    // Linear: k_n = 1e5 N/m, t_c ~ 5e-4 s; Hertz: E = 1e8 Pa, resting contact period ~ 2e-3 s.
    // Both with dt = 1e-5 s (t_c/50 or finer). e = 0.2 (zeta = 0.73, exact damping).
    double dt = 1.0e-5;
    bdl_world *w =
        bdl_test_world("[run]\nend_time = 10\ndt = %.17g\ngravity = 0 0 %.17g\n"
                       "[domain]\nmin = -0.02 -0.02 -0.01\nmax = 1.5 0.02 0.05\n"
                       "[contact]\nlaw = %s\n"
                       "[species ball]\ndiameter = %.17g\ndensity = %.17g\n%s\nrestitution = 0.2\n"
                       "friction = %.17g\ntangential_damping_ratio = 0.5\n"
                       "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"
                       "[create ball]\ntype = lattice\ncount = 1\nvelocity = %.17g 0 0\n"
                       "region_min = %.17g %.17g 0\nregion_max = %.17g %.17g %.17g\n",
                       dt, -g, hertz ? "hertz" : "linear", diameter, density,
                       hertz ? "youngs_modulus = 1e8\npoisson_ratio = 0.3" : "stiffness = 1e5", mu,
                       v0, -r, -r, r + diameter, r + diameter, 3.0 * diameter);
    // Least-squares sums of s(t) over the sliding window.
    double n = 0, st = 0, ss = 0, stt = 0, sts = 0;
    slide_result res = {-1.0, 0, 0.0, 0.0, 0.0};
    long steps = (long)(2.0 * ts / dt) + 1;
    for (long k = 0; k < steps; ++k) {
        bdl_world_step(w);
        const bdl_particles *p = &w->particles;
        double z = p->pos[0].z;
        double arm = 0.5 * (r + z); // r - delta/2 with delta = r - z
        double s = p->vel[0].x - arm * p->omega[0].y;
        double t = w->time;
        if (s > 0.2 * v0 && s < 0.8 * v0) {
            n += 1;
            st += t;
            ss += s;
            stt += t * t;
            sts += t * s;
        }
        // Wall force on the sphere: its x component is tangential (the normal is z).
        const bdl_neighbor *nb = &w->neighbor;
        bdl_vec3 fw = bdl_v3_zero();
        for (int32_t c = nb->wall_start[0]; c < nb->wall_start[1]; ++c)
            fw = bdl_v3_add(fw, nb->wall_force[c]);
        if (s > 0.05 * v0 && fw.x > 0.0) {
            ++res.forward;
            double ratio = fw.z > 0.0 ? fw.x / (mu * fw.z) : INFINITY;
            if (ratio > res.max_forward)
                res.max_forward = ratio;
        }
        res.v_roll = p->vel[0].x;
        res.slip_end = fabs(s);
    }
    double slope = (n * sts - st * ss) / (n * stt - st * st);
    double icpt = (ss - slope * st) / n;
    res.t_fit = -icpt / slope;
    bdl_world_destroy(w);
    return res;
}

int main(void)
{
    omp_set_num_threads(1);
    printf("Sliding to rolling: slip stop time t_s = 2 v0/(7 mu g) and rolling speed 5 v0/7\n\n");
    printf(
        "| law | mu | v0 (m/s) | t_s theory (s) | t_s fit (s) | err | v_roll/v0 | err | "
        "|slip|/v0 at 2 t_s | sliding steps with friction along the slip (max F_t/(mu F_n)) |\n");
    printf("|---|---|---|---|---|---|---|---|---|---|\n");
    for (int hertz = 0; hertz <= 1; ++hertz)
        for (int im = 0; im < 2; ++im)
            for (int iv = 0; iv < 2; ++iv) {
                double mu = im == 0 ? 0.3 : 0.6, v0 = iv == 0 ? 0.5 : 1.0;
                double ts = 2.0 * v0 / (7.0 * mu * g), vr = 5.0 / 7.0;
                slide_result s = slide(hertz, mu, v0);
                printf(
                    "| %s | %.1f | %.1f | %.5f | %.5f | %.1e | %.5f | %.1e | %.1e | %ld (%.2f) |\n",
                    hertz ? "hertz" : "linear", mu, v0, ts, s.t_fit, fabs(s.t_fit - ts) / ts,
                    s.v_roll / v0, fabs(s.v_roll / v0 - vr) / vr, s.slip_end / v0, s.forward,
                    s.max_forward);
                CHECK_CLOSE(s.t_fit, ts, 0.01);
                CHECK_MSG(s.forward == 0,
                          "%s mu=%.1f v0=%.1f: friction pushed along the slip in %ld sliding steps "
                          "(up to %.2f mu F_n)",
                          hertz ? "hertz" : "linear", mu, v0, s.forward, s.max_forward);
                CHECK_CLOSE(s.v_roll / v0, vr, 0.01);
                CHECK(s.slip_end < 0.01 * v0); // rolling without slip
            }
    return bdl_test_summary("test_slide_roll");
}
