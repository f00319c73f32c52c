// bedlam — the verification registry: what each case checks, against what, at which
// refinements, and what counts as a pass.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "analysis/rheology.h"
#include "cfd/gas.h"
#include "verify/verify.h"

static double finite_or_inf(double x) { return isfinite(x) ? x : INFINITY; }

// Bounce: e = 0.6 at 0.5 m/s, dt = t_c/N.
static bdl_result run_restitution(int series, double n, bdl_verify_result *out)
{
    const double e = 0.6, v = 0.5, dt = bdl_verify_bounce_contact_time(series, e, v) / n;
    out->error = bdl_verify_restitution_worst(series, e, v, dt, &out->steps);
    out->exact = e;
    out->value = e * (1.0 - out->error); // the worst case's magnitude (its sign is not kept)
    return isfinite(out->error) ? BDL_OK : BDL_ERR_UNSTABLE;
}

static bdl_result run_hertz_duration(int series, double n, bdl_verify_result *out)
{
    const double v = 1.0, ref = bdl_verify_hertz_time(series, v);
    double rebound = 0.0;
    out->value = bdl_verify_hertz_duration(series, v, ref / n, &rebound, &out->steps);
    out->exact = ref;
    out->error = out->value > 0.0 ? fabs(out->value - ref) / ref : INFINITY;
    return out->value > 0.0 ? BDL_OK : BDL_ERR_UNSTABLE;
}

static bdl_result run_slide_roll(int series, double n, bdl_verify_result *out)
{
    const double mu = 0.3, v0 = 0.5, ts = 2.0 * v0 / (7.0 * mu * 9.81);
    bdl_verify_slide s = bdl_verify_slide_roll(series, mu, v0, 1.0 / n);
    out->value = s.t_fit;
    out->exact = ts;
    out->error = finite_or_inf(fabs(s.t_fit - ts) / ts);
    out->steps = s.steps;
    return s.t_fit > 0.0 && s.forward == 0 ? BDL_OK : BDL_ERR_UNSTABLE;
}

static bdl_result run_collision_energy(int series, double n, bdl_verify_result *out)
{
    const double v = 1.0, dt = bdl_verify_collision_contact_time(series, v) / n;
    out->error = 0.0;
    for (int ph = 0; ph < 8; ++ph)
        out->error = fmax(
            out->error, bdl_verify_collision_energy(series, v, dt, (ph + 0.5) / 8.0, &out->steps));
    out->exact = 0.0;
    out->value = out->error;
    return isfinite(out->error) ? BDL_OK : BDL_ERR_UNSTABLE;
}

// Oblique elastic impact: the tangential rebound against the continuum limit of the law, in full
// stick (v_t = 0.5 m/s, mu = 1e6) and in gross sliding (psi1 = 8, mu = 0.3); dt = t_c/N.
static bdl_result run_oblique(int series, double n, bdl_verify_result *out)
{
    const double mu = series ? 0.3 : 1e6, vt = series ? bdl_verify_oblique_speed(8.0, mu) : 0.5;
    const bdl_verify_oblique ref = bdl_verify_oblique_reference(vt, mu, series);
    out->exact = ref.vt2 / vt;
    out->error = 0.0;
    out->value = NAN;
    for (int ph = 0; ph < 8; ++ph) {
        const double dt = bdl_verify_oblique_contact_time() / n;
        const bdl_verify_oblique o = bdl_verify_oblique_impact(vt, mu, dt, (ph + 0.5) / 8.0);
        const double e = finite_or_inf(fabs(o.vt2 - ref.vt2) / fabs(ref.vt2));
        if (!(e <= out->error))
            out->value = o.vt2 / vt; // the worst phase's
        out->error = fmax(out->error, e);
        out->steps += o.steps;
    }
    return isfinite(out->error) ? BDL_OK : BDL_ERR_UNSTABLE;
}

// Silo discharge: series 0 and 1 the orifices D = 6 d and 8 d (18 and 24 mm).
static bdl_result run_silo(int series, double n, bdl_verify_result *out)
{
    (void)n;
    bdl_verify_silo s;
    bdl_result r = bdl_verify_silo_discharge(series ? 0.024 : 0.018, 11000, 1.2, &s);
    printf("  silo D = %.0f mm: rho_b %.1f kg/m^3, W %.5f kg/s against Beverloo %.5f kg/s; %ld "
           "out + %ld left of 11000, mass balance %.1e\n",
           1000.0 * s.orifice, s.bulk_density, s.rate, s.rate_beverloo, s.out, s.left,
           s.mass_imbalance);
    out->value = s.rate;
    out->exact = s.rate_beverloo;
    out->error = finite_or_inf(fabs(s.rate / s.rate_beverloo - 1.0));
    out->steps = s.steps;
    return r;
}

/// Prints a shear cell's averages beside Lun et al.
static void print_shear(const char *what, const bdl_verify_shear *s)
{
    printf("  %s: nu %.4f, %.4g/s, %ld samples: T %.4g (Lun %.4g), p %.4g Pa (Lun %.4g; at the "
           "run's T %.4g), tau %.4g Pa (Lun %.4g; at the run's T %.4g)\n",
           what, s->solids_fraction, s->shear_rate, s->samples, s->temperature, s->lun_temperature,
           s->pressure, s->lun_pressure, s->lun_pressure_at_t, s->shear_stress, s->lun_shear_stress,
           s->lun_shear_stress_at_t);
}

/// A shear cell (e = 0.7, 1 s) scored against Lun et al.: at its solids fraction and shear rate,
/// or with `at_t` at its own temperature too; the larger of the pressure's and shear stress's
/// relative errors.
static bdl_result shear_case(double nu, int walls, int at_t, bdl_verify_result *out)
{
    bdl_verify_shear s;
    const bdl_verify_shear_setup set = {
        .solids_fraction = nu, .restitution = 0.7, .walls = walls, .from = 0.1, .to = 1.0};
    const bdl_result r = bdl_verify_shear_cell(&set, &s);
    print_shear(walls ? "wall-driven bulk" : "Lees-Edwards", &s);
    const double p = at_t ? s.lun_pressure_at_t : s.lun_pressure;
    const double tau = at_t ? s.lun_shear_stress_at_t : s.lun_shear_stress;
    out->value = s.pressure;
    out->exact = p;
    out->error = finite_or_inf(fmax(fabs(s.pressure / p - 1.0), fabs(s.shear_stress / tau - 1.0)));
    out->steps = s.steps;
    return r;
}

// Lees–Edwards shear of frictionless spheres (e = 0.7) at solids fractions 0.2, 0.3, 0.4.
static bdl_result run_shear_lun(int series, double n, bdl_verify_result *out)
{
    (void)n;
    return shear_case(0.2 + 0.1 * series, 0, 0, out);
}

