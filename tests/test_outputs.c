// A run's outputs against a state gone wrong: the finite check names the first non-finite number
// (array, particle id or gas cell, component, step); an output due at a non-finite state is not
// written and the step stops the run; closing writes that state to checkpoint/failed.bdlckpt and
// leaves the good state.bdlckpt as it was.
#define _POSIX_C_SOURCE 200809L // mkdtemp
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "check.h"
#include "scene_util.h"
#include "cfd/gas.h"
#include "core/file.h"
#include "core/log.h"
#include "io/csv.h"
#include "run/outputs.h"

static const char *const scene_text =
    "[run]\nend_time = 1\ngravity = 0 0 -9.81\n"
    "[domain]\nmin = 0 0 0\nmax = 0.02 0.02 0.04\n"
    "[contact]\nlaw = linear\n"
    "[species s]\ndiameter = 0.002\ndensity = 2500\nstiffness = 1000\nrestitution = 0.5\n"
    "[wall box]\ntype = box\nmin = 0 0 0\nmax = 0.02 0.02 0.04\n"
    "[create bed]\ntype = lattice\ncount = 20\nregion_min = 0 0 0.002\nregion_max = 0.02 0.02 "
    "0.02\n"
    "[gas]\ncells = 2 2 4\nzmin = inlet\nzmax = outlet\ninlet_velocity = 0.1\n"
    "[output]\ndiagnostics_interval = 1e-6\n";

static long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

/// The finite check's message for a velocity, then for the gas pressure.
static void finite_check(bdl_world *w)
{
    bdl_guard_state g = {.finite_step = 40};
    char message[1024];
    CHECK(bdl_guards_check_finite(w, &g, message, sizeof message) == BDL_OK);
    CHECK(g.finite_step == w->step);
    g.finite_step = 40;
    const long i = bdl_test_find(w, 7);
    const bdl_vec3 v = w->particles.vel[i];
    w->particles.vel[i].z = INFINITY;
    CHECK(bdl_guards_check_finite(w, &g, message, sizeof message) == BDL_ERR_UNSTABLE);
    CHECK_MSG(strstr(message, "the velocity of particle 7 (z component) is inf") != NULL, "%s",
              message);
    char when[64];
    snprintf(when, sizeof when, "(step %ld); the state was finite at step 40", w->step);
    CHECK_MSG(strstr(message, when) != NULL, "%s", message);
    w->particles.vel[i] = v;
    w->gas->p[bdl_grid_index(&w->gas->grid, 1, 0, 2)] = NAN;
    CHECK(bdl_guards_check_finite(w, &g, message, sizeof message) == BDL_ERR_UNSTABLE);
    CHECK_MSG(strstr(message, "the gas pressure in cell (1, 0, 2) is nan") != NULL, "%s", message);
    w->gas->p[bdl_grid_index(&w->gas->grid, 1, 0, 2)] = 0.0;
}

/// A diagnostics row: NaN is accepted only in the columns that may be undefined, found by name
/// (a column added before the rods' must not shift the set): spring_work_left is refused, the
/// rods' order accepted.
static void undefined_columns(const bdl_world *w)
{
    static const char *const undefined[] = {"probe_pressure_drop", "weight_ratio",
                                            "mean_height",         "segregation",
                                            "rod_vertical_cos",    "rod_order"};
    int spring = -1, order = -1;
    for (int c = 0; c < bdl_diagnostics_column_count; ++c) {
        int expected = 0;
        for (size_t k = 0; k < sizeof undefined / sizeof undefined[0]; ++k)
            expected |= strcmp(bdl_diagnostics_columns[c], undefined[k]) == 0;
        CHECK_MSG(bdl_diagnostics_may_be_undefined(c) == expected, "column %d (%s)", c,
                  bdl_diagnostics_columns[c]);
        spring = strcmp(bdl_diagnostics_columns[c], "spring_work_left") == 0 ? c : spring;
        order = strcmp(bdl_diagnostics_columns[c], "rod_order") == 0 ? c : order;
    }
    CHECK(spring >= 0 && order >= 0);
    if (spring < 0 || order < 0)
        return;
    bdl_diagnostics d;
    bdl_diagnostics_compute(w, 0.0, &d);
    double row[64];
    CHECK(bdl_diagnostics_column_count <= 64);
    bdl_diagnostics_row(&d, row);
    row[order] = NAN;
    const int n = bdl_diagnostics_column_count;
    char message[1024];
    CHECK(bdl_guards_check_row(w, "diagnostics.csv", bdl_diagnostics_columns, row, n,
                               bdl_diagnostics_may_be_undefined, message,
                               sizeof message) == BDL_OK);
    row[spring] = NAN;
    CHECK(bdl_guards_check_row(w, "diagnostics.csv", bdl_diagnostics_columns, row, n,
                               bdl_diagnostics_may_be_undefined, message,
                               sizeof message) == BDL_ERR_UNSTABLE);
    CHECK_MSG(strstr(message, "the spring_work_left of") != NULL, "%s", message);
}

int main(void)
{
    bdl_log_set_file(tmpfile());
    char folder[] = "/tmp/bedlam-test-outputs-XXXXXX";
    CHECK(mkdtemp(folder) != NULL);
    char sub[256], csv[256], state[256], failed[256];
    snprintf(sub, sizeof sub, "%s/checkpoint", folder);
    bdl_mkdir_p(sub);
    snprintf(csv, sizeof csv, "%s/diagnostics.csv", folder);
    snprintf(state, sizeof state, "%s/checkpoint/state.bdlckpt", folder);
    snprintf(failed, sizeof failed, "%s/checkpoint/failed.bdlckpt", folder);

    bdl_world *w = bdl_test_world("%s", scene_text);
    bdl_run_outputs o;
    memset(&o, 0, sizeof o);
    CHECK(bdl_run_outputs_open(&o, w, folder, 0, 0) == BDL_OK);
    CHECK(file_size(state) > 0); // the checkpoint of the start
    for (int k = 0; k < 3; ++k) {
        CHECK(bdl_world_step(w) == BDL_OK);
        CHECK(bdl_run_outputs_step(&o, w) == BDL_OK);
    }
    finite_check(w);
    undefined_columns(w);

    // A position gone NaN: the row due at this step is not written, the step stops the run.
    CHECK(bdl_world_step(w) == BDL_OK);
    w->particles.pos[bdl_test_find(w, 3)].x = NAN;
    bdl_result r = bdl_run_outputs_step(&o, w);
    CHECK(r == BDL_ERR_UNSTABLE);
    CHECK_MSG(strstr(o.failure, "the position of particle 3 (x component) is nan") != NULL, "%s",
              o.failure);
    const long good = file_size(state);
    CHECK(bdl_run_outputs_close(&o, 1, &r) == 1);
    CHECK(r == BDL_ERR_UNSTABLE);
    CHECK(bdl_csv_read_column(csv, "step", NULL, 0) == 4); // the start and three steps
    CHECK(file_size(failed) > 0);
    CHECK(file_size(state) == good);
    CHECK(strcmp(o.final_checkpoint, "failed.bdlckpt") == 0);
    CHECK(o.good_step == 0); // the start's
    bdl_world_destroy(w);
    char remove[300];
    snprintf(remove, sizeof remove, "rm -rf '%s'", folder);
    CHECK(system(remove) == 0);
    return bdl_test_summary("test_outputs");
}
