// bedlam — the files a run writes while it goes: diagnostics and series, VTK, contact files,
// frames, synthetic camera images and checkpoints, each at its times.
#define _POSIX_C_SOURCE 200809L // SIGKILL
#include "run/outputs.h"

#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/file.h"
#include "core/log.h"
#include "core/timer.h"
#include "output/capture.h"
#include "output/checkpoint.h"
#include "output/fields_out.h"
#include "output/granular_out.h"
#include "output/rheology_out.h"
#include "output/rod_angles_out.h"
#include "output/world_vtk.h"

static void path_join(char *out, size_t len, const char *a, const char *b)
{
    snprintf(out, len, "%s/%s", a, b);
}

/// Times are due when the step lands within half a step of them.
static int due(const bdl_world *w, double t) { return w->time >= t - 0.5 * w->dt; }

/// Output k of an interval is at k interval, computed as a product: a resumed run finds the
/// same times as the run it continues.
static double multiple(long k, double interval) { return (double)k * interval; }

/// Moves `next` past the current time to the following multiples of `interval`.
static void advance(const bdl_world *w, double *next, double interval)
{
    while (due(w, *next))
        *next = multiple(lround(*next / interval) + 1, interval);
}

/// The number of the first multiple of `interval` not due at the world's time: a run that
/// stands here (the step of its checkpoint) has written outputs 0 .. k - 1 of this interval.
static long first_not_due(const bdl_world *w, double interval)
{
    long k = (long)floor((w->time + 0.5 * w->dt) / interval);
    k = k < 0 ? 0 : k;
    while (k > 0 && !due(w, multiple(k - 1, interval)))
        --k;
    while (due(w, multiple(k, interval)))
        ++k;
    return k;
}

/// Records what stopped the run: a write of `path` that failed with result r (errno says why
/// for BDL_ERR_IO). The first failure is the one kept. Returns r.
static bdl_result failed_write(bdl_run_outputs *o, bdl_result r, const char *path)
{
    if (!o->write_failed) {
        if (r == BDL_ERR_IO)
            bdl_describe_write_error(o->failure, sizeof o->failure, path, errno);
        else
            snprintf(o->failure, sizeof o->failure, "%s: %s", path, bdl_result_text(r));
        o->write_failed = 1;
    }
    return r;
}

// ---------------------------------------------------------------------------------------------
// Writing one output.

static bdl_result write_vtk(bdl_run_outputs *o)
{
    const bdl_world *w = o->world;
    char rel[64], path[1200];
    snprintf(rel, sizeof rel, "vtk/particles_%06ld.vtp", o->vtk_index);
    path_join(path, sizeof path, o->out, rel);
    bdl_result r = bdl_world_vtp_write(w, path);
    if (r == BDL_OK && (r = bdl_pvd_add(o->pvd, w->time, rel)) != BDL_OK)
        path_join(path, sizeof path, o->out, "particles.pvd");
    if (r == BDL_OK && w->gas) {
        snprintf(rel, sizeof rel, "vtk/gas_%06ld.vti", o->vtk_index);
        path_join(path, sizeof path, o->out, rel);
        r = bdl_world_gas_vti_write(w, path);
        if (r == BDL_OK && o->gas_pvd && (r = bdl_pvd_add(o->gas_pvd, w->time, rel)) != BDL_OK)
            path_join(path, sizeof path, o->out, "gas.pvd");
    }
    o->vtk_index++;
    return r == BDL_OK ? r : failed_write(o, r, path);
}

/// A sample of the particles for fields.vti, counted from fields_start on.
static bdl_result sample_fields(bdl_run_outputs *o)
{
    const bdl_world *w = o->world;
    if (!due(w, w->scene.output.fields_start))
        return BDL_OK;
    const bdl_result r = bdl_fields_add_world(&o->fields, w);
    if (r != BDL_OK) {
        char path[1200];
        path_join(path, sizeof path, o->out, "fields.vti");
        return failed_write(o, r, path);
    }
    return r;
}

/// fields.vti of the samples so far (none yet: nothing written); `failure` says why it failed.
static bdl_result write_fields(const bdl_run_outputs *o, char *failure, size_t len)
{
    if (o->fields.samples == 0)
        return BDL_OK;
    char path[1200];
    path_join(path, sizeof path, o->out, "fields.vti");
    const bdl_result r = bdl_fields_vti_write(&o->fields, path);
    if (r == BDL_ERR_IO)
        bdl_describe_write_error(failure, len, path, errno);
    else if (r != BDL_OK)
        snprintf(failure, len, "%s: %s", path, bdl_result_text(r));
    return r;
}

/// The sums of the fields, before the checkpoint of the same state: checkpoint/fields.sums. The
/// sums of the last good checkpoint move aside to fields.prev.sums first, so that whenever the run
/// is killed one of the two files holds the sums of the checkpoint on the disk.
static bdl_result save_sums(bdl_run_outputs *o, char *failure, size_t len)
{
    char path[1200], previous[1200];
    path_join(path, sizeof path, o->out, "checkpoint/fields.sums");
    path_join(previous, sizeof previous, o->out, "checkpoint/fields.prev.sums");
    if (o->sums_at_good && rename(path, previous) != 0) {
        bdl_describe_write_error(failure, len, previous, errno);
        return BDL_ERR_IO;
    }
    o->sums_at_good = 0;
    const bdl_fields_stamp stamp = bdl_fields_stamp_of(o->world, o->fields_cell);
    const bdl_result r = bdl_fields_sums_save(&o->fields, &stamp, path);
    if (r != BDL_OK)
        bdl_describe_write_error(failure, len, path, errno);
    return r;
}

