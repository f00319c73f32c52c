// A vibrating container seen from its own frame ([wall] frame = container): the walls stand still
// and particles and gas feel gravity plus the inertial acceleration A w^2 sin(w t).
//
// 1. A ball resting on a floor vibrated at Gamma = 0.5 (it never takes off): the overlap history
//    in the container's frame matches the run with the floor moving through the lab frame, and
//    both follow m g_eff / k.
// 2. With `start`, the vibration waits: before it the floor stands still (lab frame) or adds
//    nothing to gravity (container frame), and the ball rests at m g / k; after it the motion is
//    A sin(w (t - start)).
// 3. The gas above it, at rest in the container: the pressure difference over the column is the
//    hydrostatic one of the effective gravity at the middle of the gas step, at every gas step.
#include <math.h>
#include <stdio.h>

#include "cfd/gas.h"
#include "check.h"
#include "scene_util.h"

#define SCENE                                                                                      \
    "[run]\nend_time = 1\ndt = %g\ngravity = 0 0 -9.81\n"                                          \
    "[domain]\nmin = -0.01 -0.01 -0.01\nmax = 0.01 0.01 0.03\n"                                    \
    "[contact]\nlaw = linear\n"                                                                    \
    "[species ball]\ndiameter = 0.004\ndensity = 2500\nstiffness = 100\nrestitution = 0.5\n"       \
    "friction = 0\n"                                                                               \
    "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\nmotion = vibrate\n"                \
    "frequency = 20\ngamma = 0.5\nframe = %s\n"                                                    \
    "[create ball]\ntype = lattice\nspecies = ball\ncount = 1\nregion_min = -0.002 -0.002 0\n"     \
    "region_max = 0.002 0.002 0.004\n"

static const double PI_ = 3.14159265358979323846;

/// Overlap of the ball with the floor, in the given frame.
static double overlap(const bdl_world *w, int container)
{
    const double r = w->particles.radius[0];
    double floor_z = container ? 0.0 : w->walls.offset[0].z;
    return r - (w->particles.pos[0].z - floor_z);
}

/// The largest difference of the overlaps in the two frames over t in [0.1, 0.4] s, relative to
/// the peak overlap; also checks the overlap against the quasi-static m g_eff / k.
static double compare_frames(double dt)
{
    bdl_world *lab = bdl_test_world(SCENE, dt, "lab");
    bdl_world *box = bdl_test_world(SCENE, dt, "container");
    CHECK(lab && box && lab->container == -1 && box->container == 0);
    if (!lab || !box)
        return INFINITY;
    // The lab floor starts moving up at A w; start the ball with it, so both runs begin alike.
    const double omega = 2.0 * PI_ * 20.0, A = 0.5 * 9.81 / (omega * omega);
    lab->particles.vel[0].z = A * omega;
    double worst = 0.0, peak = 0.0, lo = INFINITY, hi = -INFINITY;
    while (box->time < 0.4) {
        CHECK(bdl_world_step(lab) == BDL_OK && bdl_world_step(box) == BDL_OK);
        if (box->time < 0.1)
            continue;
        double a = overlap(lab, 0), b = overlap(box, 1);
        worst = fmax(worst, fabs(a - b));
        peak = fmax(peak, fabs(b));
        lo = fmin(lo, b), hi = fmax(hi, b);
    }
    // Nearly quasi-static (contact frequency 9x the drive): m g_eff / k, g_eff in [0.5, 1.5] g.
    const double m = 1.0 / box->particles.inv_mass[0], static_overlap = m * 9.81 / 100.0;
    printf("dt %.0e: ball on a floor at Gamma 0.5: overlap %.4g..%.4g um (m g_eff / k: %.4g..%.4g "
           "um); lab and container frames differ by at most %.3g um (%.2g %% of the peak)\n",
           dt, 1e6 * lo, 1e6 * hi, 1e6 * 0.5 * static_overlap, 1e6 * 1.5 * static_overlap,
           1e6 * worst, 100.0 * worst / peak);
    CHECK_MSG(fabs(lo / (0.5 * static_overlap) - 1.0) < 0.05 &&
                  fabs(hi / (1.5 * static_overlap) - 1.0) < 0.05,
              "overlap range %g..%g vs %g..%g", lo, hi, 0.5 * static_overlap, 1.5 * static_overlap);
    bdl_world_destroy(lab);
    bdl_world_destroy(box);
    return worst / peak;
}

