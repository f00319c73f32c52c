// Oblique impact of an elastic sphere (e = 1, Hertz-Mindlin with friction) on a plane and on
// another sphere (docs/verification-dem.md, "Oblique impact").
//
// 1. A sticking impact (v_t = 2 v_n, mu = 1e6) runs through the default guards, checked at every
//    step. The energy balance (kinetic + rotational + elastic, the spring's stored work booked as
//    the work its force took from the bodies, and the work it still held at separation booked as
//    having left them) stays within the integration error of zero, during the contact and after
//    it: 3e-3 of the energy at t_c/50, 3e-4 at t_c/200 (the step in which the contact ends books
//    the spring by its last force: O(dt^1.7), 2e-3 at t_c/50). The energy the bodies lose
//    matches the law's own continuum limit (RK4) within 1e-3. The former booking, 1/2 k_t(delta)
//    |u|^2 with the stiffness of the current overlap, is printed beside it: it grew by 13 %, beyond
//    the guard's 5 %.
// 2. The same for two equal spheres (the pair path of the force pass, which keeps the work in the
//    pair lists).
// 3. Gross sliding (psi1 = 8, mu = 0.3) rebounds as the rigid-body Coulomb impulse: within 1e-4 of
//    the law's limit (the lever arm r - delta/2) at t_c/50, and within 0.3 % of the textbook
//    psi2 = psi1 - 4 chi (lever arm r).
// 4. The tangential rebound converges with dt, worst over 8 phases of first touch: order >= 1.4
//    in full stick over the finest pair (the spring's force ends as sqrt(delta)), >= 2.2 in gross
//    sliding, and at t_c/50 the sticking error is below 0.5 % (6.7 % before the onset of the
//    spring was resolved).
// 5. The reduced rebound psi2 against the reduced incidence psi1 beside the theory of Maw, Barber
//    & Fawcett (1976), computed by the method of dimensionality reduction, which reproduces the
//    theory's own landmarks (gross slip from psi1 = 4 chi - 1 on, where psi2 = -1; the rigid line
//    beyond): bedlam matches it in gross sliding within 0.01; the sticking regime is printed, and
//    both curves in steps of 0.25 for the plot (tools/plot_verification.sh).
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "scene_util.h"
#include "output/diagnostics.h"
#include "run/guards.h"
#include "verify/verify.h"

static const double r = 0.005, youngs = 2e11, nu = 0.3;

/// The former booking of the sphere's wall spring, 1/2 k_t(delta) |u|^2, k_t = 8 G* sqrt(r delta).
static double former_spring_energy(const bdl_world *w)
{
    const bdl_neighbor *nb = &w->neighbor;
    const double gs = youngs / (2.0 * (1.0 + nu)) / (2.0 * (2.0 - nu));
    const double overlap = r - w->particles.pos[0].z;
    double e = 0.0;
    for (int32_t k = nb->wall_start[0]; k < nb->wall_start[1]; ++k)
        if (overlap > 0.0)
            e += 4.0 * gs * sqrt(r * overlap) * bdl_v3_len2(nb->wall_history[k]);
    return e;
}

typedef struct energy_run {
    double growth;     ///< largest |energy balance| / E0, in contact and after
    double former;     ///< largest energy balance / E0 in contact with the former booking
    double change;     ///< (kinetic + rotational energy after - E0) / E0
    double left;       ///< work left in the spring at separation / E0
    int guard_stopped; ///< the guards (default limits, every step) stopped it
} energy_run;