/// The world's state as checkpoint/NAME; a written state.bdlckpt is the run's last good one, with
/// the sums of the fields beside it. fields.vti is written with every checkpoint, just before it.
static bdl_result write_checkpoint(bdl_run_outputs *o, const char *name, char *failure, size_t len)
{
    char file[64], path[1200];
    snprintf(file, sizeof file, "checkpoint/%s", name);
    path_join(path, sizeof path, o->out, file);
    const int good = strcmp(name, "state.bdlckpt") == 0;
    bdl_result r = good && o->fields_on ? save_sums(o, failure, len) : BDL_OK;
    if (r == BDL_OK && o->fields_on)
        r = write_fields(o, failure, len);
    if (r != BDL_OK)
        return r;
    r = bdl_checkpoint_save(o->world, path);
    if (r == BDL_ERR_IO)
        bdl_describe_write_error(failure, len, path, errno);
    else if (r != BDL_OK)
        snprintf(failure, len, "%s: %s", path, bdl_result_text(r));
    if (r == BDL_OK && good) {
        snprintf(o->good_path, sizeof o->good_path, "%s", path);
        o->good_time = o->world->time;
        o->good_step = o->world->step;
        o->sums_at_good = o->fields_on;
    }
    return r;
}

/// Accepts NaN in any column: it marks a value that is not defined (a species with no
/// particles, an empty histogram).
static int any_column(int column)
{
    (void)column;
    return 1;
}

/// The rows of the diagnostics and the series, checked to be finite before any is written.
static bdl_result write_diagnostics(bdl_run_outputs *o, bdl_diagnostics *d)
{
    const bdl_world *w = o->world;
    double row[64];
    if (bdl_diagnostics_column_count > 64)
        return BDL_ERR_ARGS; // a column added without room for it here
    d->wall_seconds = bdl_wall_seconds() - o->start_wall;
    bdl_diagnostics_row(d, row);
    if (o->species_csv)
        bdl_species_row(w, o->species_row);
    if (o->profile_csv)
        bdl_profile_row(w, o->profile_row);
    char *why = o->failure;
    const size_t len = sizeof o->failure;
    bdl_result r = bdl_guards_check_row(w, "diagnostics.csv", bdl_diagnostics_columns, row,
                                        bdl_diagnostics_columns_for(w),
                                        bdl_diagnostics_may_be_undefined, why, len);
    if (r == BDL_OK && o->species_csv)
        r = bdl_guards_check_row(w, "species.csv", NULL, o->species_row, o->species_columns,
                                 any_column, why, len);
    if (r == BDL_OK && o->profile_csv)
        r = bdl_guards_check_row(w, "profile.csv", NULL, o->profile_row, o->profile_columns, NULL,
                                 why, len);
    if (r != BDL_OK)
        return r;
    char path[1200];
    if (bdl_csv_row(o->csv, row) != BDL_OK) {
        path_join(path, sizeof path, o->out, "diagnostics.csv");
        return failed_write(o, BDL_ERR_IO, path);
    }
    if (o->species_csv && bdl_csv_row(o->species_csv, o->species_row) != BDL_OK) {
        path_join(path, sizeof path, o->out, "species.csv");
        return failed_write(o, BDL_ERR_IO, path);
    }
    if (o->profile_csv && bdl_csv_row(o->profile_csv, o->profile_row) != BDL_OK) {
        path_join(path, sizeof path, o->out, "profile.csv");
        return failed_write(o, BDL_ERR_IO, path);
    }
    return BDL_OK;
}

static bdl_result write_orientation(bdl_run_outputs *o)
{
    double row[BDL_ROD_ANGLE_COLUMNS];
    bdl_rod_angle_row(o->world, row);
    bdl_result r =
        bdl_guards_check_row(o->world, "orientation.csv", NULL, row, BDL_ROD_ANGLE_COLUMNS,
                             any_column, o->failure, sizeof o->failure);
    if (r == BDL_OK && bdl_csv_row(o->orientation_csv, row) != BDL_OK) {
        char path[1200];
        path_join(path, sizeof path, o->out, "orientation.csv");
        r = failed_write(o, BDL_ERR_IO, path);
    }
    return r;
}

static bdl_result write_rheology(bdl_run_outputs *o)
{
    double row[BDL_RHEOLOGY_COLUMNS];
    char path[1200];
    path_join(path, sizeof path, o->out, "rheology.csv");
    bdl_result r = bdl_rheology_row(o->world, row);
    if (r != BDL_OK) {
        snprintf(o->failure, sizeof o->failure, "out of memory for the contacts of %s", path);
        return r;
    }
    if (bdl_csv_row(o->rheology_csv, row) != BDL_OK)
        r = failed_write(o, BDL_ERR_IO, path);
    return r;
}

static bdl_result write_contacts(bdl_run_outputs *o)
{
    char rel[64], path[1200];
    const bdl_world *w = o->world;
    snprintf(rel, sizeof rel, "contacts/contacts_%06ld.csv",
             lround(w->time / w->scene.output.contacts_interval));
    path_join(path, sizeof path, o->out, rel);
    bdl_result r = bdl_contacts_write(w, path);
    return r == BDL_OK ? r : failed_write(o, r, path);
}