// Lees–Edwards shear of dilute spheres (solids fraction 0.05, e = 0.7, in a box 26 mean free
// paths high), in a medium moving with the shear that damps them at b [1/s] or without one,
// against the Boltzmann equation's steady shear solved by Grad's method: the reduced viscosity
// and shear rate at the run's own temperature (which fixes the reduced drag b / nu0).
static bdl_result dilute_case(double b, bdl_verify_result *out)
{
    bdl_verify_shear s;
    const double e = 0.7, d = 0.0053, rho = 1395.0;
    const bdl_verify_shear_setup set = {.solids_fraction = 0.05,
                                        .restitution = e,
                                        .box = {0.096, 0.096, 0.288},
                                        .from = 0.3,
                                        .to = 1.0,
                                        .damping = b};
    const bdl_result r = bdl_verify_shear_cell(&set, &s);
    print_shear("Lees-Edwards, dilute", &s);
    double visc, rate, visc_grad, rate_grad, n1_grad;
    bdl_rheology_reduced(s.solids_fraction, d, rho, s.temperature, s.shear_stress, s.shear_rate,
                         &visc, &rate);
    const double nu0 = fabs(s.shear_rate) / rate; // the run's collision frequency p / eta0
    bdl_grad_dilute_reduced(e, b / nu0, &visc_grad, &rate_grad, &n1_grad);
    const bdl_grad_shear g =
        bdl_grad_dilute_shear_damped(s.solids_fraction, e, d, rho, s.shear_rate, b);
    printf("  b %g/s (b/nu0 %.4f): eta/eta0 %.4f (Grad %.4f), shear rate/nu0 %.4f (Grad %.4f), "
           "N1/p %.3f (Grad %.3f); T %.4f m^2/s^2 (Grad at this b %.4f)\n",
           b, b / nu0, visc, visc_grad, rate, rate_grad, s.n1 / s.pressure, n1_grad, s.temperature,
           g.temperature);
    if (b == 0.0) {
        const bdl_lun_state l = bdl_lun_simple_shear(1e-9, e, d, rho, s.shear_rate);
        double visc_lun, rate_lun;
        bdl_rheology_reduced(1e-9, d, rho, l.temperature, l.shear_stress, s.shear_rate, &visc_lun,
                             &rate_lun);
        printf("  Lun et al.'s dilute limit: eta/eta0 %.4f, shear rate/nu0 %.4f\n", visc_lun,
               rate_lun);
    }
    out->value = visc;
    out->exact = visc_grad;
    out->error = finite_or_inf(fmax(fabs(visc / visc_grad - 1.0), fabs(rate / rate_grad - 1.0)));
    out->steps = s.steps;
    return r;
}

static bdl_result run_shear_dilute(int series, double n, bdl_verify_result *out)
{
    (void)series;
    (void)n;
    return dilute_case(0.0, out);
}

// The same in a medium that damps at 3 and 6/s (T falls to 0.80 and 0.59 of the dry run's; Grad:
// 0.76 and 0.56).
static bdl_result run_shear_damped(int series, double n, bdl_verify_result *out)
{
    (void)n;
    return dilute_case(3.0 * (series + 1), out);
}

// The bulk of a wall-driven cell and a Lees–Edwards box at solids fraction 0.2: the constitutive
// relations at each run's own temperature.
static bdl_result run_shear_walls(int series, double n, bdl_verify_result *out)
{
    (void)n;
    return shear_case(0.2, series, 1, out);
}

static bdl_result run_column(int series, double n, bdl_verify_result *out)
{
    bdl_verify_column c = bdl_verify_static_column(series, 1.0 / n);
    out->error = 0.0;
    for (int k = 0; k < BDL_VERIFY_COLUMN; ++k)
        out->error = fmax(out->error, fabs(c.overlap[k] - c.theory[k]) / c.theory[k]);
    out->error = finite_or_inf(out->error);
    out->value = c.overlap[0];
    out->exact = c.theory[0];
    out->steps = c.steps;
    return c.kinetic < c.kinetic_limit ? BDL_OK : BDL_ERR_UNSTABLE;
}

// The small rod bed of Mahajan (2019) packed at dt = t_c/N: its height against the thesis's.
static bdl_result run_rod_bed(int series, double n, bdl_verify_result *out)
{
    (void)series;
    bdl_verify_rod_bed b;
    bdl_result r = bdl_verify_rod_bed_run(1.0 / n, &b);
    printf("  rod bed, dt = t_c/%g: height %.4f m (thesis 0.106), solids %.3f, <|cos|> to the "
           "vertical %.3f, S %.3f, %.0f%% of the rods within 20 degrees of the horizontal; %.2f "
           "s simulated, KE %.1e m g d per rod\n",
           n, b.height, b.bulk, b.vertical_cos, b.order, 100.0 * (b.tilt[0] + b.tilt[1]), b.time,
           b.kinetic);
    out->value = b.height;
    out->exact = 0.106;
    out->error = r == BDL_OK ? fabs(b.height / 0.106 - 1.0) : INFINITY;
    out->steps = b.steps;
    return r;
}

static bdl_result run_poiseuille(int series, double n, bdl_verify_result *out)
{
    (void)series;
    double cross = 0.0;
    out->error = bdl_verify_poiseuille((int)n, &cross, &out->steps);
    out->exact = 0.0;
    out->value = cross;
    return isfinite(out->error) ? BDL_OK : BDL_ERR_UNSTABLE;
}

static bdl_result run_cavity(int series, double n, bdl_verify_result *out)
{
    static const bdl_convection scheme[2] = {BDL_CONVECTION_CENTRAL, BDL_CONVECTION_VANLEER};
    double du = 0.0, dv = 0.0;
    out->error = bdl_verify_cavity((int)n, scheme[series], &du, &dv, 0, &out->steps);
    out->value = du;
    out->exact = dv;
    return out->error >= 0.0 ? BDL_OK : BDL_ERR_UNSTABLE;
}

static bdl_result run_terminal(int series, double n, bdl_verify_result *out)
{
    static const double d[3] = {40e-6, 200e-6, 1.0e-3}, rho_p[3] = {1000.0, 2500.0, 2500.0};
    bdl_verify_terminal t =
        bdl_verify_terminal_slip(d[series], rho_p[series], BDL_DRAG_SCHILLER_NAUMANN, (int)n);
    out->value = t.slip;
    out->exact = t.expected;
    out->error = finite_or_inf(fabs(t.slip / t.expected - 1.0));
    out->steps = t.steps;
    return isfinite(t.slip) ? BDL_OK : BDL_ERR_UNSTABLE;
}

static bdl_result run_ergun(int series, double n, bdl_verify_result *out)
{
    (void)series;
    const double U[2] = {0.3, 0.6};
    double ratio[2], eps[2];
    bdl_result r = bdl_verify_packed_bed((int)n, U, 2, ratio, eps, &out->steps);
    out->value = ratio[1];
    out->exact = 1.0;
    out->error =
        r == BDL_OK ? finite_or_inf(fmax(fabs(ratio[0] - 1.0), fabs(ratio[1] - 1.0))) : INFINITY;
    return r;
}

static bdl_result run_umf(int series, double n, bdl_verify_result *out)
{
    (void)series;
    double down = NAN, up = NAN, wen_yu = NAN;
    bdl_result r = bdl_verify_umf(1e-3 * n, &down, &up, &wen_yu, 0, &out->steps);
    out->value = down;
    out->exact = wen_yu;
    out->error = r == BDL_OK
                     ? finite_or_inf(fmax(fabs(down / wen_yu - 1.0), fabs(up / wen_yu - 1.0)))
                     : INFINITY;
    return r;
}

