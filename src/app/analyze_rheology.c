// bedlam analyze rheology — the shear cell's rheology over a sweep of runs: each run's
// rheology.csv averaged over its steady part (analysis/series.h), with the standard error of the
// average from block means, and with --restitution the kinetic theory of Lun et al. (1984) for
// smooth spheres beside it (analysis/rheology.h).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/rheology.h"
#include "analysis/series.h"
#include "app/analyze.h"
#include "app/analyze_files.h"
#include "core/file.h"

/// The columns of rheology.csv averaged.
enum {
    C_NU,
    C_RATE,
    C_T,
    C_P,
    C_TAU,
    C_MU,
    C_I,
    C_N1,
    C_N2,
    C_ALIGN,
    C_D,
    C_RHO,
    C_PC,
    C_TC,
    C_COUNT
};
static const char *const column_names[C_COUNT] = {
    "solids_fraction",  "shear_rate",   "temperature", "pressure",  "shear_stress", "friction",
    "inertial_number",  "n1",           "n2",          "alignment", "diameter",     "density",
    "pressure_contact", "shear_contact"};

/// One run averaged: the mean and standard error of each column, the window and the rows.
typedef struct run_mean {
    double mean[C_COUNT], se[C_COUNT];
    double from, to;
    long rows;
} run_mean;

/// The start of the steady part when --from is not given: a shear strain of 10 (the mean shear
/// rate of the second half of the series), but no later than three quarters of the series.
static double steady_from(const double *t, const double *rate, long n)
{
    if (n < 2)
        return t[0];
    const bdl_sample_stats s = bdl_sample_stats_in(t, rate, n, 0.5 * (t[0] + t[n - 1]), t[n - 1]);
    const double t10 = fabs(s.mean) > 0.0 ? t[0] + 10.0 / fabs(s.mean) : t[0];
    return fmin(t10, t[0] + 0.75 * (t[n - 1] - t[0]));
}

/// Reads and averages RUN/rheology.csv; 0 after an error message.
static int average_run(const char *run, const bdl_analyze_opts *o, run_mean *m)
{
    double *t = NULL, *x[C_COUNT] = {NULL};
    long n = 0, rows = 0;
    int ok = 1;
    for (int c = 0; c < C_COUNT && ok; ++c) {
        free(t);
        t = NULL;
        ok = bdl_analyze_read_series(run, "rheology.csv", column_names[c], &t, &x[c], &rows);
        ok = ok && (c == 0 || rows == n);
        n = rows;
    }
    if (ok) {
        m->from = isfinite(o->from) ? o->from : steady_from(t, x[C_RATE], n);
        m->to = o->to;
        for (int c = 0; c < C_COUNT; ++c) {
            const bdl_block_mean b = bdl_block_mean_in(t, x[c], n, m->from, m->to, 10);
            m->mean[c] = b.samples.mean;
            m->se[c] = b.standard_error;
            m->rows = c == C_P ? b.samples.count : m->rows;
        }
        m->to = fmin(m->to, t[n - 1]);
    }
    free(t);
    for (int c = 0; c < C_COUNT; ++c)
        free(x[c]);
    if (ok && m->rows < 10) {
        fprintf(stderr, "error: %s/rheology.csv: %ld rows from %g s; at least 10 are needed\n", run,
                m->rows, m->from);
        return 0;
    }
    return ok;
}

/// Lun et al. at the run's solids fraction and shear rate (their T from the energy balance), and
/// their pressure and shear stress at the run's own temperature (the constitutive relations
/// alone): p = rho nu T (1 + 4 eta nu g0), tau = (5/96) rho d sqrt(pi T) F |rate|.
typedef struct lun_beside {
    bdl_lun_state at_rate;
    double p_at_t, tau_at_t;
} lun_beside;

static lun_beside lun_of(const run_mean *m, double e)
{
    lun_beside l;
    const double nu = m->mean[C_NU], d = m->mean[C_D], rho = m->mean[C_RHO];
    l.at_rate = bdl_lun_simple_shear(nu, e, d, rho, m->mean[C_RATE]);
    // The relations scale with sqrt(T) (tau) and T (p): rescale the balance's state to the run's T.
    const double r = m->mean[C_T] / l.at_rate.temperature;
    l.p_at_t = l.at_rate.pressure * r;
    l.tau_at_t = l.at_rate.shear_stress * sqrt(r);
    return l;
}

