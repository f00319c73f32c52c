// bedlam analyze sweep — U_mf from a run's pressure-drop sweep ([gas] sweep): its stages, both
// branches fitted (analysis/umf.h), sweep.csv and sweep.png.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "analysis/umf.h"
#include "app/analyze.h"
#include "app/analyze_files.h"
#include "core/file.h"

typedef struct sweep_data {
    double *t, *u, *dp, *ratio;
    long n;
} sweep_data;

static void free_sweep(sweep_data *d) { free(d->t), free(d->u), free(d->dp), free(d->ratio); }

static int read_sweep(const char *run, sweep_data *d)
{
    static const char *const columns[] = {"inlet_velocity", "pressure_drop", "weight_ratio"};
    double **to[] = {&d->u, &d->dp, &d->ratio};
    long m = 0;
    if (!bdl_analyze_read_column(run, "diagnostics.csv", "time", &d->t, &d->n))
        return 0;
    for (int k = 0; k < 3; ++k)
        if (!bdl_analyze_read_column(run, "diagnostics.csv", columns[k], to[k], &m) || m != d->n)
            return 0;
    return 1;
}

static bdl_result write_sweep(const char *out, const bdl_sweep_stage *st, int ns,
                              const bdl_sweep_branch br[2])
{
    char path[1300];
    snprintf(path, sizeof path, "%s/sweep.csv", out);
    bdl_atomic_file af;
    if (bdl_atomic_open_csv(&af, path,
                            "stage,inlet_velocity,branch,pressure_drop,pressure_drop_std,"
                            "weight_ratio") != BDL_OK) {
        fprintf(stderr, "error: cannot write %s\n", path);
        return BDL_ERR_OUTPUT_DIR;
    }
    for (int k = 0; k < ns; ++k)
        fprintf(af.file, "%d,%.6g,%s,%.6g,%.6g,%.6g\n", k, st[k].u,
                st[k].branch > 0 ? "increasing" : "decreasing", st[k].dp, st[k].dp_std,
                st[k].ratio);
    fprintf(af.file, "# U_mf increasing %.6g m/s, decreasing %.6g m/s; plateau %.6g / %.6g Pa\n",
            br[0].fit.umf, br[1].fit.umf, br[0].fit.plateau, br[1].fit.plateau);
    if (bdl_atomic_commit(&af) != BDL_OK) {
        fprintf(stderr, "error: cannot write %s\n", path);
        return BDL_ERR_OUTPUT_DIR;
    }
    return BDL_OK;
}

static void plot_sweep(const char *out, const bdl_umf_result *d)
{
    char path[1300];
    snprintf(path, sizeof path, "%s/sweep.gp", out);
    bdl_analyze_plot(
        path,
        "set terminal pngcairo size 900,600 font 'DejaVu Sans,11'\n"
        "set output '%s/sweep.png'\nset datafile separator ','\n"
        "set xlabel 'superficial gas velocity U_0 [m/s]'\n"
        "set ylabel 'pressure drop over the bed [Pa]'\nset key bottom right\n"
        "set grid\nset yrange [0:*]\n"
        "a = %.9g; b = %.9g; P = %.9g; umf = %.9g\n"
        "set arrow from umf, graph 0 to umf, graph 1 nohead dt 2 lc rgb '#808080'\n"
        "plot '%s/sweep.csv' using (strcol(3) eq 'increasing' ? $2 : 1/0):4:5 every "
        "::1 with yerrorlines pt 7 lc rgb '#c03030' title 'increasing', \\\n"
        "     '%s/sweep.csv' using (strcol(3) eq 'decreasing' ? $2 : 1/0):4:5 every "
        "::1 with yerrorlines pt 5 lc rgb '#3060c0' title 'decreasing', \\\n"
        "     (x <= umf ? a*x + b*x*x : 1/0) lw 2 lc rgb '#3060c0' dt 3 title "
        "'packed branch a U + b U^2', \\\n"
        "     P lw 1 lc rgb '#404040' dt 2 title sprintf('plateau; U_{mf} = %%.3f m/s', "
        "umf)\n",
        out, d->a, d->b, d->plateau, d->umf, out, out);
}

/// Fits both branches (0 increasing, 1 decreasing) and prints them.
static bdl_result fit_branches(const bdl_sweep_stage *st, int ns, bdl_sweep_branch br[2])
{
    for (int b = 0; b < 2; ++b) {
        if (bdl_sweep_branch_fit(st, ns, b == 0 ? 1 : -1, &br[b]) != BDL_OK) {
            fprintf(stderr, "error: out of memory\n");
            return BDL_ERR_NOMEM;
        }
        const bdl_umf_result *r = &br[b].fit;
        printf("%s branch: %d stages, U_mf %.4f m/s (packed fit a %.4g, b %.4g on %d points), "
               "plateau %.2f Pa over %d points = %.4f of the bed's weight per area\n",
               b ? "decreasing" : "increasing", br[b].stages, r->umf, r->a, r->b, r->packed,
               r->plateau, r->fluidized, br[b].plateau_ratio);
    }
    return BDL_OK;
}

bdl_result bdl_analyze_sweep(const bdl_analyze_opts *o)
{
    sweep_data d = {0};
    const int ok = read_sweep(o->run, &d);
    bdl_sweep_stage *st = ok ? calloc((size_t)d.n, sizeof *st) : NULL;
    if (ok && !st) {
        fprintf(stderr, "error: out of memory\n");
        free_sweep(&d);
        return BDL_ERR_NOMEM;
    }
    const int ns = ok ? bdl_sweep_stages(d.t, d.u, d.dp, d.ratio, d.n, st) : 0;
    free_sweep(&d);
    if (!ok || ns < 4) {
        fprintf(stderr,
                "error: %s: no sweep in diagnostics.csv (%d stages of the inlet velocity); "
                "set [gas] sweep\n",
                o->run, ns);
        free(st);
        return ok ? BDL_ERR_NO_RESULT : BDL_ERR_ARGS;
    }
    bdl_sweep_branch br[2];
    bdl_result rc = fit_branches(st, ns, br);
    if (rc == BDL_OK)
        rc = write_sweep(o->out, st, ns, br);
    if (rc == BDL_OK && o->plots)
        plot_sweep(o->out, &br[1].fit);
    free(st);
    if (rc != BDL_OK)
        return rc;
    return isfinite(br[1].fit.umf) ? BDL_OK : BDL_ERR_NO_RESULT;
}