static bdl_result run_settling(int series, double n, bdl_verify_result *out)
{
    static const double phi[3] = {0.1, 0.2, 0.3};
    bdl_verify_settling s;
    bdl_result r = bdl_verify_suspension(phi[series], (int)lrint(8.0 / n), &s);
    out->value = s.measured;
    out->exact = s.expected;
    out->error = r == BDL_OK ? finite_or_inf(fabs(s.measured / s.expected - 1.0)) : INFINITY;
    out->steps = s.steps;
    return r;
}

// The particle momentum balance of a slugging bed with its floor on the inlet plane or raised
// two cells (series), averaged over N seconds after one second of start-up.
static bdl_result run_bed_balance(int series, double n, bdl_verify_result *out)
{
    bdl_verify_balance b;
    bdl_result r = bdl_verify_bed_balance(series == 0 ? 0 : 2, 1.0, n, &b);
    printf("  bed balance, floor %s, %g s: pressure drop - gas column %.2f Pa, weight %.2f Pa, "
           "walls %.2f Pa, momentum rate %.2f Pa: residual %.2f Pa (%.2f %% of the weight); of "
           "it the gas's budget (pressure drop - gas column - gas force on the beads net of "
           "buoyancy %.2f Pa) %.2f Pa, the beads' Newton %.2f Pa; the gas's net inflow of "
           "momentum %.2f Pa\n",
           series == 0 ? "at the inlet" : "raised 2 cells", n, b.pressure, b.weight, b.wall,
           b.momentum_rate, b.residual, 100.0 * b.residual / b.weight, b.fluid, b.gas_residual,
           b.residual - b.gas_residual, b.inflow_momentum);
    out->value = b.residual;
    out->exact = 0.0;
    out->error = r == BDL_OK ? finite_or_inf(fabs(b.residual / b.weight)) : INFINITY;
    out->steps = b.steps;
    return r;
}

// Parcels settling on a lattice: N refines the layers of parcels per cell (series 0), the cells
// along the column (series 1) or the step (series 2), the others held at 4 layers, 20 cells and
// 0.01 s.
static bdl_result run_parcel_settling(int series, double n, bdl_verify_result *out)
{
    const int layers = series == 0 ? (int)lrint(n) : 4;
    const int cells = series == 1 ? (int)lrint(10 * n) : 20;
    const double dt = series == 2 ? 0.02 / n : 0.01;
    bdl_verify_settling s;
    bdl_result r = bdl_verify_parcel_settling(layers, cells, dt, 0.1, 0, &s);
    printf("  parcels: %d layers per cell, %d cells, dt %g s: interface %.5g mm/s, model %.5g "
           "mm/s (n = %.3f, Re_t %.2g)\n",
           layers, cells, dt, 1e3 * s.measured, 1e3 * s.expected, s.n, s.re_t);
    out->value = s.measured;
    out->exact = s.expected;
    out->error = r == BDL_OK ? finite_or_inf(fabs(s.measured / s.expected - 1.0)) : INFINITY;
    out->steps = s.steps;
    return r;
}

// Bimodal sedimentation: N = 1 the paper's case A, 2 case B; series 0 the heavy front, 1 the top
// interface, against the Kynch-type speeds of the model (digest of seed 001, sec. 3.1). One run
// serves both series.
static bdl_result run_parcel_bimodal(int series, double n, bdl_verify_result *out)
{
    static double done = 0.0;
    static bdl_verify_bimodal b;
    static bdl_result r = BDL_OK;
    if (done != n) {
        r = bdl_verify_parcel_bimodal(n > 1.5, 100.0, &b);
        done = n;
        printf("  bimodal case %s: heavy front %.5f cm/s (Kynch 0.0542), light zone %.5f cm/s "
               "(0.0192)\n",
               n > 1.5 ? "B" : "A", 100.0 * b.heavy_front, 100.0 * b.light_zone);
    }
    out->exact = series == 0 ? 0.0542e-2 : 0.0192e-2;
    out->value = series == 0 ? b.heavy_front : b.light_zone;
    out->error = r == BDL_OK ? finite_or_inf(fabs(out->value / out->exact - 1.0)) : INFINITY;
    out->steps = series == 0 ? b.steps : 0;
    return r;
}

// The Boycott effect: the 35-degree column to 800 s (one run serves all series): series 0 the
// interface's axial position against the PNK estimate above the sediment, the worst sample from
// 100 s on; series 1 its mean speed over the first 200 s against PNK's; series 2 the interface
// against PNK without the sediment from 100 to 500 s.
static bdl_result run_parcel_boycott(int series, double n, bdl_verify_result *out)
{
    static int done = 0;
    static bdl_verify_boycott b;
    static bdl_result r = BDL_OK;
    (void)n;
    if (!done) {
        r = bdl_verify_parcel_boycott(0, 800.0, &b);
        done = 1;
        printf("  35-degree column, v0 = %.4g cm/s, sediment at %.3f; t [s], interface y [cm], "
               "PNK [cm], PNK above the sediment [cm]:\n",
               100.0 * b.v0, b.theta_sed);
        for (int k = 1; k < b.samples; k += 2)
            printf("    %5.0f  %6.2f  %6.2f  %6.2f\n", b.t[k], 100.0 * b.y[k], 100.0 * b.y_pnk[k],
                   100.0 * b.y_sed[k]);
    }
    const double pnk = b.speed_200_pnk;
    const double worst[3] = {b.worst, fabs(b.speed_200 / pnk - 1.0), b.worst_pnk};
    out->exact = series == 1 ? pnk : 0.0;
    out->value = series == 1 ? b.speed_200 : worst[series];
    out->error = r != BDL_OK ? INFINITY : finite_or_inf(worst[series]);
    out->steps = series == 1 ? 0 : b.steps;
    return r;
}

// Two-fluid model: the homogeneous cooling state, N steps per Haff time.
static bdl_result run_tfm_cooling(int series, double n, bdl_verify_result *out)
{
    (void)series;
    bdl_result r = bdl_verify_tfm_cooling((int)lrint(n), &out->error, &out->steps);
    out->exact = 1.0 / 16.0;
    out->value = out->exact * (1.0 + out->error); // theta / theta0 (the sign is not kept)
    return r;
}

// Two-fluid model: the settling column on N cells (dt ~ 1/N^2); the interface's error over its
// fall.
static bdl_result run_tfm_settling(int series, double n, bdl_verify_result *out)
{
    (void)series;
    bdl_verify_sediment s;
    bdl_result r = bdl_verify_tfm_settling((int)lrint(n), &s);
    printf("  settling column, %d cells: top %.5f m (Kynch %.5f); fraction %.3g to %.5f, bed "
           "%.5f (Schaeffer %.5f)\n",
           (int)lrint(n), s.interface, s.expected, s.eps_low, s.eps_peak, s.eps_bed,
           s.eps_bed_expected);
    out->value = s.interface;
    out->exact = s.expected;
    out->error =
        r == BDL_OK ? finite_or_inf(fabs(s.interface - s.expected) / (0.1 - s.expected)) : INFINITY;
    out->steps = s.steps;
    if (r == BDL_OK && (s.eps_low < 0.0 || s.eps_peak > s.eps_bed_expected + 2e-3))
        r = BDL_ERR_UNSTABLE; // below zero, or packed past Schaeffer's fraction for the weight
    return r;
}