/// Steps world w through one impact, computing the diagnostics and the guards at every step.
static energy_run through_guards(bdl_world *w, int on_plane)
{
    energy_run e = {0.0, 0.0, NAN, NAN, 0};
    bdl_diagnostics d;
    bdl_diagnostics_compute(w, 0.0, &d);
    const double e0 = bdl_diagnostics_total_energy(&d), spring0 = 0.0;
    bdl_guard_state g;
    bdl_guards_init(&g, w, &d);
    int touched = 0;
    char message[512];
    for (long s = 0; s < 5000 && bdl_world_step(w) == BDL_OK; ++s) {
        bdl_diagnostics_compute(w, e0, &d);
        if (bdl_guards_check(w, &g, &d, message, sizeof message) != BDL_OK) {
            printf("  guard: %s\n", message);
            e.guard_stopped = 1;
            break;
        }
        const int in_contact = d.max_overlap_ratio > 0.0;
        touched |= in_contact;
        e.growth = fmax(e.growth, fabs(d.energy_balance) / e0);
        if (in_contact) {
            if (on_plane) {
                const double spring = former_spring_energy(w) - spring0;
                const double tangential =
                    d.elastic_energy - (8.0 / 15.0) * youngs / (2.0 * (1.0 - nu * nu)) * sqrt(r) *
                                           pow(r - w->particles.pos[0].z, 2.5);
                e.former = fmax(e.former, (d.energy_balance - tangential + spring) / e0);
            }
        } else if (touched) {
            e.change = (d.kinetic_energy + d.rotational_energy) / e0 - 1.0;
            e.left = d.spring_work_left / e0;
            break;
        }
    }
    return e;
}

static void sticking_through_guards(void)
{
    const double vt = 2.0, mu = 1e6, tc = bdl_verify_oblique_contact_time();
    const bdl_verify_oblique ref = bdl_verify_oblique_reference(vt, mu, 0);
    printf("\nSticking elastic impact on a plane, v_t = 2 v_n, mu = 1e6 (continuum: energy "
           "change %.4e, v_t2/v_t1 = %.5f)\n\n",
           ref.energy_error, ref.vt2 / vt);
    printf(
        "| dt | phase | guards | largest \\|balance\\| | former booking, in contact | energy "
        "change | vs continuum | work left in the spring |\n|---|---|---|---|---|---|---|---|\n");
    static const double n[2] = {50, 200}, limit[2] = {3e-3, 3e-4};
    for (int l = 0; l < 2; ++l)
        for (int ph = 0; ph < 8; ++ph) {
            bdl_world *w = bdl_verify_oblique_world(vt, mu, tc / n[l], (ph + 0.5) / 8.0);
            CHECK(w != NULL);
            if (!w)
                return;
            const energy_run e = through_guards(w, 1);
            printf("| t_c/%g | %.4f | %s | %.2e | %.2e | %.4e | %.1e | %.4e |\n", n[l],
                   (ph + 0.5) / 8.0, e.guard_stopped ? "stopped" : "ran", e.growth, e.former,
                   e.change, e.change - ref.energy_error, e.left);
            CHECK_MSG(!e.guard_stopped, "the guards stopped an elastic sticking impact");
            CHECK_MSG(e.growth < limit[l], "energy balance %g at t_c/%g", e.growth, n[l]);
            CHECK_MSG(fabs(e.change - ref.energy_error) < 1e-3, "energy change %g, continuum %g",
                      e.change, ref.energy_error);
            bdl_world_destroy(w);
        }
}

static void sphere_pair_through_guards(void)
{
    // Two equal spheres, relative velocity (2, 0, -1) m/s at the contact: each moves at half of
    // it, the contact starting 0.3 of the 4th step (t_c of the pair at 1 m/s, dt = t_c/50).
    const double tc = bdl_verify_hertz_time(1, 1.0), dt = tc / 50.0, gap = 3.3 * dt;
    const double z0 = r + 0.5 * gap;
    bdl_world *w =
        bdl_test_world("[run]\nend_time = 1\ndt = %.17g\ngravity = 0 0 0\n"
                       "[domain]\nmin = -0.05 -0.02 -0.03\nmax = 0.05 0.02 0.03\n"
                       "[contact]\nlaw = hertz\n"
                       "[species steel]\ndiameter = 0.01\ndensity = 7800\nyoungs_modulus = 2e11\n"
                       "poisson_ratio = 0.3\nrestitution = 1\nfriction = 1e6\n"
                       "[create top]\ntype = lattice\ncount = 1\nvelocity = 1 0 -0.5\n"
                       "region_min = -0.005 -0.005 %.17g\nregion_max = 0.01 0.01 %.17g\n"
                       "[create bottom]\ntype = lattice\ncount = 1\nvelocity = -1 0 0.5\n"
                       "region_min = -0.005 -0.005 %.17g\nregion_max = 0.01 0.01 %.17g\n",
                       dt, z0 - r, z0 + 2.0 * r, -z0 - r, -z0 + 2.0 * r);
    const energy_run e = through_guards(w, 0);
    printf("\nSticking elastic impact of two spheres (relative v_t = 2 v_n, t_c/50): guards %s, "
           "largest |balance| %.2e, energy change %.4e, work left in the spring %.4e\n",
           e.guard_stopped ? "stopped" : "ran", e.growth, e.change, e.left);
    CHECK(!e.guard_stopped);
    CHECK_MSG(e.growth < 2e-3, "energy balance %g", e.growth);
    CHECK_MSG(e.change < 0.0 && e.change > -0.05, "energy change %g", e.change);
    bdl_world_destroy(w);
}