static const char header[] =
    "run,rows,from,to,solids_fraction,shear_rate,temperature,temperature_se,pressure,pressure_se,"
    "shear_stress,shear_stress_se,friction,friction_se,inertial_number,n1,n2,alignment,"
    "pressure_scaled,shear_stress_scaled,lun_temperature,lun_pressure,lun_shear_stress,"
    "lun_pressure_at_temperature,lun_shear_stress_at_temperature,pressure_contact,shear_contact,"
    "contact_friction,contact_pressure_scaled,reduced_viscosity,reduced_shear_rate";

/// rho d^2 (shear rate)^2 of a run's means: the scale of its stresses.
static double stress_scale(const double *v)
{
    return v[C_RHO] * v[C_D] * v[C_D] * v[C_RATE] * v[C_RATE];
}

static void write_row(FILE *f, const char *run, const run_mean *m, double e)
{
    const double *v = m->mean, *se = m->se;
    const double scale = stress_scale(v);
    fprintf(
        f,
        "%s,%ld,%.6g,%.6g,%.6g,%.6g,%.6g,%.3g,%.6g,%.3g,%.6g,%.3g,%.6g,%.3g,%.6g,%.6g,%.6g,%.6g,"
        "%.6g,%.6g",
        run, m->rows, m->from, m->to, v[C_NU], v[C_RATE], v[C_T], se[C_T], v[C_P], se[C_P],
        v[C_TAU], se[C_TAU], v[C_MU], se[C_MU], v[C_I], v[C_N1], v[C_N2], v[C_ALIGN],
        v[C_P] / scale, v[C_TAU] / scale);
    if (isnan(e)) {
        fprintf(f, ",nan,nan,nan,nan,nan");
    } else {
        const lun_beside l = lun_of(m, e);
        fprintf(f, ",%.6g,%.6g,%.6g,%.6g,%.6g", l.at_rate.temperature, l.at_rate.pressure,
                l.at_rate.shear_stress, l.p_at_t, l.tau_at_t);
    }
    double visc, rate;
    bdl_rheology_reduced(v[C_NU], v[C_D], v[C_RHO], v[C_T], v[C_TAU], v[C_RATE], &visc, &rate);
    fprintf(f, ",%.6g,%.6g,%.6g,%.6g,%.6g,%.6g\n", v[C_PC], v[C_TC], v[C_TC] / v[C_PC],
            v[C_PC] / scale, visc, rate);
}

static void print_row(const char *run, const run_mean *m, double e, double b)
{
    const double *v = m->mean, *se = m->se;
    printf("%s: %ld rows, %.3g-%.3g s: nu %.4f  rate %.4g/s  T %.4g  p %.4g +- %.2g Pa  "
           "tau %.4g +- %.2g Pa  mu %.3f  I %.3g  N1/p %.3f  N2/p %.3f  contact mu %.3f",
           run, m->rows, m->from, m->to, v[C_NU], v[C_RATE], v[C_T], v[C_P], se[C_P], v[C_TAU],
           se[C_TAU], v[C_MU], v[C_I], v[C_N1] / v[C_P], v[C_N2] / v[C_P], v[C_TC] / v[C_PC]);
    if (isfinite(v[C_ALIGN]))
        printf("  alignment %.1f deg", v[C_ALIGN]);
    printf("\n");
    if (isnan(e))
        return;
    const lun_beside l = lun_of(m, e);
    printf("  Lun et al. (e = %g): T %.4g  p %.4g  tau %.4g  -> T %.3f  p %.3f  tau %.3f of "
           "theirs; at the run's T: p %.3f  tau %.3f\n",
           e, l.at_rate.temperature, l.at_rate.pressure, l.at_rate.shear_stress,
           v[C_T] / l.at_rate.temperature, v[C_P] / l.at_rate.pressure,
           v[C_TAU] / l.at_rate.shear_stress, v[C_P] / l.p_at_t, v[C_TAU] / l.tau_at_t);
    // Lun et al.'s theory is first order in the shear; where the flow is dilute the reduced shear
    // rate is not small, and Grad's solution of the Boltzmann equation gives the limit nu -> 0.
    const double nu = v[C_NU], d = v[C_D], rho = v[C_RHO], g = v[C_RATE];
    double visc, rate, visc_lun, rate_lun;
    bdl_rheology_reduced(nu, d, rho, v[C_T], v[C_TAU], g, &visc, &rate);
    bdl_rheology_reduced(nu, d, rho, l.at_rate.temperature, l.at_rate.shear_stress, g, &visc_lun,
                         &rate_lun);
    // With a drag, Grad's values at the reduced drag b / nu0 of the run's own temperature.
    const double b_reduced = b * rate / fabs(g);
    double visc_grad, rate_grad, n1_grad;
    bdl_grad_dilute_reduced(e, b_reduced, &visc_grad, &rate_grad, &n1_grad);
    printf("  reduced (eta0, nu0 at T): eta/eta0 %.4f  rate/nu0 %.4f  N1/p %.3f; Lun et al. %.4f  "
           "%.4f  0; nu -> 0 (Boltzmann by Grad's method",
           visc, rate, v[C_N1] / v[C_P], visc_lun, rate_lun);
    if (b > 0.0)
        printf(", drag %g/s: b/nu0 %.4f", b, b_reduced);
    printf(") %.4f  %.4f  %.3f\n", visc_grad, rate_grad, n1_grad);
}

