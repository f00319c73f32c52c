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
#include "verify/verify.h"

static const double g = 9.81;

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
                bdl_verify_slide s = bdl_verify_slide_roll(hertz, mu, v0, 1.0e-5);
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