static void gross_sliding(void)
{
    const double mu = 0.3, psi1 = 8.0, vt = bdl_verify_oblique_speed(psi1, mu);
    const double kappa = bdl_verify_oblique_kappa(), chi = bdl_verify_oblique_chi();
    const bdl_verify_oblique ref = bdl_verify_oblique_reference(vt, mu, 1);
    const bdl_verify_oblique o =
        bdl_verify_oblique_impact(vt, mu, bdl_verify_oblique_contact_time() / 50.0, 0.5);
    const double psi2 = kappa * o.vt2 / (mu * o.vn1), rigid = psi1 - 4.0 * chi;
    printf("\nGross sliding, psi1 = 8 (t_c/50): psi2 = %.6f; the law's limit %.6f (lever arm r - "
           "delta/2); rigid body psi1 - 4 chi = %.6f; normal restitution %.6f\n",
           psi2, kappa * ref.vt2 / (mu * ref.vn1), rigid, o.vn2 / o.vn1);
    CHECK_CLOSE(o.vt2, ref.vt2, 1e-4);
    CHECK_CLOSE(psi2, rigid, 3e-3);
}

/// Worst relative error of v_t2 over 8 phases at dt = t_c/n.
static double worst(double vt, double mu, double ref, double n)
{
    double e = 0.0;
    for (int ph = 0; ph < 8; ++ph) {
        const bdl_verify_oblique o = bdl_verify_oblique_impact(
            vt, mu, bdl_verify_oblique_contact_time() / n, (ph + 0.5) / 8);
        e = fmax(e, isfinite(o.vt2) ? fabs(o.vt2 / ref - 1.0) : INFINITY);
    }
    return e;
}

static void convergence(void)
{
    static const double n[5] = {25, 50, 100, 200, 400};
    static const char *name[2] = {"full stick (v_t = 0.5 m/s, mu = 1e6)",
                                  "gross sliding (psi1 = 8)"};
    printf("\nTangential rebound error vs dt (worst |v_t2 - v_t2,ref|/|v_t2,ref| over 8 phases)\n\n"
           "| regime | t_c/25 | t_c/50 | t_c/100 | t_c/200 | t_c/400 | order 25-50 | 50-100 | "
           "100-200 | 200-400 |\n|---|---|---|---|---|---|---|---|---|---|\n");
    for (int s = 0; s < 2; ++s) {
        const double mu = s ? 0.3 : 1e6, vt = s ? bdl_verify_oblique_speed(8.0, mu) : 0.5;
        const double ref = bdl_verify_oblique_reference(vt, mu, s).vt2;
        double e[5];
        printf("| %s |", name[s]);
        for (int k = 0; k < 5; ++k)
            printf(" %.2e |", e[k] = worst(vt, mu, ref, n[k]));
        for (int k = 0; k < 4; ++k)
            printf(" %.2f |", bdl_verify_order(n[k], e[k], n[k + 1], e[k + 1]));
        printf("\n");
        const double q = bdl_verify_order(n[3], e[3], n[4], e[4]);
        CHECK_MSG(q >= (s ? 2.2 : 1.4), "%s: order %.2f over the finest pair", name[s], q);
        if (!s)
            CHECK_MSG(e[1] < 5e-3, "sticking error %g at t_c/50", e[1]);
    }
}