static void plot_rheology(const bdl_analyze_opts *o)
{
    char path[1300];
    snprintf(path, sizeof path, "%s/rheology.gp", o->out);
    const int lun = !isnan(o->restitution);
    bdl_analyze_plot(
        path,
        "set terminal pngcairo size 900,550 font 'DejaVu Sans,11'\n"
        "set output '%s/rheology.png'\nset datafile separator ','\n"
        "set xlabel 'solids fraction'\nset ylabel 'stress / (rho d^2 shear rate^2)'\n"
        "set logscale y\nset grid\nset key top left\n"
        "plot '%s/rheology.csv' every ::1 using 5:19 with points pt 7 ps 1.4 lc rgb '#3060c0' "
        "title 'pressure', '' every ::1 using 5:20 with points pt 5 ps 1.4 lc rgb '#c03030' "
        "title 'shear stress'%s\n",
        o->out, o->out,
        lun ? ", '' every ::1 using 5:($22*$19/$9) with linespoints dt 2 pt 6 lc rgb '#3060c0' "
              "title 'Lun et al. (1984)', '' every ::1 using 5:($23*$20/$11) with linespoints dt 2 "
              "pt 4 lc rgb '#c03030' title 'Lun et al. (1984)'"
            : "");
}

/// With --amplitude: the nu_cr of each run on the law with A held; with --stiffness and --a2 as
/// well, on the whole dense branch, or past jamming when its pressure is above the branch's peak.
static void jamming_points(const bdl_analyze_opts *o, const double (*v)[C_COUNT], const double *y,
                           int n, FILE *f)
{
    const bdl_jamming_branch b = {o->jamming, o->amplitude, o->a2, o->stiffness};
    for (int k = 0; k < n; ++k) {
        const double *m = v[k];
        int beyond = 0;
        double near = NAN;
        const double cr = o->stiffness > 0.0
                              ? bdl_rheology_jamming_soft(&b, m[C_NU], m[C_PC], m[C_RATE], m[C_D],
                                                          m[C_RHO], &beyond, &near)
                              : bdl_rheology_jamming_point(m[C_NU], y[k], o->jamming, o->amplitude);
        const char *says = beyond      ? "lies past jamming: its contact pressure is above the "
                                         "branch's peak at this rate, nu_cr <="
                           : isnan(cr) ? "has no nu_cr: no contact pressure, or more than 1 from "
                                         "jamming"
                                       : "gives nu_cr";
        char text[700], value[120] = "";
        if (!isnan(cr) && !isnan(near))
            snprintf(value, sizeof value,
                     " %.4f (the branch's other crossing, on the springs' "
                     "side: %.4f)",
                     cr, near);
        else if (!isnan(cr))
            snprintf(value, sizeof value, " %.4f", cr);
        snprintf(text, sizeof text, "jamming with A = %.6g held%s: %s (nu %.4f) %s%s", o->amplitude,
                 o->stiffness > 0.0 ? " on the soft branch" : "", o->runs[k], m[C_NU], says, value);
        printf("%s\n", text);
        fprintf(f, "# %s\n", text);
    }
}

