// Conservation in collisions (MFiX DEM05-style oblique collisions; Chung & Ooi 2011 test 3).
//
// (a) Oblique, frictional collisions of two spheres of different radii and densities with initial
//     spins, both laws (Hertz also with rolling resistance): total linear momentum sum m v and
//     total angular momentum about the origin sum (m x × v + I w), I = 2/5 m r^2, are conserved
//     to round-off at every step. Pair forces are stored once and applied with opposite signs,
//     and the torques use lever arms that add up to the centre distance, so with velocity Verlet
//     both are conserved exactly in exact arithmetic: x(t+dt) × v(t+dt/2) = x(t) × v(t+dt/2), and
//     each half kick changes L by h (x_i × F + x_j × (-F) + T_i + T_j) = h (d × F - d × F) = 0.
//     What remains is rounding: each step adds a few roundings of terms no larger than the
//     magnitudes sum |m v| and sum (|m x × v| + |I w|), i.e. ~1e-16 of them per step; over the
//     few thousand steps of a run, if they all added up, a few 1e-13. We require 1e-12 of those
//     initial magnitudes (10x margin).
// (b) e = 1, frictionless, head-on: the relative kinetic-energy error after one collision falls at
//     second order with dt (velocity Verlet is second order for conservative forces; the onset of
//     contact only kinks the linear force and leaves the Hertz force C^1). Worst over 8 contact
//     phases; observed order >= 1.8 between every pair of the dts used.
// (c) 1000 elastic frictionless spheres in a periodic box, volume fraction 0.15, random velocities,
//     no gravity, 1e5 steps at dt = t_c/50: total energy (kinetic + rotational + elastic, from
//     bdl_diagnostics_compute) shows no secular drift: max |E(t) - E(0)|/E(0) <= 1e-3, sampled
//     every 1000 steps.
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <time.h>

#include "check.h"
#include "scene_util.h"
#include "output/diagnostics.h"
#include "verify/verify.h"

#define PI 3.14159265358979323846

static double inertia(const bdl_particles *p, long i)
{
    return 1.0 / bdl_particle_inv_inertia(p, i);
}

/// Total linear and angular momentum (about the origin), and the magnitudes they are made of.
static void momenta(const bdl_world *w, bdl_vec3 *P, bdl_vec3 *L, double *p_scale, double *l_scale)
{
    const bdl_particles *p = &w->particles;
    *P = *L = bdl_v3_zero();
    *p_scale = *l_scale = 0.0;
    for (long i = 0; i < p->count; ++i) {
        double m = 1.0 / p->inv_mass[i];
        bdl_vec3 mv = bdl_v3_scale(p->vel[i], m);
        bdl_vec3 orbital = bdl_v3_cross(p->pos[i], mv);
        bdl_vec3 spin = bdl_v3_scale(p->omega[i], inertia(p, i));
        *P = bdl_v3_add(*P, mv);
        *L = bdl_v3_add(*L, bdl_v3_add(orbital, spin));
        *p_scale += bdl_v3_len(mv);
        *l_scale += bdl_v3_len(orbital) + bdl_v3_len(spin);
    }
}