static void against_maw(void)
{
    const double kappa = bdl_verify_oblique_kappa(), chi = bdl_verify_oblique_chi(), mu = 0.3;
    const double psi[] = {0.1, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 4.0 * chi - 1.0, 5.0, 6.0, 8.0};
    const int count = (int)(sizeof psi / sizeof psi[0]);
    const double tc = bdl_verify_oblique_contact_time();
    printf("\nReduced rebound against reduced incidence, steel (nu = 0.3, chi = %.4f), mu = 0.3, "
           "v_n = 1 m/s; bedlam at t_c/50 and t_c/400 (phase 0.5); Maw, Barber & Fawcett's theory "
           "by the method of dimensionality reduction (2000 springs)\n\n",
           chi);
    printf("| psi1 | tan theta1 | e_t (t_c/400) | rebound angle [deg] | psi2 t_c/50 | psi2 "
           "t_c/400 | psi2 MBF | psi2 rigid body |\n|---|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < count; ++k) {
        const double vt = bdl_verify_oblique_speed(psi[k], mu);
        const bdl_verify_oblique a = bdl_verify_oblique_impact(vt, mu, tc / 50.0, 0.5);
        const bdl_verify_oblique b = bdl_verify_oblique_impact(vt, mu, tc / 400.0, 0.5);
        const double mbf = bdl_verify_mbf_psi2(0.3, 3.5, psi[k], 2000);
        const double rigid = psi[k] >= 4.0 * chi ? psi[k] - 4.0 * chi : 0.0;
        const double psi2 = kappa * b.vt2 / (mu * b.vn1);
        printf("| %.3f | %.3f | %.4f | %.2f | %.4f | %.4f | %.4f | %.4f |\n", psi[k], vt / b.vn1,
               b.vt2 / vt, atan2(b.vt2, b.vn2) * 180.0 / BDL_PI, kappa * a.vt2 / (mu * a.vn1), psi2,
               mbf, rigid);
        if (psi[k] >= 4.0 * chi - 1.0 + 1e-9) // gross slip throughout, in the theory too
            CHECK_MSG(fabs(psi2 - mbf) < 0.01, "psi1 %g: bedlam %g, MBF %g", psi[k], psi2, mbf);
    }
    // The theory's own landmarks, as Maw et al. state them: gross slip throughout from
    // psi1 = 4 chi - 1 on (there psi2 = -1), psi2 = psi1 - 4 chi beyond.
    CHECK_CLOSE(bdl_verify_mbf_psi2(0.3, 3.5, 4.0 * chi - 1.0, 2000), -1.0, 1e-3);
    CHECK_CLOSE(bdl_verify_mbf_psi2(0.3, 3.5, 8.0, 2000), 8.0 - 4.0 * chi, 1e-4);
}

/// psi2 against psi1 in steps of 0.25 for the plot (tools/plot_verification.sh): bedlam at t_c/100
/// (phase 0.5) and the theory (1000 springs: within 2e-5 of 2000).
static void curve(void)
{
    const double kappa = bdl_verify_oblique_kappa(), mu = 0.3;
    const double dt = bdl_verify_oblique_contact_time() / 100.0;
    printf("\nCurve: psi1, psi2 bedlam (t_c/100), psi2 Maw et al.\n");
    for (int k = 1; k <= 36; ++k) {
        const double psi1 = 0.25 * k;
        const bdl_verify_oblique o =
            bdl_verify_oblique_impact(bdl_verify_oblique_speed(psi1, mu), mu, dt, 0.5);
        printf("curve %.2f %.5f %.5f\n", psi1, kappa * o.vt2 / (mu * o.vn1),
               bdl_verify_mbf_psi2(0.3, 3.5, psi1, 1000));
    }
}

int main(void)
{
    sticking_through_guards();
    sphere_pair_through_guards();
    gross_sliding();
    convergence();
    against_maw();
    curve();
    return bdl_test_summary("test_oblique");
}