/// With --jamming: the contact pressure scaled by rho d^2 (shear rate)^2 against the solids
/// fraction, fitted with A (nu_cr - nu)^-exponent over the runs.
static void fit_jamming(const bdl_analyze_opts *o, const double (*v)[C_COUNT], int n, FILE *f)
{
    double nu[BDL_ANALYZE_RUNS_MAX], y[BDL_ANALYZE_RUNS_MAX];
    for (int k = 0; k < n; ++k) {
        nu[k] = v[k][C_NU];
        y[k] = v[k][C_PC] / stress_scale(v[k]);
    }
    if (o->amplitude > 0.0)
        jamming_points(o, v, y, n, f);
    double cr, a;
    const double r = bdl_rheology_fit_jamming(nu, y, n, o->jamming, &cr, &a);
    if (isnan(r)) {
        if (!(o->amplitude > 0.0))
            printf("jamming fit: needs three runs or more with a contact pressure\n");
        return;
    }
    printf("jamming fit over %d runs: p_contact / (rho d^2 rate^2) = %.4g (%.4f - nu)^-%g, rms "
           "residual of the log %.3f\n",
           n, a, cr, o->jamming, r);
    fprintf(f,
            "# jamming fit over %d runs: p_contact / (rho d^2 rate^2) = %.6g (%.6f - nu)^-%g, "
            "rms residual of the log %.4f\n",
            n, a, cr, o->jamming, r);
}

bdl_result bdl_analyze_rheology(const bdl_analyze_opts *o)
{
    if (!isnan(o->restitution) && !(o->restitution > 0.0 && o->restitution < 1.0)) {
        fprintf(stderr,
                "error: --restitution %g: must lie in (0, 1) (an elastic gas has no steady "
                "shear)\n",
                o->restitution);
        return BDL_ERR_ARGS;
    }
    if (!(o->damping >= 0.0 && isfinite(o->damping)) ||
        (o->damping > 0.0 && isnan(o->restitution))) {
        fprintf(stderr, "error: --damping %g: must be >= 0, and comes with --restitution E\n",
                o->damping);
        return BDL_ERR_ARGS;
    }
    if (!(o->jamming >= 0.0 && isfinite(o->jamming))) {
        fprintf(stderr, "error: --jamming %g: must be a positive exponent\n", o->jamming);
        return BDL_ERR_ARGS;
    }
    if (!(o->amplitude >= 0.0 && isfinite(o->amplitude)) ||
        (o->amplitude > 0.0 && !(o->jamming > 0.0))) {
        fprintf(stderr, "error: --amplitude %g: must be positive, and comes with --jamming X\n",
                o->amplitude);
        return BDL_ERR_ARGS;
    }
    if (!(o->stiffness >= 0.0 && o->a2 >= 0.0 && isfinite(o->stiffness) && isfinite(o->a2)) ||
        ((o->stiffness > 0.0 || o->a2 > 0.0) &&
         !(o->stiffness > 0.0 && o->a2 > 0.0 && o->amplitude > 0.0))) {
        fprintf(stderr,
                "error: --stiffness %g, --a2 %g: both positive, and they come with "
                "--jamming X --amplitude A\n",
                o->stiffness, o->a2);
        return BDL_ERR_ARGS;
    }
    char path[1300];
    snprintf(path, sizeof path, "%s/rheology.csv", o->out);
    bdl_atomic_file af;
    if (bdl_atomic_open_csv(&af, path, header) != BDL_OK)
        return BDL_ERR_OUTPUT_DIR;
    double v[BDL_ANALYZE_RUNS_MAX][C_COUNT];
    for (int r = 0; r < o->run_count; ++r) {
        run_mean m;
        if (!average_run(o->runs[r], o, &m)) {
            bdl_atomic_abort(&af);
            return BDL_ERR_ARGS;
        }
        write_row(af.file, o->runs[r], &m, o->restitution);
        print_row(o->runs[r], &m, o->restitution, o->damping);
        for (int c = 0; c < C_COUNT; ++c)
            v[r][c] = m.mean[c];
    }
    if (o->jamming > 0.0)
        fit_jamming(o, (const double(*)[C_COUNT])v, o->run_count, af.file);
    bdl_result rc = bdl_atomic_commit(&af);
    if (rc == BDL_OK && o->plots)
        plot_rheology(o);
    if (rc == BDL_OK)
        printf("wrote %s\n", path);
    return rc;
}