static void conservation(void)
{
    printf("(a) Oblique frictional collisions: momentum conservation (max deviation over all "
           "steps)\n\n");
    printf("| law | steps | contact steps | |dP|max / sum|m v| | |dL|max / sum(|m x×v|+|I w|) | "
           "|dw_A| (rad/s) |\n");
    printf("|---|---|---|---|---|---|\n");
    for (int hertz = 0; hertz <= 1; ++hertz) {
        // Sphere A: d = 10 mm, glass; sphere B: d = 6 mm, steel. B approaches A obliquely (impact
        // parameter about half the sum of the radii) with both spinning.
        bdl_world *w = bdl_test_world(
            "[run]\nend_time = 1\ndt_fraction = 0.02\ngravity = 0 0 0\n"
            "[domain]\nmin = -0.05 -0.05 -0.05\nmax = 0.05 0.05 0.05\n"
            "[contact]\nlaw = %s\nrolling = %s\n"
            "[species glass]\ndiameter = 0.01\ndensity = 2500\n%s\nrestitution = 0.7\nfriction = "
            "0.4\n"
            "tangential_damping_ratio = 0.3\nrolling_friction = 0.05\n"
            "[species steel]\ndiameter = 0.006\ndensity = 7800\n%s\nrestitution = 0.8\nfriction = "
            "0.6\n"
            "tangential_damping_ratio = 0.3\nrolling_friction = 0.02\n"
            "[create a]\ntype = lattice\nspecies = glass\ncount = 1\nvelocity = 0.3 0.1 -0.05\n"
            "region_min = -0.011 0.001 0.002\nregion_max = 0.004 0.016 0.017\n"
            "[create b]\ntype = lattice\nspecies = steel\ncount = 1\nvelocity = -0.4 -0.05 0.1\n"
            "region_min = 0.0025 0.0015 0.0045\nregion_max = 0.0125 0.0115 0.0145\n",
            hertz ? "hertz" : "linear", hertz ? "constant" : "none",
            hertz ? "youngs_modulus = 5e8\npoisson_ratio = 0.25" : "stiffness = 2e5",
            hertz ? "youngs_modulus = 2e9\npoisson_ratio = 0.3" : "stiffness = 5e5");
        bdl_particles *p = &w->particles;
        // Initial spins (no scene key for them): set directly; forces are recomputed after.
        p->omega[bdl_test_find(w, 0)] = bdl_v3(40.0, -25.0, 60.0);
        p->omega[bdl_test_find(w, 1)] = bdl_v3(-80.0, 50.0, 30.0);
        bdl_world_compute_forces(w);
        bdl_vec3 w_a0 = p->omega[bdl_test_find(w, 0)];
        bdl_vec3 P0, L0;
        double p_scale, l_scale, dp = 0.0, dl = 0.0;
        momenta(w, &P0, &L0, &p_scale, &l_scale);
        int contact_steps = 0, steps = 0;
        // Approach, contact, and stop once the spheres have separated.
        while (steps < 50000) {
            bdl_world_step(w);
            ++steps;
            int touching = 0;
            for (long k = 0; k < w->neighbor.pair_count; ++k)
                touching |= w->neighbor.touching[k];
            contact_steps += touching;
            bdl_vec3 P, L;
            double ps, ls;
            momenta(w, &P, &L, &ps, &ls);
            dp = fmax(dp, bdl_v3_len(bdl_v3_sub(P, P0)));
            dl = fmax(dl, bdl_v3_len(bdl_v3_sub(L, L0)));
            if (!touching && contact_steps > 0)
                break;
        }
        double dw = bdl_v3_len(bdl_v3_sub(p->omega[bdl_test_find(w, 0)], w_a0));
        printf("| %s | %d | %d | %.2e | %.2e | %.3g |\n", hertz ? "hertz + rolling" : "linear",
               steps, contact_steps, dp / p_scale, dl / l_scale, dw);
        CHECK_MSG(contact_steps >= 10, "the spheres must collide (%d contact steps)",
                  contact_steps);
        CHECK(dw > 1.0); // friction acted: the spin of A changed
        CHECK_MSG(dp <= 1e-12 * p_scale, "linear momentum drift %.3g of %.3g", dp, p_scale);
        CHECK_MSG(dl <= 1e-12 * l_scale, "angular momentum drift %.3g of %.3g", dl, l_scale);
        bdl_world_destroy(w);
    }
}

