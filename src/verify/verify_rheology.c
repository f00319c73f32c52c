// bedlam — verification of the shear cell: the bulk rheology of frictionless spheres against the
// kinetic theory of Lun et al. (1984) (verify.h).
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "analysis/rheology.h"
#include "output/rheology_out.h"
#include "verify/verify.h"

static const double sphere_volume = 3.14159265358979323846 / 6.0 * 0.0053 * 0.0053 * 0.0053;

/// The triangle wave: 0 at multiples of the 6 mm period, 1 halfway between.
static double wave(double x)
{
    const double f = x / 0.006 - floor(x / 0.006);
    return f <= 0.5 ? 2.0 * f : 2.0 - 2.0 * f;
}

/// Writes the corrugated plate of tools/shear_meshes.py (square dimples of 6 mm, 3 mm deep, over
/// x in [-12, 84] mm and y in [-12, 60] mm) to `path`; 0 on failure.
static int write_plate(const char *path)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return 0;
    enum { NX = 32, NY = 24 }; // half periods
    for (int j = 0; j <= NY; ++j)
        for (int i = 0; i <= NX; ++i) {
            const double x = -0.012 + 0.003 * i, y = -0.012 + 0.003 * j;
            fprintf(f, "v %.9g %.9g %.9g\n", x, y, 0.0015 * (wave(x) + wave(y)));
        }
    for (int j = 0; j < NY; ++j)
        for (int i = 0; i < NX; ++i) {
            const int a = j * (NX + 1) + i + 1, b = a + 1, c = a + NX + 2, d = a + NX + 1;
            fprintf(f, "f %d %d %d\nf %d %d %d\n", a, b, c, a, c, d);
        }
    return fclose(f) == 0;
}

/// The cell of `set` (Lees–Edwards in its box, or the thesis's box between plates): random fills
/// up to solids fraction 0.3, a lattice of 5.33 mm above (random insertion jams near 0.38).
static bdl_world *shear_world(const bdl_verify_shear_setup *set, const char *plate)
{
    const double nu = set->solids_fraction, e = set->restitution, t_end = set->to;
    const int thesis = !(set->box[0] > 0.0 && set->box[1] > 0.0 && set->box[2] > 0.0) || plate;
    const double lx = thesis ? 0.072 : set->box[0], ly = thesis ? 0.048 : set->box[1],
                 lz = thesis ? 0.048 : set->box[2];
    const long count = lround(nu * lx * ly * lz / sphere_volume);
    const char *fill = nu > 0.33 ? "type = lattice\nspacing = 0.00533\nvelocity_jitter = 0.2\n"
                                 : "type = random\n";
    if (!plate)
        return bdl_verify_world(
            "[run]\nend_time = %g\ngravity = 0 0 0\n[domain]\nmin = 0 0 0\n"
            "max = %.17g %.17g %.17g\nperiodic = x y z\nshear_rate = 100\n"
            "[contact]\nlaw = linear\ndamping = closed_form\n"
            "[species bead]\ndiameter = 0.0053\ndensity = 1395\nstiffness = 6e5\n"
            "restitution = %g\nbackground_damping = %.17g\n[create bed]\n%sspecies = bead\n"
            "count = %ld\nregion_min = 0 0 0\nregion_max = %.17g %.17g %.17g\n"
            "[output]\nrheology_bins = 16\n",
            t_end, lx, ly, lz, e, set->damping, fill, count, lx, ly, lz);
    return bdl_verify_world(
        "[run]\nend_time = %g\ngravity = 0 0 0\n[domain]\nmin = 0 0 0\n"
        "max = 0.072 0.048 0.048\nperiodic = x y\n"
        "[contact]\nlaw = linear\ndamping = closed_form\n"
        "[species bead]\ndiameter = 0.0053\ndensity = 1395\nstiffness = 6e5\nrestitution = %g\n"
        "[wall floor]\ntype = mesh\nfile = %s\nperiodic = x y\n"
        "motion = move\nvelocity = -2.4 0 0\n"
        "[wall lid]\ntype = mesh\nfile = %s\nrotate = 180 0 0\n"
        "translate = 0 0.048 0.048\nperiodic = x y\nmotion = move\nvelocity = 2.4 0 0\n"
        "[create bed]\n%sspecies = bead\ncount = %ld\nregion_min = 0 0 0.0031\n"
        "region_max = 0.072 0.048 0.0449\nvelocity_jitter = 0.5\n"
        "[output]\nrheology_margin = 0.012\nrheology_bins = 16\n",
        t_end, e, plate, plate, fill, count);
}

bdl_result bdl_verify_shear_cell(const bdl_verify_shear_setup *set, bdl_verify_shear *out)
{
    *out = (bdl_verify_shear){.pressure = NAN};
    const int walls = set->walls;
    const double e = set->restitution, t_end = set->to;
    char folder[] = "/tmp/bedlam-shear-XXXXXX", plate[64];
    if (walls && !mkdtemp(folder))
        return BDL_ERR_IO;
    snprintf(plate, sizeof plate, "%s/plate.obj", folder);
    bdl_world *w = !walls || write_plate(plate) ? shear_world(set, walls ? plate : NULL) : NULL;
    if (walls) {
        unlink(plate);
        rmdir(folder);
    }
    if (!w)
        return BDL_ERR_SCENE;
    double sum[6] = {0}, next = set->from;
    bdl_result r = BDL_OK;
    while (r == BDL_OK && w->time < t_end - 0.5 * w->dt) {
        r = bdl_world_step(w);
        if (r != BDL_OK || w->time < next - 0.5 * w->dt)
            continue;
        next += 0.002;
        bdl_rheology_sample s;
        r = bdl_rheology_of_world(w, &s);
        const double v[6] = {s.solids_fraction, s.shear_rate,   s.temperature,
                             s.pressure,        s.shear_stress, s.n1};
        for (int k = 0; k < 6 && r == BDL_OK; ++k)
            sum[k] += v[k];
        out->samples += r == BDL_OK;
    }
    out->steps = w->step;
    const double n = (double)out->samples;
    out->solids_fraction = sum[0] / n;
    out->shear_rate = sum[1] / n;
    out->temperature = sum[2] / n;
    out->pressure = sum[3] / n;
    out->shear_stress = sum[4] / n;
    out->n1 = sum[5] / n;
    const bdl_lun_state lun =
        bdl_lun_simple_shear(out->solids_fraction, e, 0.0053, 1395.0, out->shear_rate);
    out->lun_temperature = lun.temperature;
    out->lun_pressure = lun.pressure;
    out->lun_shear_stress = lun.shear_stress;
    const double ratio = out->temperature / lun.temperature; // p ~ T, tau ~ sqrt(T)
    out->lun_pressure_at_t = lun.pressure * ratio;
    out->lun_shear_stress_at_t = lun.shear_stress * sqrt(ratio);
    bdl_world_destroy(w);
    return r;
}