/// Why the frame writer failed, as the run's failure; returns r.
static bdl_result frames_failed(bdl_run_outputs *o, bdl_result r)
{
    if (!o->write_failed) {
        const char *why = bdl_frames_failure(o->frames);
        snprintf(o->failure, sizeof o->failure, "frames: %s", why[0] ? why : bdl_result_text(r));
        o->write_failed = 1;
    }
    return r;
}

static bdl_result write_frame(bdl_run_outputs *o)
{
    bdl_result r = bdl_run_frame(o->frames, o->world, o->frame_index++);
    return r == BDL_OK ? r : frames_failed(o, r);
}

static bdl_result camera_images(bdl_run_outputs *o, const bdl_particle_view *view)
{
    bdl_result r = bdl_dia_run_step(o->dia, view);
    if (r != BDL_OK && !o->write_failed) {
        const char *why = bdl_dia_run_failure(o->dia);
        snprintf(o->failure, sizeof o->failure, "synthetic camera images: %s",
                 why[0] ? why : bdl_result_text(r));
        o->write_failed = 1;
    }
    return r;
}

/// Everything written so far on the disk, before a checkpoint: the rows of the series flushed
/// and fsynced, the queued frames written, the cameras' indexes fsynced. (VTK, contact, .pvd,
/// image and frame files are written atomically, each fsynced as it is renamed into place.)
static bdl_result sync_outputs(bdl_run_outputs *o)
{
    const struct {
        bdl_csv *csv;
        const char *file;
    } series[] = {{o->csv, "diagnostics.csv"},
                  {o->species_csv, "species.csv"},
                  {o->profile_csv, "profile.csv"},
                  {o->orientation_csv, "orientation.csv"},
                  {o->rheology_csv, "rheology.csv"}};
    for (int k = 0; k < 5; ++k)
        if (bdl_csv_sync(series[k].csv) != BDL_OK) {
            char path[1200];
            path_join(path, sizeof path, o->out, series[k].file);
            return failed_write(o, BDL_ERR_IO, path);
        }
    bdl_result r = o->frames ? bdl_frames_sync(o->frames) : BDL_OK;
    if (r != BDL_OK)
        return frames_failed(o, r);
    if (o->dia && (r = bdl_dia_run_sync(o->dia)) != BDL_OK) {
        snprintf(o->failure, sizeof o->failure, "synthetic camera images: %s",
                 bdl_dia_run_failure(o->dia));
        o->write_failed = 1;
    }
    return r;
}

// ---------------------------------------------------------------------------------------------
// Opening.

/// A CSV file of the run: `count` columns named by `names` (NULL: none, nothing opened). A
/// resumed run drops the rows after the checkpoint's time and appends.
static bdl_result open_csv(const bdl_run_outputs *o, const char *file, const char *const *names,
                           int count, int resume, bdl_csv **csv)
{
    char path[1200], why[1300];
    path_join(path, sizeof path, o->out, file);
    if (resume && bdl_csv_truncate_after(path, o->world->time) != BDL_OK) {
        bdl_describe_write_error(why, sizeof why, path, errno);
        bdl_error("cannot continue %s", why);
        return BDL_ERR_OUTPUT_DIR;
    }
    if (!(*csv = bdl_csv_open(path, names, count, resume))) {
        bdl_describe_write_error(why, sizeof why, path, errno);
        bdl_error("cannot create %s", why);
        return BDL_ERR_OUTPUT_DIR;
    }
    return BDL_OK;
}

/// species.csv (two or more species) and profile.csv (a gas), with their row buffers.
static bdl_result open_series(bdl_run_outputs *o, int resume)
{
    char names[BDL_SPECIES_COLUMNS_MAX][BDL_SPECIES_COLUMN_LEN];
    const char *pointers[BDL_SPECIES_COLUMNS_MAX];
    int count = bdl_species_columns(o->world, names);
    for (int c = 0; c < count; ++c)
        pointers[c] = names[c];
    bdl_result r = BDL_OK;
    if (count > 0 && !(o->species_row = malloc(BDL_SPECIES_COLUMNS_MAX * sizeof(double))))
        return BDL_ERR_NOMEM;
    o->species_columns = count;
    if (count > 0)
        r = open_csv(o, "species.csv", pointers, count, resume, &o->species_csv);
    count = bdl_profile_columns(o->world, NULL);
    if (r != BDL_OK || count == 0)
        return r;
    char(*profile)[BDL_SPECIES_COLUMN_LEN] = malloc((size_t)count * sizeof *profile);
    const char **profile_names = malloc((size_t)count * sizeof *profile_names);
    o->profile_row = malloc((size_t)count * sizeof(double));
    o->profile_columns = count;
    r = profile && profile_names && o->profile_row ? BDL_OK : BDL_ERR_NOMEM;
    if (r == BDL_OK) {
        bdl_profile_columns(o->world, profile);
        for (int c = 0; c < count; ++c)
            profile_names[c] = profile[c];
        r = open_csv(o, "profile.csv", profile_names, count, resume, &o->profile_csv);
    }
    free(profile);
    free(profile_names);
    return r;
}

