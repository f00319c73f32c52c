// bedlam — the files a run writes while it goes: diagnostics and series, VTK, contact files,
// frames, synthetic camera images and checkpoints, each at its times.
#include "run/outputs.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/file.h"
#include "core/log.h"
#include "core/timer.h"
#include "output/capture.h"
#include "output/checkpoint.h"
#include "output/granular_out.h"
#include "output/rod_angles_out.h"
#include "output/world_vtk.h"

static void path_join(char *out, size_t len, const char *a, const char *b)
{
    snprintf(out, len, "%s/%s", a, b);
}

/// The first multiple of `interval` after t: a resumed run keeps the first run's output times.
static double next_multiple(double t, double interval)
{
    return interval > 0.0 ? (floor(t / interval + 1e-9) + 1.0) * interval : INFINITY;
}

/// Times are due when the step lands within half a step of them.
static int due(const bdl_world *w, double t) { return w->time >= t - 0.5 * w->dt; }

/// Moves `next` past the current time in steps of `interval`.
static void advance(const bdl_world *w, double *next, double interval)
{
    while (due(w, *next))
        *next += interval;
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
    if (r == BDL_OK)
        r = bdl_pvd_add(o->pvd, w->time, rel);
    if (r == BDL_OK && w->gas) {
        snprintf(rel, sizeof rel, "vtk/gas_%06ld.vti", o->vtk_index);
        path_join(path, sizeof path, o->out, rel);
        r = bdl_world_gas_vti_write(w, path);
        if (r == BDL_OK && o->gas_pvd)
            r = bdl_pvd_add(o->gas_pvd, w->time, rel);
    }
    o->vtk_index++;
    return r;
}

static bdl_result write_checkpoint(bdl_run_outputs *o)
{
    char path[1200];
    path_join(path, sizeof path, o->out, "checkpoint/state.bdlckpt");
    bdl_result r = bdl_checkpoint_save(o->world, path);
    if (r != BDL_OK)
        bdl_error("could not write checkpoint %s", path);
    return r;
}

static bdl_result write_diagnostics(bdl_run_outputs *o, bdl_diagnostics *d)
{
    double row[32];
    d->wall_seconds = bdl_wall_seconds() - o->start_wall;
    bdl_diagnostics_row(d, row);
    bdl_result r = bdl_csv_row(o->csv, row);
    if (r == BDL_OK && o->species_csv) {
        bdl_species_row(o->world, o->species_row);
        r = bdl_csv_row(o->species_csv, o->species_row);
    }
    if (r == BDL_OK && o->profile_csv) {
        bdl_profile_row(o->world, o->profile_row);
        r = bdl_csv_row(o->profile_csv, o->profile_row);
    }
    return r;
}

static bdl_result write_orientation(bdl_run_outputs *o)
{
    double row[BDL_ROD_ANGLE_COLUMNS];
    bdl_rod_angle_row(o->world, row);
    return bdl_csv_row(o->orientation_csv, row);
}

static bdl_result write_contacts(bdl_run_outputs *o)
{
    char rel[64], path[1200];
    const bdl_world *w = o->world;
    snprintf(rel, sizeof rel, "contacts/contacts_%06ld.csv",
             lround(w->time / w->scene.output.contacts_interval));
    path_join(path, sizeof path, o->out, rel);
    bdl_result r = bdl_contacts_write(w, path);
    if (r != BDL_OK)
        bdl_error("could not write %s", path);
    return r;
}

static bdl_result write_frame(bdl_run_outputs *o)
{
    return bdl_run_frame(o->frames, o->world, o->frame_index++);
}

// ---------------------------------------------------------------------------------------------
// Opening.