// Two-fluid model: the granular energy's transport against a manufactured solution on N cells.
static bdl_result run_tfm_energy(int series, double n, bdl_verify_result *out)
{
    (void)series;
    bdl_verify_energy e;
    bdl_result r = bdl_verify_tfm_energy((int)lrint(n), &e);
    printf("  granular energy, %d cells: largest |theta / theta_exact - 1| %.3e (conduction up to "
           "%.2f of the source; solids at most %.2e m/s)\n",
           (int)lrint(n), e.error, e.conduction_share, e.speed);
    out->exact = 0.0;
    out->value = e.error;
    out->error = r == BDL_OK ? finite_or_inf(e.error) : INFINITY;
    out->steps = e.steps;
    return r;
}

// The acceptance, quick-set, series and level fields of a case stand on one line each.
// clang-format off
static const bdl_verify_case cases[] = {
    {
        .name = "restitution",
        .breaks = "above dt = t_c/5 (`[guards] dt_refuse` 0.2) bedlam refuses the scene; between "
                  "t_c/20 and t_c/5 it warns; restitution 0.01 and 1.0 stay bounded over long runs "
                  "(stability.md: test_restitution_limits).",
        .title = "Restitution of a sphere bouncing on a plane",
        .model = "normal contact laws (linear spring-dashpot; Hertz with the damping solved for "
                 "the configured e) in velocity Verlet",
        .reference = "the configured restitution e = 0.6 (MFiX DEM01/DEM02), impact at 0.5 m/s, "
                     "gravity off",
        .measure = "worst |e_realised - e|/e over 8 phases of first touch within a step",
        .param = "N = t_c/dt (steps per contact time)",
        .order_note = "first order: the linear dashpot force jumps at first touch, and both laws "
                      "evaluate the dashpot with the half-step velocity",
        .tolerance = 0.05, .tolerance_level = 1, .order_min = 0.8,
        .quick = 1, .quick_levels = 3,
        .series_count = 2, .series = {"linear", "hertz"},
        .level_count = 5, .level = {25, 50, 100, 200, 400},
        .run = run_restitution,
    },
    {
        .name = "hertz_duration",
        .breaks = "70 GPa glass at 100 µm has t_c of tens of ns: the same limits apply, and "
                  "`bedlam check` prints them (stability.md: test_stiff_contacts).",
        .title = "Duration of an elastic Hertz contact",
        .model = "Hertz normal force, e = 1, velocity Verlet",
        .reference = "2.8683 (m*^2/(R* E*^2 v))^(1/5) (Johnson 1985; often rounded to 2.87), "
                     "steel, 1 m/s",
        .measure = "|t_c measured - t_c theory|/t_c theory, start and end interpolated between "
                   "steps",
        .param = "N = t_c/dt",
        .order_note = "second order (velocity Verlet; the Hertz force is C^1 at touch); the "
                      "linear interpolation of the instants of touch and release is second "
                      "order too",
        .tolerance = 0.02, .tolerance_level = 1, .order_min = 1.8,
        .quick = 1, .quick_levels = 3,
        .series_count = 2, .series = {"sphere-wall", "sphere-sphere"},
        .level_count = 5, .level = {25, 50, 100, 200, 400},
        .run = run_hertz_duration,
    },
    {
        .name = "slide_roll",
        .tolerance = 0.01, .tolerance_level = 2, .order_min = 0.0, .no_order = 1,
        .breaks = "the tangential spring needs dt well below its own period, the same limit as the "
                  "normal contact; without friction no history is kept.",
        .title = "A sliding sphere starts rolling",
        .model = "Coulomb-capped tangential spring with history on a plane wall",
        .reference = "slip stops at t_s = 2 v0/(7 mu g) (MFiX DEM04), mu = 0.3, v0 = 0.5 m/s",
        .measure = "|t_s fitted - t_s|/t_s",
        .param = "N = 1/dt [1/s]",
        .order_note = "none: while sliding the friction force is exactly mu F_n at any step, so "
                      "t_s is exact up to the normal transient and the fit",
        .quick = 1, .quick_levels = 3,
        .series_count = 2, .series = {"linear", "hertz"},
        .level_count = 4, .level = {25000, 50000, 100000, 200000},
        .run = run_slide_roll,
    },
    {
        .name = "collision_energy",
        .breaks = "a dense box of 1000 elastic spheres drifts by less than 1e-3 over 1e5 steps at "
                  "t_c/50 (test_collision); with dt near t_c/5 energy grows and the run is stopped "
                  "by the energy guard.",
        .title = "Energy of an elastic head-on collision",
        .model = "linear and Hertz springs, e = 1, no friction, velocity Verlet",
        .reference = "kinetic energy conserved exactly",
        .measure = "worst relative kinetic-energy error after one collision over 8 contact "
                   "phases",
        .param = "N = t_c/dt",
        .order_note = "at least second order, the scheme's formal order. Observed: 3 (linear) "
                      "and 2.5 (Hertz). Velocity Verlet conserves a modified energy that "
                      "differs from the true one by O(dt^2) terms in the spring force, and "
                      "those vanish at zero overlap; what is left after separation comes from "
                      "the two steps that straddle touch and release, where the force is only "
                      "C^0 (linear: O(dt^3)) or C^1 with a singular second derivative (Hertz, "
                      "delta^(3/2): O(dt^2.5))",
        .tolerance = 0.01, .tolerance_level = 1, .order_min = 1.8,
        .quick = 1, .quick_levels = 3,
        .series_count = 2, .series = {"linear", "hertz"},
        .level_count = 5, .level = {25, 50, 100, 200, 400},
        .run = run_collision_energy,
    },
    {
        .name = "oblique_impact",
        .breaks = "the sticking spring loses what it holds at separation (k_t goes to zero with the "
                  "overlap): 2 % of the energy of a full-stick impact at v_t = 2 v_n. Against Maw, "
                  "Barber & Fawcett's theory the law is right in gross sliding and far off in the "
                  "sticking regime (docs/verification-dem.md).",
        .title = "Tangential rebound of an oblique elastic impact",
        .model = "Hertz-Mindlin with the Coulomb-capped spring (e = 1), steel sphere on a steel "
                 "plane at 1 m/s, the spring's first increment resolved at contact onset",
        .reference = "the law's own limit dt -> 0 (RK4 of the same equations, lever arm r - "
                     "delta/2): full stick (mu = 1e6, v_t = 0.5 m/s) and gross sliding (psi1 = 8, "
                     "mu = 0.3: the rigid-body Coulomb impulse)",
        .measure = "worst |v_t2 - v_t2,ref|/|v_t2,ref| over 8 phases of first touch within a step "
                   "(v_t2: the contact point's tangential velocity after the impact)",
        .param = "N = t_c/dt",
        .order_note = "1.5 in full stick: the spring keeps its length to the end while k_t falls "
                      "as sqrt(delta), so the tangential force ends like the square root of the "
                      "time left, and a step straddling that end is O(dt^1.5); without the onset "
                      "resolution the first increment v_t dt made it first order (6.7 % at N = "
                      "50). In gross sliding the force is mu F_n throughout: order 2.5, as the "
                      "Hertz normal impulse",
        .tolerance = 0.01, .tolerance_level = 1, .order_min = 1.4,
        .quick = 1, .quick_levels = 3,
        .series_count = 2, .series = {"sticking", "gross sliding"},
        .level_count = 5, .level = {25, 50, 100, 200, 400},
        .run = run_oblique,
    },
    {
        .name = "column",
        .tolerance = 1e-3, .tolerance_level = 0, .order_min = 0.0, .no_order = 1,
        .breaks = "overlaps beyond `[guards] max_overlap` (default 0.1 of the radius) stop the "
                  "run: contacts too soft for the load.",
        .title = "Static overlaps in a column of five spheres",
        .model = "normal contact laws at rest under gravity (MFiX DEM03)",
        .reference = "delta_k = k m g / k_n (linear), (k m g / (4/3 E* sqrt(R*)))^(2/3) (Hertz)",
        .measure = "worst relative overlap error over the five contacts",
        .param = "N = t_c/dt",
        .order_note = "none: velocity Verlet's fixed point is exact force balance at any step; "
                      "what remains is the residual motion when the run stops",
        .quick = 1, .quick_levels = 3,
        .series_count = 2, .series = {"linear", "hertz"},
        .level_count = 3, .level = {10, 20, 50},
        .run = run_column,
    },
    {
        .name = "silo_beverloo",
        .breaks = "Beverloo's correlation holds for orifices of more than about 6 particle "
                  "diameters and silos more than 2.5 orifices across; below 5 d the orifice jams "
                  "intermittently (arches), and C depends on friction",
        .title = "Discharge of a flat-bottomed silo through a mesh orifice",
        .model = "11 000 glass beads of 3 mm (linear law 2000 N/m, e = 0.5, mu = 0.5) in a "
                 "cylinder 72 mm across on a mesh floor (an annulus of 192 triangles), a plug "
                 "taken away at 0.5 s, beads removed 30 mm below the floor "
                 "(scenes/silo_discharge.ini)",
        .reference = "Beverloo, Leniger & van de Velde (1961): W = C rho_b sqrt(g) (D - k d)^2.5 "
                     "with C = 0.58 and k = 1.5 (Nedderman 1992, ch. 10), rho_b measured in the "
                     "settled bed before the plug opens",
        .measure = "|W / W_Beverloo - 1|, W the least-squares slope of the mass out over "
                   "0.7-1.2 s",
        .param = "one resolution (d/dt fixed at t_c/20)",
        .order_note = "none: a correlation, not a limit",
        .tolerance = 0.15, .tolerance_level = 0, .order_min = 0.0, .no_order = 1,
        .quick = 0, .quick_levels = 0,
        .series_count = 2, .series = {"D = 6 d (18 mm)", "D = 8 d (24 mm)"},
        .level_count = 1, .level = {1},
        .run = run_silo,
    },
    {
        .name = "shear_lun",
        .breaks = "Lun et al.'s theory is first order in the shear rate: at e = 0.7 and solids "
                  "fraction 0.1 bedlam's pressure and shear stress are 20 and 26 % below it in "
                  "this box (ten mean free paths high), 11 and 20 % in a box large enough, at "
                  "e = 0.9 10 and 11 %; more dilute, the flow follows the Boltzmann equation's "
                  "non-Newtonian solution instead (shear_dilute; docs/validation/rheology.md)",
        .title = "Simple shear of inelastic spheres against kinetic theory",
        .model = "frictionless spheres of 5.3 mm (linear law 6e5 N/m, e = 0.7) between "
                 "Lees-Edwards images at 100/s in a 72 x 48 x 48 mm box (scenes/shear_cell.ini); "
                 "stress from the particles (streaming + contact), averaged every 2 ms over "
                 "0.1-1 s (strain 10-100)",
        .reference = "Lun, Savage, Jeffrey & Chepurniy (1984): p = rho nu T (1 + 4 eta nu g0), "
                     "tau = (5/96) rho d sqrt(pi T) F g, T from production = dissipation; "
                     "Carnahan-Starling g0, eta = (1 + e)/2",
        .measure = "max(|p/p_Lun - 1|, |tau/tau_Lun - 1|) at the run's solids fraction and shear "
                   "rate",
        .param = "one resolution (dt = t_c/50)",
        .order_note = "none: a theory's approximation, not a limit",
        .tolerance = 0.10, .tolerance_level = 0, .order_min = 0.0, .no_order = 1,
        .quick = 0, .quick_levels = 0,
        .series_count = 3, .series = {"nu = 0.2", "nu = 0.3", "nu = 0.4"},
        .level_count = 1, .level = {1},
        .run = run_shear_lun,
    },
    {
        .name = "shear_dilute",
        .breaks = "Grad's solution is the limit nu -> 0 and a truncation (the distribution's "
                  "fourth cumulant and the terms quadratic in the stress left out): at nu = 0.05 "
                  "the reduced shear rate is 3-4 % above it (T 6-7 % below), at 0.025 within 1 %; "
                  "from nu = 0.1 on the collisional transfer, outside it, takes over (use Lun et "
                  "al. there: shear_lun; docs/validation/rheology.md)",
        .title = "Dilute simple shear against the Boltzmann equation (Grad's method)",
        .model = "the spheres of shear_lun at solids fraction 0.05 (1702 of them) between "
                 "Lees-Edwards images at 100/s in a 96 x 96 x 288 mm box (26 mean free paths "
                 "high), averaged every 2 ms over 0.3-1 s",
        .reference = "the steady simple shear of a dilute gas of inelastic spheres by Grad's "
                     "method (Montanero et al. 1999, Santos et al. 2004): eta/eta0 = (beta - "
                     "zeta)/beta^2, (g/nu0)^2 = (3/2) zeta beta^2/(beta - zeta), beta = (1 + e)(3 "
                     "- e)/4, zeta = (5/12)(1 - e^2); 0.801 and 0.631 at e = 0.7, where Lun et "
                     "al.'s dilute limit gives 1.023 and 0.558",
        .measure = "max(|eta/eta_Grad - 1|, |(g/nu0)/(g/nu0)_Grad - 1|), eta0 and nu0 from the "
                   "run's own temperature",
        .param = "one resolution (dt = t_c/50)",
        .order_note = "none: a theory's approximation, not a limit",
        .tolerance = 0.05, .tolerance_level = 0, .order_min = 0.0, .no_order = 1,
        .quick = 0, .quick_levels = 0,
        .series_count = 1, .series = {"nu = 0.05"},
        .level_count = 1, .level = {1},
        .run = run_shear_dilute,
    },
    {
        .name = "shear_damped",
        .breaks = "Grad's truncation as in shear_dilute (the runs' N1/p lies 2-5 % below "
                  "Grad's); at e = 0.7 Grad's linear balance has no root from b = 0.166 g on, "
                  "while a run at b = 0.2 g still shears steadily (N1/p 2.0, T 9 % of the dry "
                  "gas's): there the truncation fails, not the flow",
        .title = "Dilute simple shear in a damping medium against Grad's method",
        .model = "the gas of shear_dilute in a medium that moves with the shear and damps each "
                 "sphere's velocity relative to the profile, -b m (v - u) ([species] "
                 "background_damping in a Lees-Edwards box), b = 3 and 6/s",
        .reference = "Grad's steady shear (shear_dilute) with the drag's 2 b P_ij in each "
                     "balance (the suspension model of Chamorro, Vega Reyes & Garzo 2015): "
                     "eta/eta0 = (beta - zeta)/(beta + 2 b*)^2, (g/nu0)^2 = (3/2)(zeta + 2 b*)"
                     "(beta + 2 b*)^2/(beta - zeta), b* = b/nu0",
        .measure = "max(|eta/eta_Grad - 1|, |(g/nu0)/(g/nu0)_Grad - 1|), eta0, nu0 and b* from "
                   "the run's own temperature",
        .param = "one resolution (dt = t_c/50)",
        .order_note = "none: a theory's approximation, not a limit",
        .tolerance = 0.05, .tolerance_level = 0, .order_min = 0.0, .no_order = 1,
        .quick = 0, .quick_levels = 0,
        .series_count = 2, .series = {"b = 3/s", "b = 6/s"},
        .level_count = 1, .level = {1},
        .run = run_shear_damped,
    },
    {
        .name = "shear_walls",
        .breaks = "in a cell driven by walls the bulk's temperature is not set by its own shear "
                  "rate (the walls heat it, and with e = 0.7 the shear gathers at the walls): its "
                  "T is 1.4-1.6 times Lun's for its shear rate; the relations between p, tau and T "
                  "still hold there",
        .title = "Wall-driven and Lees-Edwards shear cells: the bulk's constitutive relations",
        .model = "the spheres of shear_lun at solids fraction 0.2: between Lees-Edwards images, "
                 "and between two corrugated plates moving at -+2.4 m/s (a bulk 12 mm from "
                 "each; scenes/shear_cell_walls.ini)",
        .reference = "Lun et al. (1984) at each run's own solids fraction, shear rate and "
                     "temperature: p = rho nu T (1 + 4 eta nu g0), tau = (5/96) rho d sqrt(pi T) "
                     "F g",
        .measure = "max(|p/p_Lun(T) - 1|, |tau/tau_Lun(T) - 1|)",
        .param = "one resolution (dt = t_c/50)",
        .order_note = "none: a theory's approximation, not a limit",
        .tolerance = 0.15, .tolerance_level = 0, .order_min = 0.0, .no_order = 1,
        .quick = 0, .quick_levels = 0,
        .series_count = 2, .series = {"Lees-Edwards", "walls"},
        .level_count = 1, .level = {1},
        .run = run_shear_walls,
    },
    {
        .name = "poiseuille",
        .breaks = "the gas step is CFL 0.5 and within the viscous limit; a run whose gas step "
                  "exceeds twice the stable one is stopped.",
        .title = "Plane Poiseuille flow",
        .model = "gas momentum and projection on the staggered grid, van Leer convection",
        .reference = "u = g y (1 - y)/(2 nu)",
        .measure = "max |u - u_exact| / u_max",
        .param = "N = cells across the channel",
        .order_note = "second order (central viscous stencil; the wall sits on a face)",
        .tolerance = 0.02, .tolerance_level = 0, .order_min = 1.9,
        .quick = 1, .quick_levels = 3,
        .series_count = 1, .series = {"van Leer"},
        .level_count = 4, .level = {8, 16, 32, 64},
        .run = run_poiseuille,
    },
    {
        .name = "cavity",
        .breaks = "central differences oscillate at cell Reynolds numbers above 2; scenes use van "
                  "Leer or Superbee, which stay bounded.",
        .title = "Lid-driven cavity, Re = 100",
        .model = "incompressible gas solver: convection, viscosity, pressure projection",
        .reference = "Ghia, Ghia & Shin (1982), tables I and II (129 x 129 cells)",
        .measure = "largest |u - u_Ghia| and |v - v_Ghia| on the centrelines (lid speed 1)",
        .param = "N = cells per side",
        .order_note = "second order for central differences (van Leer drops to first order "
                      "at extrema) while our error is above the reference's own; Ghia et al. "
                      "used 129 x 129 cells, and from 32 cells on our difference to their table "
                      "stays at 0.7-0.9 % of the lid speed on both schemes: that is the floor "
                      "of the comparison, not of the solver",
        .tolerance = 0.02, .tolerance_level = 2, .order_min = 0.0,
        .quick = 1, .quick_levels = 3,
        .series_count = 2, .series = {"central", "van Leer"},
        .level_count = 4, .level = {16, 32, 64, 128},
        .run = run_cavity,
    },
    {
        .name = "terminal",
        .tolerance = 0.01, .tolerance_level = 1, .order_min = 0.0, .no_order = 1,
        .breaks = "cells smaller than about 3 particle diameters let the sphere's own wake slow "
                  "the gas it feels (the undisturbed velocity is not available); particles whose "
                  "drag relaxation time is far below dt are stable because the drag is implicit "
                  "(stability.md: test_stiff_drag).",
        .title = "Terminal slip of a settling sphere",
        .model = "drag coupling (Schiller-Naumann), implicit drag, the particle's own wake on "
                 "the grid",
        .reference = "the slip the drag law implies at the particle's voidage, K(s) s = "
                     "(rho_p - rho) g",
        .measure = "|slip/slip_law - 1|",
        .param = "N = cells across a box 24 d wide (cell size 24 d/N; kernel half-width 6 d)",
        .order_note = "none: the drag is backward Euler and the terminal state is its fixed "
                      "point at any step; what remains is the disturbance the sphere makes in "
                      "the gas it feels, which grows as cells shrink towards d",
        .quick = 1, .quick_levels = 2,
        .series_count = 3, .series = {"Re 0.1", "Re 19", "Re 460"},
        .level_count = 4, .level = {3, 6, 9, 12},
        .run = run_terminal,
    },
    {
        .name = "ergun",
        .tolerance = 0.03, .tolerance_level = 1, .order_min = 0.0, .no_order = 1,
        .breaks = "Ergun holds for fixed beds; near close packing the deposited voidage is capped "
                  "at 1 - max_solids (stability.md: test_close_packing).",
        .title = "Packed bed against Ergun",
        .model = "volume-averaged gas through a DEM packing, Ergun drag, voidage by a tent "
                 "kernel",
        .reference = "Ergun: 150 (1-e)^2 mu U/(e^3 d^2) + 1.75 (1-e) rho U^2/(e^3 d) at the "
                     "layers' voidage; U = 0.3 and 0.6 m/s",
        .measure = "worst |measured/Ergun - 1| over the two velocities",
        .param = "N = cells along the bed (N/5 across)",
        .order_note = "none formal: the error is in the sampling, not a truncation. On cells of "
                      "5 d only two or three layers fit between a quarter and three quarters of "
                      "the bed, and the layer voidage mixes in the looser packing at the floor "
                      "and the free surface; finer layers sample the uniform interior",
        .quick = 1, .quick_levels = 2,
        .series_count = 1, .series = {"ergun"},
        .level_count = 3, .level = {15, 25, 50},
        .run = run_ergun,
    },
    {
        .name = "rod_bed",
        .tolerance = 0.05, .tolerance_level = 0, .order_min = 0.0, .no_order = 1,
        .breaks = "the thesis's own step, 5e-5 s, is t_c/2 of a centre impact and is refused; the "
                  "packed height depends on the rolling friction, which the thesis tuned to it",
        .title = "Packed bed of 8070 rods (Mahajan 2019, small set-up)",
        .model = "spherocylinders, linear spring-dashpot, Coulomb friction 0.46 (walls 0.33), "
                 "constant rolling resistance 0.025, random axes dropped under gravity",
        .reference = "the thesis's simulated packed height, 0.106 m (table 4.1)",
        .measure = "|h/0.106 - 1|, h where the solids fraction falls to half its bulk value",
        .param = "N = shortest contact time / dt (rods struck at their tips)",
        .order_note = "none: a random packing; the step changes the packing as a different seed "
                      "would, it does not converge to one height",
        .quick = 0, .quick_levels = 0,
        .series_count = 1, .series = {"rods"},
        .level_count = 1, .level = {20},
        .run = run_rod_bed,
    },
    {
        .name = "settling",
        .breaks = "density ratios down to 1 (liquid-solid) run stably with the added buoyancy and "
                  "pressure-gradient force (stability.md: test_density_ratio).",
        .title = "Hindered settling (Richardson-Zaki)",
        .model = "four-way coupled suspension, Wen-Yu drag, gas step over several particle steps",
        .reference = "the drag law's settling speed in the zero-volume-flux frame, v/v_t = "
                     "eps^n (n = 4.65 in creeping flow)",
        .measure = "|v/v_law - 1|",
        .param = "N = gas steps per 8 particle steps (particle dt = t_c/20 = 5.7e-5 s)",
        .order_note = "first order in the gas step: the drag coefficient and the voidage are "
                      "held over a gas step. The error tends to a floor that the gas step does "
                      "not touch (the particles' disturbance of the gas on the 4 x 4 x 8 grid, "
                      "as in the terminal case), so the plain order falls towards 0 while the "
                      "successive differences halve with the step: their order is 1",
        .tolerance = 0.05, .tolerance_level = 0, .order_min = 0.0, .diff_order_min = 0.8,
        .quick = 1, .quick_levels = 3,
        .series_count = 3, .series = {"phi 0.1", "phi 0.2", "phi 0.3"},
        .level_count = 4, .level = {1, 2, 4, 8},
        .run = run_settling,
    },
    {
        .name = "umf",
        .tolerance = 0.10, .tolerance_level = 1, .order_min = 0.0, .no_order = 1,
        .breaks = "the narrow periodic column slugs above U_mf, so the pressure drop there "
                  "fluctuates by tens of per cent; the packed branch below U_mf gives U_mf.",
        .title = "Minimum fluidization velocity from a velocity sweep",
        .model = "CFD-DEM bed of 1400 beads of 2 mm, Gidaspow drag",
        .reference = "Wen & Yu (1966): Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7",
        .measure = "worst |U_mf/U_mf,Wen-Yu - 1| of the decreasing and the increasing sweep",
        .param = "N = dwell per velocity [ms] (averaging time)",
        .order_note = "none: the sweep averages a fluctuating signal; longer dwells reduce the "
                      "noise, not a truncation error",
        .quick = 0, .quick_levels = 0,
        .series_count = 1, .series = {"sweep"},
        .level_count = 3, .level = {40, 80, 160},
        .run = run_umf,
    },
    {
        .name = "bed_balance",
        .tolerance = 0.01, .tolerance_level = 1, .order_min = 0.0, .no_order = 1,
        .breaks = "the balance holds while every bead stays in the slot; a jet or a bed that "
                  "throws beads through the outlet loses them (particles_out) and the case stops.",
        .title = "Particle momentum balance of a slugging bed",
        .model = "pressure force on the particles as the complement of the gas's share on every "
                 "momentum face (the hydrostatic part whole), drag with both sides equal",
        .reference = "Newton for the beads: pressure drop - gas column - weight/area + walls/area "
                     "- d(momentum)/dt/area = 0, each term measured on its own",
        .measure = "|residual| / (weight less buoyancy per base area)",
        .param = "N = averaging window [s] after 1 s of start-up",
        .order_note = "none: a time average of a slugging bed; the momentum-rate term falls like "
                      "1/N, and what stays is the gas's own momentum budget (its acceleration "
                      "through the bed and the shear on the side walls, a few tenths of a per cent)",
        .quick = 1, .quick_levels = 1,
        .series_count = 2, .series = {"floor at the inlet", "floor raised"},
        .level_count = 3, .level = {1, 2, 4},
        .run = run_bed_balance,
    },
    {
        .name = "parcel_settling",
        .tolerance = 0.03, .tolerance_level = 1, .order_min = 0.0, .no_order = 1,
        .breaks = "parcels placed at random carry noise (each stands for many particles, so the "
                  "solids fraction fluctuates far more than the real suspension's): in this "
                  "column it moves the interface speed by +-9 % (one standard deviation over "
                  "seeds) at 20 parcels per cell, and in columns several cells across it drives "
                  "convection that speeds the interface (docs/parcels.md).",
        .title = "Hindered settling of parcels (MP-PIC)",
        .model = "parcels with the implicit drag and the gas's pressure share 1 - C_pr "
                 "(Patankar & Joseph 2001), model A stress, patankar drag; a column one cell "
                 "across, the parcels on a lattice",
        .reference = "the model's own Richardson-Zaki law: v = eps w with K(eps, w) w = eps "
                     "(rho_p - rho) g (n = 4.79 here, 4.8 in the Stokes limit), 198 um glass at "
                     "phi 0.1 in a liquid (seed 001, sec. 4.1)",
        .measure = "|v_interface / v_model - 1|, the interface from the solids above a level",
        .param = "N: layers of parcels per cell, 10N cells along the column, or dt = 0.02/N s "
                 "(the others 4 layers per cell, 20 cells, 0.01 s)",
        .order_note = "the error is the discreteness of the parcels' layers: it falls with their "
                      "spacing h/N (series 1 refines h at 4 layers per cell, the same spacing as "
                      "series 0 at twice the layers) faster than first order; the step barely "
                      "matters (the drag is implicit and the interface a shock)",
        .quick = 1, .quick_levels = 2,
        .series_count = 3, .series = {"layers per cell", "cells", "time step"},
        .level_count = 3, .level = {1, 2, 4},
        .run = run_parcel_settling,
    },
    {
        .name = "parcel_bimodal",
        .tolerance = 0.10, .tolerance_level = 0, .order_min = 0.0, .no_order = 1,
        .breaks = "in the paper's 10 x 10 cross-section with its 4.5 parcels per cell the parcels' "
                  "noise drives convection that speeds both fronts (docs/parcels.md).",
        .title = "Bimodal sedimentation of parcels (Davis et al. 1982 set-up)",
        .model = "two species of parcels (heavy 177-219 um, 2990 kg/m^3 at 0.01; light 125-150 "
                 "um, 2440 kg/m^3 at 0.03) in the paper's column, one cell across, model A",
        .reference = "the Kynch-type speeds of the model at the mean diameters (Stokes limit): "
                     "heavy front 0.0542 cm/s, top interface 0.0192 cm/s (digest of seed 001, "
                     "sec. 3.1)",
        .measure = "|v / v_Kynch - 1| over the first 100 s",
        .param = "N = 1: the paper's case A (50 cells along, 9000 parcels each, dt 0.005 s); "
                 "N = 2: case B (60 cells, 18 000, dt 0.004 s); K = 5",
        .order_note = "none: two resolutions of one model, as in the paper; the size spread "
                      "(+-10 % in d) widens the fronts, the mean speeds stay",
        .quick = 0, .quick_levels = 0,
        .series_count = 2, .series = {"heavy front", "top interface"},
        .level_count = 2, .level = {1, 2},
        .run = run_parcel_bimodal,
    },
    {
        .name = "parcel_boycott",
        .tolerance = 0.10, .tolerance_level = 0, .order_min = 0.0, .no_order = 1,
        .breaks = "against PNK without the sediment beyond about 500 s: by 800 s that estimate "
                  "falls below the height the settled solids fill (8.4 cm against at least 8.7 cm "
                  "at close packing); the same column upright settles 2.3 times faster than the "
                  "model's hindered speed at these 9 parcels per cell (the parcels' noise drives "
                  "convection: docs/parcels.md).",
        .title = "The Boycott effect: parcels in a column tilted 35 degrees",
        .model = "the paper's sec. 4.2 case (scenes/parcels_inclined.ini): 18 111 parcels of "
                 "130-142 um glass at 0.1 in a viscous liquid, 32 x 72 cells, model A, dt 0.005 "
                 "s with up to 8 liquid sub-steps, gravity tilted 35 degrees from the column's "
                 "axis",
        .reference = "the Ponder-Nakamura-Kuroda estimate dy/dt = -v0 (1 / cos a + y sin a / b) "
                     "with the model's hindered speed v0 (digest of seed 001, sec. 4.2: 52.33 cm "
                     "at 0 s, 43.60 at 100 s, 36.08 at 200 s, 29.61 at 300 s, 19.22 at 500 s), "
                     "and the same above the sediment: y sin a replaced by the suspension's "
                     "length above a sediment at model A's mean solids fraction (0.511 from its "
                     "1-D balance; src/verify/verify.h)",
        .measure = "series 0: the largest |y / y_PNK,sediment - 1| from 100 to 800 s (every 20 s), "
                   "y on the centre line; series 1: |v / v_PNK - 1| of the mean speed over 0-200 "
                   "s; series 2: the largest |y / y_PNK - 1| from 100 to 500 s",
        .param = "N = 1: the paper's resolution",
        .order_note = "none: one resolution, as in the paper",
        .quick = 0, .quick_levels = 0,
        .series_count = 3,
        .series = {"interface 100-800 s", "mean speed 0-200 s", "interface 100-500 s, no sediment"},
        .level_count = 1, .level = {1},
        .run = run_parcel_boycott,
    },
    {
        .name = "tfm_cooling",
        .tolerance = 0.06, .tolerance_level = 2, .order_min = 0.95,
        .breaks = "the balance holds in the viscous regime (below eps_star = 0.58); elastic "
                  "particles (e = 1) do not cool and are refused.",
        .title = "Two-fluid model: homogeneous cooling state",
        .model = "a solids phase at rest (Goldschmidt's 2.49 mm glass, e = 0.97, solids fraction "
                 "0.3) in still gas from theta0 = 0.01 m^2/s^2, the full step of solids and gas, "
                 "the granular energy balanced in time in each cell (solids/phase.h)",
        .reference = "Haff (1983) with Lun et al.'s (1984) dissipation: theta = theta0 / (1 + "
                     "t/tau)^2, tau = 3 rho eps / (gamma/theta^(3/2)) / sqrt(theta0) = 0.251 s",
        .measure = "|theta / theta_Haff - 1| at t = 3 tau (theta_Haff = theta0/16)",
        .param = "N = steps per tau",
        .order_note = "first order: the balance is backward Euler in time",
        .quick = 1, .quick_levels = 3,
        .series_count = 1, .series = {"backward Euler"},
        .level_count = 5, .level = {5, 10, 20, 40, 80},
        .run = run_tfm_cooling,
    },
    {
        .name = "tfm_settling",
        .tolerance = 0.015, .tolerance_level = 2, .order_min = 0.8,
        .breaks = "at a fixed Courant number (dt ~ h) the interface's error stays near 1 % of its "
                  "fall: the solids' transport is point-implicit with the neighbours' old "
                  "velocities, a lag of order (v dt/h) dv/dt while the suspension accelerates, so "
                  "this case refines dt like h^2; the plastic regime holds the sediment at "
                  "Schaeffer's fraction for its weight at every grid (docs/theory-tfm.md).",
        .title = "Two-fluid model: a settling column (Kynch) that packs",
        .model = "100 um glass (2526 kg/m^3, Stokes drag) at solids fraction 0.3 in the lower 0.1 "
                 "m of a closed column of air 0.2 m tall, from rest, to 0.5 s; dt a quarter of "
                 "the cell crossing time at 20 cells, times (20/N)^2",
        .reference = "Kynch (1952): the suspension's top falls with the uniform suspension, v(t) "
                     "= -v_t (1 - exp(-t/tau)), v_t = eps_g^2 (rho_s - rho_g) g / k = 0.375 m/s, "
                     "tau = eps_g (rho_s eps_g + rho_g eps) / k = 38 ms (k = 18 mu/d^2); the "
                     "sediment at Schaeffer's fraction for the weight it carries",
        .measure = "|z - z_Kynch| / (its fall, 17 mm) at 0.08 s, z = 0.05 m + (solids volume "
                   "above 0.05 m)/0.3 (the shock has a structure of its own, a fraction's crossing "
                   "would not converge); a run whose fraction went below 0 or above Schaeffer's "
                   "+ 0.002 fails",
        .param = "N = cells along the column",
        .order_note = "first order: the transport's lag goes like the Courant number, ~ 1/N "
                      "with dt ~ 1/N^2; backward Euler's drag relaxation is O(dt)",
        .quick = 1, .quick_levels = 4,
        .series_count = 1, .series = {"dt ~ h^2"},
        .level_count = 5, .level = {20, 40, 80, 160, 320},
        .run = run_tfm_settling,
    },
    {
        .name = "tfm_energy",
        .tolerance = 2e-3, .tolerance_level = 2, .order_min = 1.8,
        .breaks = "the conduction is central with the cells' conductivities averaged harmonically "
                  "(second order where theta is smooth); the convection is not exercised (the "
                  "solids stay at rest).",
        .title = "Two-fluid model: the granular energy's transport (manufactured solution)",
        .model = "Goldschmidt's 2.49 mm glass (e 0.97) at rest in a layer 0.04 m long, periodic "
                 "along x, two cells of 1 cm between Johnson & Jackson walls (phi' 0.3, e_w 0.6); "
                 "[solids] granular_energy = transport; 4000 steps of 1 ms (solids/energy.h)",
        .reference = "eps(x) = 0.3 + 0.05 sin(2 pi x/L), theta(x) = C / (eps^2 g0(eps)) with C = "
                     "1.7e-3 m^2/s^2 (Syamlal's pressure uniform: no motion), steady under the "
                     "source k4 eps^2 theta^1.5 + D_w theta^1.5/h_z - d/dx(k_theta dtheta/dx)",
        .measure = "the largest |theta / theta(x) - 1| of the cells at the end",
        .param = "N = cells along x",
        .order_note = "second order: central conduction",
        .quick = 1, .quick_levels = 4,
        .series_count = 1, .series = {"steady"},
        .level_count = 4, .level = {8, 16, 32, 64},
        .run = run_tfm_energy,
    },
};
// clang-format on

const bdl_verify_case *bdl_verify_cases(int *count)
{
    *count = (int)(sizeof cases / sizeof cases[0]);
    return cases;
}

const bdl_verify_case *bdl_verify_find(const char *name)
{
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; ++k)
        if (strcmp(cases[k].name, name) == 0)
            return &cases[k];
    return NULL;
}