/// orientation.csv, in scenes with rods when [output] orientation_interval is set.
static bdl_result open_orientation(bdl_run_outputs *o, int resume)
{
    const bdl_world *w = o->world;
    if (!w->particles.rods || !(w->scene.output.orientation_interval > 0.0))
        return BDL_OK;
    char names[BDL_ROD_ANGLE_COLUMNS][BDL_ROD_ANGLE_COLUMN_LEN];
    const char *pointers[BDL_ROD_ANGLE_COLUMNS];
    const int count = bdl_rod_angle_columns(names);
    for (int c = 0; c < count; ++c)
        pointers[c] = names[c];
    return open_csv(o, "orientation.csv", pointers, count, resume, &o->orientation_csv);
}

/// rheology.csv, when [output] rheology_interval is set.
static bdl_result open_rheology(bdl_run_outputs *o, int resume)
{
    if (!(o->world->scene.output.rheology_interval > 0.0))
        return BDL_OK;
    return open_csv(o, "rheology.csv", bdl_rheology_columns, BDL_RHEOLOGY_COLUMNS, resume,
                    &o->rheology_csv);
}

/// A VTK collection: a new one, or a resumed run's with the entries up to its checkpoint (and
/// their true times). NULL after an error message.
static bdl_pvd *open_pvd(const bdl_run_outputs *o, const char *file, int resume)
{
    char path[1200], why[1300];
    path_join(path, sizeof path, o->out, file);
    const bdl_world *w = o->world;
    // Entries are at step times: those up to the checkpoint's step are <= its time, the later
    // ones at least a step after it (half a step also keeps the nominal times older runs wrote).
    bdl_pvd *pvd = resume ? bdl_pvd_continue(path, w->time + 0.5 * w->dt) : bdl_pvd_create(path);
    if (!pvd) {
        bdl_describe_write_error(why, sizeof why, path, errno);
        bdl_error("cannot write %s", why);
    }
    return pvd;
}

/// The diagnostics, the series, the contact folder and the VTK collections.
static bdl_result open_files(bdl_run_outputs *o, int resume)
{
    const bdl_world *w = o->world;
    const bdl_output_def *out = &w->scene.output;
    bdl_result r = open_csv(o, "diagnostics.csv", bdl_diagnostics_columns,
                            bdl_diagnostics_columns_for(w), resume, &o->csv);
    if (r == BDL_OK)
        r = open_series(o, resume);
    if (r == BDL_OK)
        r = open_orientation(o, resume);
    if (r == BDL_OK)
        r = open_rheology(o, resume);
    char sub[1200];
    if (r == BDL_OK && out->contacts_interval > 0.0) {
        path_join(sub, sizeof sub, o->out, "contacts");
        if (bdl_mkdir_p(sub) != BDL_OK) {
            bdl_error("cannot create '%s'", sub);
            r = BDL_ERR_OUTPUT_DIR;
        }
    }
    if (r != BDL_OK)
        return r;
    if (!(o->pvd = open_pvd(o, "particles.pvd", resume)))
        return BDL_ERR_OUTPUT_DIR;
    if (w->gas && out->vtk_interval > 0.0 && !(o->gas_pvd = open_pvd(o, "gas.pvd", resume)))
        return BDL_ERR_OUTPUT_DIR;
    return BDL_OK;
}

/// Whether two paths name the same file.
static int same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev &&
           sa.st_ino == sb.st_ino;
}

/// A resumed run's sums of the fields: those beside the checkpoint it resumed from that are of
/// its state and settings (fields.sums, or fields.prev.sums when the run was killed between
/// writing the two). Returns 0 when there are none (the log says why).
static int resume_sums(bdl_run_outputs *o)
{
    const bdl_world *w = o->world;
    static const char *const names[2] = {"fields.sums", "fields.prev.sums"};
    char folder[1200], path[1300], mine[1200], why[2][1400];
    snprintf(folder, sizeof folder, "%s", o->good_path);
    char *slash = strrchr(folder, '/');
    if (slash)
        *slash = '\0';
    else
        snprintf(folder, sizeof folder, ".");
    for (int k = 0; k < 2; ++k) {
        snprintf(path, sizeof path, "%s/%s", folder, names[k]);
        bdl_fields f;
        bdl_fields_stamp stamp;
        if (bdl_fields_sums_load(&f, &stamp, path, why[k], sizeof why[k]) != BDL_OK)
            continue;
        char differs[1200];
        if (!bdl_fields_stamp_matches(&f, &stamp, w, differs, sizeof differs)) {
            snprintf(why[k], sizeof why[k], "the sums in %s %s", path, differs);
            bdl_fields_free(&f);
            continue;
        }
        o->fields = f;
        o->fields_cell = stamp.cell;
        path_join(mine, sizeof mine, o->out, "checkpoint/fields.sums");
        o->sums_at_good = k == 0 && same_file(path, mine);
        return 1;
    }
    bdl_warn("fields.vti averages from t = %g s only, the sums before it are not found: %s; %s",
             w->time, why[0], why[1]);
    return 0;
}