/// The two frames are the same equations; they differ only through the integrator, whose
/// dashpot sees the half-step velocity: in the lab frame against the wall's velocity at the full
/// step. So they agree to first order in dt, and the difference halves with dt.
static void test_ball(void)
{
    double coarse = compare_frames(2e-5), fine = compare_frames(1e-5);
    printf("frames' difference halving dt: ratio %.3f (first order: 2)\n", coarse / fine);
    CHECK_MSG(coarse < 5e-3, "frames differ by %g of the peak overlap", coarse);
    CHECK_MSG(coarse / fine > 1.8 && coarse / fine < 2.2, "ratio %g", coarse / fine);
}

static void test_start(void)
{
    const double omega = 2.0 * PI_ * 20.0, A = 0.5 * 9.81 / (omega * omega), start = 0.1;
    for (int container = 0; container < 2; ++container) {
        // The frame value carries the start key into the same section.
        bdl_world *w =
            bdl_test_world(SCENE, 1e-5, container ? "container\nstart = 0.1" : "lab\nstart = 0.1");
        CHECK(w != NULL);
        if (!w)
            return;
        double worst = 0.0;
        while (w->time < start - 2e-5) {
            CHECK(bdl_world_step(w) == BDL_OK);
            worst = fmax(worst, bdl_v3_len(w->walls.offset[0]));
            worst = fmax(worst, fabs(bdl_world_gravity(w, w->time).z + 9.81));
        }
        const double m = 1.0 / w->particles.inv_mass[0];
        printf("start: %s frame, still before the start (largest offset or extra gravity %.3g); "
               "overlap %.4g um at rest (m g / k %.4g um)\n",
               container ? "container" : "lab", worst, 1e6 * overlap(w, container),
               1e6 * m * 9.81 / 100.0);
        CHECK(worst == 0.0);
        CHECK_CLOSE(overlap(w, container), m * 9.81 / 100.0, 0.01);
        const double t = start + 0.25 / 20.0; // a quarter period in: the top of the stroke
        if (container) {
            CHECK_CLOSE(bdl_world_gravity(w, t).z, -9.81 + A * omega * omega, 1e-9);
        } else {
            bdl_walls_update(&w->walls, t);
            CHECK_CLOSE(w->walls.offset[0].z, A, 1e-9);
            CHECK(fabs(w->walls.velocity[0].z) < 1e-9 * A * omega);
        }
        bdl_world_destroy(w);
    }
}

static void test_gas(void)
{
    bdl_world *w = bdl_test_world(SCENE "[gas]\ncells = 2 2 8\nzmin = wall\nzmax = outlet\n"
                                        "xmin = slip\nxmax = slip\nymin = slip\nymax = slip\n",
                                  2e-5, "container");
    CHECK(w && w->gas);
    if (!w || !w->gas)
        return;
    const bdl_grid *g = &w->gas->grid;
    const double rho = w->gas->def.density, omega = 2.0 * PI_ * 20.0;
    const double A = 0.5 * 9.81 / (omega * omega);
    double worst = 0.0, scale = rho * 9.81 * (g->n[2] - 1) * g->h[2];
    long seen = -1;
    int samples = 0;
    while (w->time < 0.2) {
        long step = w->step;
        CHECK(bdl_world_step(w) == BDL_OK);
        if (w->gas_steps == seen)
            continue;
        seen = w->gas_steps;
        // The gas step just taken started at `step` and spans gas_every particle steps.
        double mid = (double)step * w->dt + 0.5 * (double)w->gas_every * w->dt;
        double g_eff = 9.81 - A * omega * omega * sin(omega * mid); // downward
        double bottom = 0.0, top = 0.0;
        for (int j = 0; j < g->n[1]; ++j)
            for (int i = 0; i < g->n[0]; ++i) {
                bottom += w->gas->p[bdl_grid_index(g, i, j, 0)];
                top += w->gas->p[bdl_grid_index(g, i, j, g->n[2] - 1)];
            }
        double dp = (bottom - top) / (g->n[0] * g->n[1]);
        worst = fmax(worst, fabs(dp - rho * g_eff * (g->n[2] - 1) * g->h[2]));
        ++samples;
    }
    printf("gas column in the container's frame: %d gas steps, pressure difference within %.3g Pa "
           "(%.2g of rho g H) of rho g_eff H\n",
           samples, worst, worst / scale);
    CHECK(samples > 20);
    // The ball's own motion stirs the gas by about 1e-3 rho g H; evaluating g_eff at the start of
    // the gas step instead of its middle would be off by about 1.5e-2.
    CHECK_MSG(worst < 3e-3 * scale, "hydrostatic pressure off by %g Pa", worst);
    bdl_world_destroy(w);
}

int main(void)
{
    test_ball();
    test_start();
    test_gas();
    return bdl_test_summary("test_container");
}