/// A CSV file of the run: `count` columns named by `names` (NULL: none, nothing opened). A
/// resumed run drops the rows after the checkpoint's time and appends.
static bdl_result open_csv(const bdl_run_outputs *o, const char *file, const char *const *names,
                           int count, int resume, bdl_csv **csv)
{
    char path[1200];
    path_join(path, sizeof path, o->out, file);
    if (resume)
        bdl_csv_truncate_after(path, o->world->time);
    *csv = bdl_csv_open(path, names, count, resume);
    if (!*csv) {
        bdl_error("cannot create output files in '%s'", o->out);
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
    if (count > 0)
        r = open_csv(o, "species.csv", pointers, count, resume, &o->species_csv);
    count = bdl_profile_columns(o->world, NULL);
    if (r != BDL_OK || count == 0)
        return r;
    char(*profile)[BDL_SPECIES_COLUMN_LEN] = malloc((size_t)count * sizeof *profile);
    const char **profile_names = malloc((size_t)count * sizeof *profile_names);
    o->profile_row = malloc((size_t)count * sizeof(double));
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
    path_join(sub, sizeof sub, o->out, "particles.pvd");
    o->pvd = bdl_pvd_create(sub);
    if (w->gas && out->vtk_interval > 0.0) {
        path_join(sub, sizeof sub, o->out, "gas.pvd");
        o->gas_pvd = bdl_pvd_create(sub);
    }
    if (!o->pvd) {
        bdl_error("cannot create output files in '%s'", o->out);
        return BDL_ERR_OUTPUT_DIR;
    }
    return BDL_OK;
}

/// A new run writes the diagnostics row, the VTK files and the contact file of its start; a
/// resumed one finds them written and lists the VTK files it continues.
static bdl_result schedule(bdl_run_outputs *o, bdl_diagnostics *d0, int resume)
{
    const bdl_output_def *out = &o->world->scene.output;
    const double t0 = o->world->time;
    o->next_checkpoint = next_multiple(t0, out->checkpoint_interval);
    if (resume) {
        o->next_diag = next_multiple(t0, out->diagnostics_interval);
        o->next_contacts = next_multiple(t0, out->contacts_interval);
        o->next_orientation = next_multiple(t0, out->orientation_interval);
        o->next_vtk = t0;
        if (out->vtk_interval > 0.0) {
            long k = (long)floor(t0 / out->vtk_interval + 1e-9);
            for (long i = 0; i <= k; ++i) {
                char rel[64];
                snprintf(rel, sizeof rel, "vtk/particles_%06ld.vtp", i);
                bdl_pvd_add(o->pvd, i * out->vtk_interval, rel);
            }
            o->vtk_index = k + 1;
            o->next_vtk = (k + 1) * out->vtk_interval;
        }
        return BDL_OK;
    }
    bdl_result r = write_diagnostics(o, d0);
    if (r == BDL_OK && out->vtk_interval > 0.0)
        r = write_vtk(o);
    if (r == BDL_OK && out->contacts_interval > 0.0)
        r = write_contacts(o);
    if (r == BDL_OK && o->orientation_csv)
        r = write_orientation(o);
    o->next_diag = t0 + out->diagnostics_interval;
    o->next_orientation = t0 + out->orientation_interval;
    o->next_vtk = t0 + out->vtk_interval;
    o->next_contacts = t0 + out->contacts_interval;
    if (r != BDL_OK)
        bdl_error("cannot write outputs in '%s'", o->out);
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
    long k = (long)ceil(w->time / out->frame_interval - 1e-9);
    o->frame_index = k;
    o->next_frame = k * out->frame_interval;
    if (resume && due(w, o->next_frame)) { // written by the first run
        o->frame_index++;
        o->next_frame += out->frame_interval;
    }
    if (due(w, o->next_frame)) {
        write_frame(o);
        o->next_frame += out->frame_interval;
    }
    bdl_info("frames: %dx%d every %g s in %s", out->frame_width, out->frame_height,
             out->frame_interval, folder);
    return BDL_OK;
}

/// The synthetic cameras, and an image due at the start.
static bdl_result open_cameras(bdl_run_outputs *o, int resume)
{
    const bdl_scene *s = &o->world->scene;
    char why[1024] = "";
    const bdl_particle_view now = bdl_capture_view(o->world);
    bdl_result r = bdl_dia_run_open(s, &now, o->out, resume, &o->dia, why, sizeof why);
    if (r != BDL_OK) {
        bdl_error("synthetic cameras: %s", why);
        return r;
    }
    bdl_dia_run_step(o->dia, &now);
    for (int k = 0; k < s->dia_count; ++k) {
        const bdl_dia_scene_def *dd = &s->dias[k];
        bdl_info("camera %s: %dx%d %s images every %g s%s in %s/dia/%s", dd->name, dd->width,
                 dd->height, bdl_dia_lighting_labels[dd->lighting], dd->interval,
                 dd->pair_dt > 0.0 ? " (PIV pairs)" : "", o->out, dd->name);
    }
    return BDL_OK;
}

bdl_result bdl_run_outputs_open(bdl_run_outputs *o, bdl_world *w, const char *out, int resume,
                                int gl_backend)
{
    o->out = out;
    o->world = w;
    o->start_wall = bdl_wall_seconds();
    bdl_diagnostics d0;
    if (!resume) {
        bdl_diagnostics_compute(w, 0.0, &d0);
        w->energy0 = bdl_diagnostics_total_energy(&d0);
    }
    o->energy0 = w->energy0;
    bdl_diagnostics_compute(w, o->energy0, &d0);
    bdl_guards_init(&o->guard, &d0);
    bdl_result r = open_files(o, resume);
    if (r == BDL_OK)
        r = schedule(o, &d0, resume);
    if (r == BDL_OK && w->scene.output.frame_interval > 0.0)
        r = open_frames(o, resume, gl_backend);
    if (r == BDL_OK && w->scene.dia_count > 0)
        r = open_cameras(o, resume);
    return r;
}

// ---------------------------------------------------------------------------------------------
// Each step.

/// Diagnostics, when a row or a guard check is due: the row, the checks, and the error figures
/// for the progress line.
static bdl_result diagnose(bdl_run_outputs *o, bdl_world *w)
{
    const bdl_scene *s = &w->scene;
    int row = due(w, o->next_diag);
    int check = w->step % s->guards.check_interval == 0;
    if (!row && !check)
        return BDL_OK;
    bdl_diagnostics d;
    bdl_diagnostics_compute(w, o->energy0, &d);
    atomic_store(&o->energy_balance, d.energy_balance);
    atomic_store(&o->energy_in, d.wall_work + d.gas_work + w->inserted_energy);
    atomic_store(&o->weight_ratio, d.weight_ratio);
    atomic_store(&o->gas_mass, d.gas_volume_imbalance);
    atomic_store(&o->momentum, d.momentum_imbalance);
    atomic_store(&o->particles_out, d.particles_out);
    atomic_store(&o->measured, 1);
    bdl_result r = BDL_OK;
    if (check)
        r = bdl_guards_check(w, &o->guard, &d, o->failure, sizeof o->failure);
    if (r == BDL_OK && row) {
        r = write_diagnostics(o, &d);
        advance(w, &o->next_diag, s->output.diagnostics_interval);
    }
    return r;
}

bdl_result bdl_run_outputs_step(void *user, bdl_world *w)
{
    bdl_run_outputs *o = user;
    const bdl_output_def *out = &w->scene.output;
    bdl_result r = diagnose(o, w);
    if (r == BDL_OK && out->vtk_interval > 0.0 && due(w, o->next_vtk)) {
        r = write_vtk(o);
        advance(w, &o->next_vtk, out->vtk_interval);
    }
    if (r == BDL_OK && out->contacts_interval > 0.0 && due(w, o->next_contacts)) {
        r = write_contacts(o);
        advance(w, &o->next_contacts, out->contacts_interval);
    }
    if (r == BDL_OK && o->orientation_csv && due(w, o->next_orientation)) {
        r = write_orientation(o);
        advance(w, &o->next_orientation, out->orientation_interval);
    }
    if (r == BDL_OK && o->frames && due(w, o->next_frame)) {
        r = write_frame(o);
        advance(w, &o->next_frame, out->frame_interval);
    }
    if (r == BDL_OK && o->dia) {
        const bdl_particle_view view = bdl_capture_view(w);
        r = bdl_dia_run_step(o->dia, &view);
        if (r != BDL_OK)
            snprintf(o->failure, sizeof o->failure, "synthetic camera images: %s",
                     bdl_result_text(r));
    }
    if (r == BDL_OK && out->checkpoint_interval > 0.0 && due(w, o->next_checkpoint)) {
        r = write_checkpoint(o);
        advance(w, &o->next_checkpoint, out->checkpoint_interval);
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

bdl_result bdl_run_outputs_close(bdl_run_outputs *o, int solved, bdl_result *r)
{
    if (o->frames) {
        long written = 0;
        bdl_result fr = bdl_frames_close(o->frames, &written);
        o->frames = NULL;
        bdl_info("frames: %ld written", written);
        if (fr != BDL_OK && *r == BDL_OK) {
            bdl_error("frames: %s", bdl_result_text(fr));
            *r = fr;
        }
    }
    if (o->dia) {
        bdl_info("synthetic cameras: %ld images written", bdl_dia_run_count(o->dia));
        bdl_dia_run_close(o->dia);
        o->dia = NULL;
    }
    bdl_result cr = BDL_OK;
    if (solved) { // the last row (after a clean end) and the checkpoint, whatever the outcome
        const double interval = o->world->scene.output.diagnostics_interval;
        bdl_diagnostics d;
        bdl_diagnostics_compute(o->world, o->energy0, &d);
        if (*r == BDL_OK && !due(o->world, o->next_diag - interval))
            write_diagnostics(o, &d);
        cr = write_checkpoint(o);
    }
    bdl_csv_close(o->csv);
    bdl_csv_close(o->species_csv);
    bdl_csv_close(o->profile_csv);
    bdl_csv_close(o->orientation_csv);
    free(o->species_row);
    free(o->profile_row);
    bdl_pvd_destroy(o->pvd);
    bdl_pvd_destroy(o->gas_pvd);
    return cr;
}