/// The time-averaged fields ([output] fields_interval): a resumed run's sums so far, else an
/// empty grid of fields_cell, or of three mean diameters of the particles as they stand.
static bdl_result open_fields(bdl_run_outputs *o, int resume)
{
    const bdl_world *w = o->world;
    const bdl_output_def *out = &w->scene.output;
    if (!(out->fields_interval > 0.0))
        return BDL_OK;
    o->fields_on = 1;
    const int resumed = resume && resume_sums(o);
    char why[512];
    bdl_result r = BDL_OK;
    if (!resumed) {
        o->fields_cell = out->fields_cell > 0.0 ? out->fields_cell : bdl_fields_world_cell(w);
        r = bdl_fields_create_world(&o->fields, w, o->fields_cell, why, sizeof why);
    }
    if (r == BDL_ERR_SCENE && out->fields_cell > 0.0)
        bdl_error("%s: [output] fields_cell = %g: %s", w->scene.path, out->fields_cell, why);
    else if (r == BDL_ERR_SCENE)
        bdl_error("%s: [output] fields_cell is not given, and its default, three mean diameters "
                  "of the particles (%g m), %s; give a larger fields_cell",
                  w->scene.path, o->fields_cell, why);
    else if (r != BDL_OK)
        bdl_error("fields: %s", bdl_result_text(r));
    else
        bdl_info(
            "fields: a sample every %g s from t = %g s, on %d x %d x %d cells of %.3g x %.3g x "
            "%.3g m, into fields.vti%s",
            out->fields_interval, out->fields_start, o->fields.n[0], o->fields.n[1], o->fields.n[2],
            o->fields.h[0], o->fields.h[1], o->fields.h[2],
            resumed ? " (continuing the samples before the checkpoint)" : "");
    return r;
}

/// A resumed run's next outputs: after the last ones its first run wrote before the checkpoint
/// (every output due at the checkpoint's step was written before the checkpoint).
static void schedule_resumed(bdl_run_outputs *o)
{
    const bdl_world *w = o->world;
    const bdl_output_def *out = &w->scene.output;
    const double intervals[7] = {out->diagnostics_interval, out->contacts_interval,
                                 out->orientation_interval, out->checkpoint_interval,
                                 out->vtk_interval,         out->fields_interval,
                                 out->rheology_interval};
    double *next[7] = {&o->next_diag, &o->next_contacts, &o->next_orientation, &o->next_checkpoint,
                       &o->next_vtk,  &o->next_fields,   &o->next_rheology};
    for (int k = 0; k < 7; ++k)
        *next[k] =
            intervals[k] > 0.0 ? multiple(first_not_due(w, intervals[k]), intervals[k]) : INFINITY;
    o->vtk_index = out->vtk_interval > 0.0 ? first_not_due(w, out->vtk_interval) : 0;
}

/// A new run writes the diagnostics row, the VTK files and the contact file of its start; a
/// resumed one finds them written.
static bdl_result schedule(bdl_run_outputs *o, bdl_diagnostics *d0, int resume)
{
    const bdl_output_def *out = &o->world->scene.output;
    if (resume) {
        schedule_resumed(o);
        return BDL_OK;
    }
    o->next_checkpoint = out->checkpoint_interval > 0.0 ? out->checkpoint_interval : INFINITY;
    bdl_result r = bdl_guards_check_finite(o->world, &o->guard, o->failure, sizeof o->failure);
    if (r == BDL_OK)
        r = write_diagnostics(o, d0);
    if (r == BDL_OK && out->vtk_interval > 0.0)
        r = write_vtk(o);
    if (r == BDL_OK && out->contacts_interval > 0.0)
        r = write_contacts(o);
    if (r == BDL_OK && o->orientation_csv)
        r = write_orientation(o);
    if (r == BDL_OK && o->rheology_csv)
        r = write_rheology(o);
    if (r == BDL_OK && o->fields_on)
        r = sample_fields(o);
    o->next_diag = out->diagnostics_interval;
    o->next_fields = out->fields_interval;
    o->next_orientation = out->orientation_interval;
    o->next_rheology = out->rheology_interval;
    o->next_vtk = out->vtk_interval;
    o->next_contacts = out->contacts_interval;
    if (r != BDL_OK)
        bdl_error("cannot write the first outputs: %s", o->failure);
    return r;
}

/// The frame writer: frame k is at k frame_interval, so a resumed run continues the numbering.
static bdl_result open_frames(bdl_run_outputs *o, int resume, int gl_backend)
{
    const bdl_world *w = o->world;
    const bdl_output_def *out = &w->scene.output;
    char folder[1200], why[1024];
    path_join(folder, sizeof folder, o->out, "frames");
    bdl_frames_def fd = {.scene = &w->scene, .folder = folder, .backend = gl_backend};
    bdl_result r = bdl_frames_open(&fd, &o->frames, why, sizeof why);
    if (r != BDL_OK) {
        bdl_error("cannot draw frames: %s", why);
        return r;
    }
    // A new run takes the frame of its start; a resumed one the first its first run did not.
    o->frame_index = resume ? first_not_due(w, out->frame_interval) : 0;
    o->next_frame = multiple(o->frame_index, out->frame_interval);
    if (due(w, o->next_frame) && (r = write_frame(o)) != BDL_OK) {
        bdl_error("cannot draw frames: %s", o->failure);
        return r;
    }
    advance(w, &o->next_frame, out->frame_interval);
    bdl_info("frames: %dx%d every %g s in %s", out->frame_width, out->frame_height,
             out->frame_interval, folder);
    return BDL_OK;
}