static void energy_order(void)
{
    static const double div[5] = {25, 50, 100, 200, 400};
    const double v = 1.0;
    printf("\n(b) Elastic head-on collision, v_rel = %g m/s: worst relative kinetic-energy error "
           "after the collision over 8 contact phases\n\n",
           v);
    printf("| law | t_c/25 | t_c/50 | t_c/100 | t_c/200 | t_c/400 | order 25-50 | 50-100 | 100-200 "
           "| 200-400 |\n");
    printf("|---|---|---|---|---|---|---|---|---|---|\n");
    for (int hertz = 0; hertz <= 1; ++hertz) {
        double tc = bdl_verify_collision_contact_time(hertz, v);
        double err[5], order[4];
        for (int k = 0; k < 5; ++k) {
            err[k] = 0.0;
            for (int ph = 0; ph < 8; ++ph)
                err[k] = fmax(err[k], bdl_verify_collision_energy(hertz, v, tc / div[k],
                                                                  (ph + 0.5) / 8.0, NULL));
        }
        printf("| %s |", hertz ? "hertz" : "linear");
        for (int k = 0; k < 5; ++k)
            printf(" %.2e |", err[k]);
        for (int k = 0; k < 4; ++k) {
            order[k] = log(err[k] / err[k + 1]) / log(div[k + 1] / div[k]);
            printf(" %.2f |", order[k]);
        }
        printf("\n");
        for (int k = 0; k < 4; ++k)
            CHECK_MSG(order[k] >= 1.8, "%s: observed order %.2f between t_c/%g and t_c/%g",
                      hertz ? "hertz" : "linear", order[k], div[k], div[k + 1]);
    }
}

static double wall_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void gas_energy(void)
{
    // d = 1 mm glass, k_n = 1.5e4 N/m: the fastest approaches (~1.5 m/s) overlap ~1 % of d.
    // 1000 spheres in a periodic cube of side 15.2 d: volume fraction 0.15.
    const int n = 1000;
    const double d = 1e-3, phi = 0.15;
    double side = cbrt(n * PI / 6.0 * d * d * d / phi);
    bdl_world *w =
        bdl_test_world("[run]\nend_time = 1\ndt_fraction = 0.02\ngravity = 0 0 0\nseed = 11\n"
                       "[domain]\nmin = 0 0 0\nmax = %.17g %.17g %.17g\nperiodic = x y z\n"
                       "[contact]\nlaw = linear\n"
                       "[species glass]\ndiameter = %.17g\ndensity = 2500\nstiffness = "
                       "1.5e4\nrestitution = 1\nfriction = 0\n"
                       "[create gas]\ntype = random\ncount = %d\nregion_min = 0 0 0\nregion_max = "
                       "%.17g %.17g %.17g\n"
                       "velocity_jitter = 1\n",
                       side, side, side, d, n, side, side, side);
    CHECK(w->particles.count == n);
    const long steps = 100000, every = 1000;
    bdl_diagnostics diag;
    bdl_diagnostics_compute(w, 0.0, &diag);
    double e0 = bdl_diagnostics_total_energy(&diag), worst = 0.0, last = 0.0;
    long collisions_seen = 0;
    double t0 = wall_seconds();
    printf("\n(c) %d elastic spheres, periodic box, volume fraction %.2f, dt = t_c/%.0f, %ld "
           "steps\n\n",
           n, phi, 1.0 / w->contact_time_dt_ratio, steps);
    printf("| step | (E - E0)/E0 | mean coordination |\n|---|---|---|\n");
    for (long s = 1; s <= steps; ++s) {
        bdl_world_step(w);
        if (s % every)
            continue;
        bdl_diagnostics_compute(w, 0.0, &diag);
        double rel = (bdl_diagnostics_total_energy(&diag) - e0) / e0;
        worst = fmax(worst, fabs(rel));
        last = rel;
        collisions_seen += diag.mean_coordination > 0.0;
        if (s % (10 * every) == 0)
            printf("| %ld | %+.2e | %.4f |\n", s, rel, diag.mean_coordination);
    }
    printf(
        "\nmax |E - E0|/E0 = %.2e, final %+.2e (E0 = %.4g J); %.1f s wall, %ld neighbour builds\n",
        worst, last, e0, wall_seconds() - t0, w->neighbor.builds);
    CHECK(collisions_seen > 10); // contacts were present at the samples: the gas does collide
    CHECK_MSG(worst <= 1e-3, "energy drift %.3g", worst);
    bdl_world_destroy(w);
}

int main(void)
{
    omp_set_num_threads(1);
    conservation();
    energy_order();
    gas_energy();
    return bdl_test_summary("test_collision");
}