/// The synthetic cameras, and an image due at the start.
static bdl_result open_cameras(bdl_run_outputs *o, int resume)
{
    const bdl_scene *s = &o->world->scene;
    char why[1024] = "";
    bdl_particle_view now;
    if (!bdl_capture_solids_view(&o->solids_sample, o->world, &now)) {
        bdl_error("synthetic cameras: out of memory for the spheres of the solids phases");
        return BDL_ERR_NOMEM;
    }
    bdl_result r = bdl_dia_run_open(s, &now, o->out, resume, &o->dia, why, sizeof why);
    if (r != BDL_OK) {
        bdl_error("synthetic cameras: %s", why);
        return r;
    }
    if ((r = camera_images(o, &now)) != BDL_OK) {
        bdl_error("%s", o->failure);
        return r;
    }
    for (int k = 0; k < s->dia_count; ++k) {
        const bdl_dia_scene_def *dd = &s->dias[k];
        bdl_info("camera %s: %dx%d %s images every %g s%s in %s/dia/%s", dd->name, dd->width,
                 dd->height, bdl_dia_lighting_labels[dd->lighting], dd->interval,
                 dd->pair_dt > 0.0 ? " (PIV pairs)" : "", o->out, dd->name);
    }
    return BDL_OK;
}

/// A new run's first checkpoint, of its start, once the outputs of the start are on the disk: a
/// run killed before its first checkpoint_interval resumes from here, never from a checkpoint an
/// earlier run left in the folder. (This is the caller's thread, which draws the frames: it draws
/// the first one before waiting for it.)
static bdl_result start_checkpoint(bdl_run_outputs *o)
{
    if (o->frames)
        bdl_frames_pump(o->frames, 0.0);
    bdl_result r = sync_outputs(o);
    if (r == BDL_OK &&
        (r = write_checkpoint(o, "state.bdlckpt", o->failure, sizeof o->failure)) != BDL_OK)
        o->write_failed = 1;
    if (r != BDL_OK)
        bdl_error("cannot write the outputs of the start: %s", o->failure);
    return r;
}

/// Left-overs of a killed run: its temporary files (never renamed into place), and for a new
/// run the failed state of an earlier one and the sums of its fields.
static void clear_leftovers(const bdl_run_outputs *o, int resume)
{
    static const char *const folders[] = {"", "/vtk", "/checkpoint", "/frames", "/contacts"};
    char folder[1200];
    for (int k = 0; k < 5; ++k) {
        snprintf(folder, sizeof folder, "%s%s", o->out, folders[k]);
        bdl_remove_stale_temporaries(folder);
    }
    const bdl_scene *s = &o->world->scene;
    for (int k = 0; k < s->dia_count; ++k) {
        snprintf(folder, sizeof folder, "%s/dia/%s", o->out, s->dias[k].name);
        bdl_remove_stale_temporaries(folder);
    }
    if (!resume) { // an earlier run's failed state, and its fields' sums
        static const char *const files[3] = {"checkpoint/failed.bdlckpt", "checkpoint/fields.sums",
                                             "checkpoint/fields.prev.sums"};
        for (int k = 0; k < 3; ++k) {
            path_join(folder, sizeof folder, o->out, files[k]);
            unlink(folder);
        }
    }
}

bdl_result bdl_run_outputs_open(bdl_run_outputs *o, bdl_world *w, const char *out, int resume,
                                int gl_backend)
{
    o->out = out;
    o->world = w;
    o->start_wall = bdl_wall_seconds();
    // Tests only: the run kills itself (SIGKILL, as kill -9) at the end of this step's outputs,
    // just before its checkpoint would be written (tests/scripts/kill_cli.sh).
    const char *kill_at = getenv("BEDLAM_TEST_KILL_AT_STEP");
    o->kill_at_step = kill_at ? strtol(kill_at, NULL, 10) : -1;
    o->good_time = w->time;
    o->good_step = w->step;
    clear_leftovers(o, resume);
    bdl_diagnostics d0;
    if (!resume) {
        bdl_diagnostics_compute(w, 0.0, &d0);
        w->energy0 = bdl_diagnostics_total_energy(&d0);
    }
    o->energy0 = w->energy0;
    bdl_diagnostics_compute(w, o->energy0, &d0);
    bdl_guards_init(&o->guard, w, &d0);
    bdl_result r = open_files(o, resume);
    if (r == BDL_OK)
        r = open_fields(o, resume);
    if (r == BDL_OK)
        r = schedule(o, &d0, resume);
    if (r == BDL_OK && w->scene.output.frame_interval > 0.0)
        r = open_frames(o, resume, gl_backend);
    if (r == BDL_OK && w->scene.dia_count > 0)
        r = open_cameras(o, resume);
    if (r == BDL_OK && !resume)
        r = start_checkpoint(o);
    return r;
}

// ---------------------------------------------------------------------------------------------
// Each step.

/// What falls due at this step.
typedef struct due_now {
    int row, check, vtk, contacts, orientation, rheology, frame, camera, fields, checkpoint;
} due_now;

static due_now what_is_due(const bdl_run_outputs *o, const bdl_world *w)
{
    const bdl_output_def *out = &w->scene.output;
    due_now d = {0};
    d.row = due(w, o->next_diag);
    d.check = w->step % w->scene.guards.check_interval == 0;
    d.vtk = out->vtk_interval > 0.0 && due(w, o->next_vtk);
    d.contacts = out->contacts_interval > 0.0 && due(w, o->next_contacts);
    d.orientation = o->orientation_csv && due(w, o->next_orientation);
    d.rheology = o->rheology_csv && due(w, o->next_rheology);
    d.frame = o->frames && due(w, o->next_frame);
    d.fields = o->fields_on && due(w, o->next_fields);
    if (o->dia) {
        const bdl_particle_view view = bdl_capture_view(w);
        d.camera = bdl_dia_run_due(o->dia, &view);
    }
    d.checkpoint = out->checkpoint_interval > 0.0 && due(w, o->next_checkpoint);
    return d;
}

int bdl_run_outputs_due(const bdl_run_outputs *o, const bdl_world *w)
{
    const due_now d = what_is_due(o, w);
    return d.row || d.check || d.vtk || d.contacts || d.orientation || d.rheology || d.frame ||
           d.camera || d.fields || d.checkpoint || w->step == o->kill_at_step ||
           (o->stop && *o->stop);
}

/// The guards: all of them every check_interval steps, those of the state before a checkpoint,
/// the finite check before any other output; the diagnostics row when one is due; the error figures
/// for the progress line.
static bdl_result diagnose(bdl_run_outputs *o, bdl_world *w, const due_now *now)
{
    const int writes = now->vtk || now->contacts || now->orientation || now->rheology ||
                       now->frame || now->camera || now->fields;
    if (!now->row && !now->check && !now->checkpoint)
        return writes ? bdl_guards_check_finite(w, &o->guard, o->failure, sizeof o->failure)
                      : BDL_OK;
    bdl_diagnostics d;
    bdl_diagnostics_compute(w, o->energy0, &d);
    atomic_store(&o->energy_balance, d.energy_balance);
    atomic_store(&o->energy_in, d.wall_work + d.gas_work + w->inserted_energy);
    atomic_store(&o->weight_ratio, d.weight_ratio);
    atomic_store(&o->gas_mass, d.gas_volume_imbalance);
    atomic_store(&o->momentum, d.momentum_imbalance);
    atomic_store(&o->particles_out, d.particles_out);
    atomic_store(&o->measured, 1);
    char *why = o->failure;
    bdl_result r = now->check ? bdl_guards_check(w, &o->guard, &d, why, sizeof o->failure)
                   : now->checkpoint
                       ? bdl_guards_check_state(w, &o->guard, &d, why, sizeof o->failure)
                       : bdl_guards_check_finite(w, &o->guard, why, sizeof o->failure);
    if (r == BDL_OK && now->row) {
        r = write_diagnostics(o, &d);
        advance(w, &o->next_diag, w->scene.output.diagnostics_interval);
    }
    return r;
}

/// The outputs due but the diagnostics and the checkpoint, in file order.
static bdl_result write_due(bdl_run_outputs *o, bdl_world *w, const due_now *d)
{
    const bdl_output_def *out = &w->scene.output;
    bdl_result r = BDL_OK;
    if (d->vtk) {
        r = write_vtk(o);
        advance(w, &o->next_vtk, out->vtk_interval);
    }
    if (r == BDL_OK && d->contacts) {
        r = write_contacts(o);
        advance(w, &o->next_contacts, out->contacts_interval);
    }
    if (r == BDL_OK && d->orientation) {
        r = write_orientation(o);
        advance(w, &o->next_orientation, out->orientation_interval);
    }
    if (r == BDL_OK && d->rheology) {
        r = write_rheology(o);
        advance(w, &o->next_rheology, out->rheology_interval);
    }
    if (r == BDL_OK && d->frame) {
        r = write_frame(o);
        advance(w, &o->next_frame, out->frame_interval);
    }
    if (r == BDL_OK && o->dia) { // a continuum's spheres sampled only when an image is due
        bdl_particle_view view = bdl_capture_view(w);
        if (d->camera && !bdl_capture_solids_view(&o->solids_sample, w, &view))
            r = BDL_ERR_NOMEM;
        if (r == BDL_OK)
            r = camera_images(o, &view);
    }
    if (r == BDL_OK && d->fields) {
        r = sample_fields(o);
        advance(w, &o->next_fields, out->fields_interval);
    }
    return r;
}

bdl_result bdl_run_outputs_step(void *user, bdl_world *w)
{
    bdl_run_outputs *o = user;
    const due_now d = what_is_due(o, w);
    bdl_result r = diagnose(o, w, &d);
    if (r == BDL_OK)
        r = write_due(o, w, &d);
    if (w->step == o->kill_at_step)
        raise(SIGKILL);
    if (r == BDL_OK && d.checkpoint) {
        r = sync_outputs(o);
        if (r == BDL_OK &&
            (r = write_checkpoint(o, "state.bdlckpt", o->failure, sizeof o->failure)) != BDL_OK)
            o->write_failed = 1;
        advance(w, &o->next_checkpoint, w->scene.output.checkpoint_interval);
    }
    if (r == BDL_OK && o->stop && *o->stop)
        r = BDL_ERR_INTERRUPTED;
    return r;
}

void bdl_run_outputs_status(bdl_run_outputs *o, bdl_run_status *s)
{
    s->measured = atomic_load(&o->measured);
    s->energy_balance = atomic_load(&o->energy_balance);
    s->energy_in = atomic_load(&o->energy_in);
    s->weight_ratio = atomic_load(&o->weight_ratio);
    s->gas_volume_imbalance = atomic_load(&o->gas_mass);
    s->momentum_imbalance = atomic_load(&o->momentum);
    s->particles_out = atomic_load(&o->particles_out);
}

// ---------------------------------------------------------------------------------------------
// Closing.

/// A failure while closing: the run's own when it had none yet, else reported after it.
static void close_failed(bdl_run_outputs *o, bdl_result *r, bdl_result failure, const char *why)
{
    if (*r == BDL_OK || *r == BDL_ERR_INTERRUPTED) {
        *r = failure;
        snprintf(o->failure, sizeof o->failure, "%s", why);
        o->write_failed = failure != BDL_ERR_UNSTABLE;
    } else if (!o->also[0]) {
        snprintf(o->also, sizeof o->also, "%s", why);
    }
}

/// The frame writer and the cameras, with what they wrote in the log.
static void close_images(bdl_run_outputs *o, bdl_result *r)
{
    if (o->frames) {
        long written = 0;
        bdl_result fr = bdl_frames_close(o->frames, &written);
        bdl_info("frames: %ld written", written);
        if (fr != BDL_OK) {
            char why[1300];
            snprintf(why, sizeof why, "frames: %s", bdl_result_text(fr));
            close_failed(o, r, fr, why);
        }
        o->frames = NULL;
    }
    if (o->dia) {
        bdl_info("synthetic cameras: %ld images written", bdl_dia_run_count(o->dia));
        bdl_dia_run_close(o->dia);
        o->dia = NULL;
    }
    bdl_solids_sample_free(&o->solids_sample); // (filled before the cameras opened, or failed to)
}

/// The series closed: their last rows reach the disk, or the failure names the file.
static void close_series(bdl_run_outputs *o, bdl_result *r)
{
    bdl_csv **csvs[5] = {&o->csv, &o->species_csv, &o->profile_csv, &o->orientation_csv,
                         &o->rheology_csv};
    static const char *const files[5] = {"diagnostics.csv", "species.csv", "profile.csv",
                                         "orientation.csv", "rheology.csv"};
    for (int k = 0; k < 5; ++k) {
        if (!*csvs[k])
            continue;
        bdl_result cr = bdl_csv_sync(*csvs[k]);
        cr = bdl_csv_close(*csvs[k]) == BDL_OK ? cr : BDL_ERR_IO;
        *csvs[k] = NULL;
        if (cr != BDL_OK) {
            char path[1200], why[1300];
            path_join(path, sizeof path, o->out, files[k]);
            bdl_describe_write_error(why, sizeof why, path, errno);
            close_failed(o, r, cr, why);
        }
    }
}

/// What fields.vti holds at the end.
static void log_fields(const bdl_run_outputs *o)
{
    const bdl_fields *f = &o->fields;
    if (o->fields_on && f->samples > 0)
        bdl_info("fields.vti: %ld sample%s from t = %g to %g s; solids volume on the grid %.6g "
                 "of %.6g m^3 (the rest was outside the domain)",
                 f->samples, f->samples == 1 ? "" : "s", f->first, f->last, f->deposited, f->total);
    else if (o->fields_on)
        bdl_warn("fields.vti is not written: no sample from fields_start = %g s on",
                 o->world->scene.output.fields_start);
}

/// The end of a run that stepped: the last row after a clean end, the series on the disk, and the
/// state as state.bdlckpt when it passes the guards, else beside it as failed.bdlckpt.
static int close_solved(bdl_run_outputs *o, bdl_result *r)
{
    bdl_world *w = o->world;
    const double interval = w->scene.output.diagnostics_interval;
    bdl_diagnostics d;
    bdl_diagnostics_compute(w, o->energy0, &d);
    // The state is sound after a clean end, a stop, or a failed write, if it passes the guards of
    // the state now (the last check may be up to check_interval steps back).
    int broken = !(*r == BDL_OK || *r == BDL_ERR_INTERRUPTED || o->write_failed);
    char why[1400];
    if (!broken && bdl_guards_check_state(w, &o->guard, &d, why, sizeof why) != BDL_OK) {
        broken = 1;
        if (*r == BDL_OK || *r == BDL_ERR_INTERRUPTED)
            close_failed(o, r, BDL_ERR_UNSTABLE, why);
        else // after a failed write: the instability is news as well
            snprintf(o->also, sizeof o->also, "%s", why);
    }
    if (*r == BDL_OK && !due(w, o->next_diag - interval) && write_diagnostics(o, &d) != BDL_OK) {
        broken = !o->write_failed;
        *r = o->write_failed ? BDL_ERR_IO : BDL_ERR_UNSTABLE;
    }
    close_series(o, r);
    const char *name = broken ? "failed.bdlckpt" : "state.bdlckpt";
    const bdl_result cr = write_checkpoint(o, name, why, sizeof why);
    snprintf(o->final_checkpoint, sizeof o->final_checkpoint, "%s", cr == BDL_OK ? name : "");
    if (cr != BDL_OK) {
        char line[1500];
        snprintf(line, sizeof line, "cannot write the checkpoint: %s", why);
        close_failed(o, r, cr, line);
    }
    log_fields(o);
    return broken;
}

int bdl_run_outputs_close(bdl_run_outputs *o, int solved, bdl_result *r)
{
    close_images(o, r);
    const int failed = solved ? close_solved(o, r) : 0;
    bdl_result ignored = BDL_OK;
    close_series(o, &ignored); // a run that never stepped: nothing to keep of them
    free(o->species_row);
    free(o->profile_row);
    bdl_pvd_destroy(o->pvd);
    bdl_pvd_destroy(o->gas_pvd);
    bdl_fields_free(&o->fields);
    return failed;
}
