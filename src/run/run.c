// The headless run driver: validation, output folder, solver thread, progress, clean stops.
#define _POSIX_C_SOURCE 200809L
#include "run/run.h"

#include <math.h>
#include <omp.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cfd/gas.h"
#include "core/log.h"
#include "core/timer.h"
#include "dia/dia_run.h"
#include "core/file.h"
#include "output/capture.h"
#include "output/checkpoint.h"
#include "io/csv.h"
#include "io/vtk.h"
#include "render/frames.h"
#include "output/diagnostics.h"
#include "output/granular_out.h"
#include "run/guards.h"
#include "run/loop.h"

static volatile sig_atomic_t stop_requested = 0;

void bdl_run_request_stop(void) { stop_requested = 1; }

static void on_sigint(int sig)
{
    (void)sig;
    stop_requested = 1;
}

bdl_run_def bdl_default_run_def(void)
{
    bdl_run_def d;
    memset(&d, 0, sizeof d);
    d.until = -1.0;
    d.progress = 1;
    return d;
}

/// Everything the solver thread's per-step callback needs.
typedef struct run_state {
    const char *out;
    bdl_world *world;
    bdl_csv *csv;
    bdl_csv *species_csv; ///< species.csv, with two or more species only
    double *species_row;
    bdl_csv *profile_csv; ///< profile.csv, with a gas only
    double *profile_row;
    bdl_pvd *pvd;
    bdl_pvd *gas_pvd; ///< gas fields, with [gas] only
    bdl_guard_state guard;
    double energy0;
    double start_wall;
    double next_diag, next_vtk, next_checkpoint, next_contacts;
    long vtk_index;
    double next_frame;
    long frame_index;
    bdl_frames *frames; ///< NULL: no frames
    char failure[1024];
    // The errors of the last diagnostics, for the progress line (written by the solver thread).
    _Atomic double energy_balance, energy_in, weight_ratio, gas_mass, momentum;
    _Atomic long particles_out;
    bdl_dia_run *dia; ///< synthetic cameras ([camera NAME]); NULL without
    _Atomic int measured;
} run_state;

static void path_join(char *out, size_t len, const char *a, const char *b)
{
    snprintf(out, len, "%s/%s", a, b);
}

/// The gas fields in the cells: voidage, pressure, velocity (face values averaged to the centre).
static bdl_result write_gas_vtk(run_state *rs)
{
    const bdl_gas *gas = rs->world->gas;
    const bdl_grid *g = &gas->grid;
    long cells = (long)g->n[0] * g->n[1] * g->n[2];
    double *eps = malloc((size_t)cells * sizeof(double)),
           *p = malloc((size_t)cells * sizeof(double));
    double *u = malloc((size_t)cells * 3 * sizeof(double));
    bdl_result r = BDL_ERR_NOMEM;
    if (eps && p && u) {
        long c = 0;
        for (int k = 0; k < g->n[2]; ++k)
            for (int j = 0; j < g->n[1]; ++j)
                for (int i = 0; i < g->n[0]; ++i, ++c) {
                    long idx = bdl_grid_index(g, i, j, k);
                    eps[c] = gas->eps[idx];
                    p[c] = gas->p[idx];
                    for (int a = 0; a < 3; ++a)
                        u[3 * c + a] = bdl_gas_cell_velocity(gas, a, i, j, k);
                }
        bdl_vtk_array arrays[] = {{"voidage", BDL_VTK_FLOAT64, 1, eps},
                                  {"pressure", BDL_VTK_FLOAT64, 1, p},
                                  {"gas_velocity", BDL_VTK_FLOAT64, 3, u}};
        char rel[64], path[1200];
        snprintf(rel, sizeof rel, "vtk/gas_%06ld.vti", rs->vtk_index);
        path_join(path, sizeof path, rs->out, rel);
        double origin[3] = {g->origin[0], g->origin[1], g->origin[2]};
        double spacing[3] = {g->h[0], g->h[1], g->h[2]};
        r = bdl_vti_write(path, g->n, origin, spacing, arrays, 3);
        if (r == BDL_OK && rs->gas_pvd)
            r = bdl_pvd_add(rs->gas_pvd, rs->world->time, rel);
    }
    free(eps);
    free(p);
    free(u);
    return r;
}

static bdl_result write_vtk(run_state *rs)
{
    const bdl_particles *p = &rs->world->particles;
    long n = p->count;
    double *radius = p->radius;
    int32_t *id = malloc((size_t)(n > 0 ? n : 1) * sizeof(int32_t));
    int32_t *coord = malloc((size_t)(n > 0 ? n : 1) * sizeof(int32_t));
    if (!id || !coord) {
        free(id);
        free(coord);
        return BDL_ERR_NOMEM;
    }
    for (long i = 0; i < n; ++i) {
        id[i] = (int32_t)p->id[i];
        coord[i] = rs->world->coordination[i];
    }
    bdl_vtk_array arrays[] = {
        {"radius", BDL_VTK_FLOAT64, 1, radius},    {"velocity", BDL_VTK_FLOAT64, 3, p->vel},
        {"omega", BDL_VTK_FLOAT64, 3, p->omega},   {"id", BDL_VTK_INT32, 1, id},
        {"species", BDL_VTK_INT32, 1, p->species}, {"coordination", BDL_VTK_INT32, 1, coord},
    };
    char rel[64], path[1200];
    snprintf(rel, sizeof rel, "vtk/particles_%06ld.vtp", rs->vtk_index);
    path_join(path, sizeof path, rs->out, rel);
    bdl_result r = bdl_vtp_write(path, n, p->pos, arrays, (int)(sizeof arrays / sizeof arrays[0]));
    free(id);
    free(coord);
    if (r == BDL_OK)
        r = bdl_pvd_add(rs->pvd, rs->world->time, rel);
    if (r == BDL_OK && rs->world->gas)
        r = write_gas_vtk(rs);
    rs->vtk_index++;
    return r;
}

static bdl_result write_checkpoint(run_state *rs)
{
    char path[1200];
    path_join(path, sizeof path, rs->out, "checkpoint/state.bdlckpt");
    bdl_result r = bdl_checkpoint_save(rs->world, path);
    if (r != BDL_OK)
        bdl_error("could not write checkpoint %s", path);
    return r;
}

static bdl_result write_diagnostics(run_state *rs, bdl_diagnostics *d)
{
    double row[32];
    d->wall_seconds = bdl_wall_seconds() - rs->start_wall;
    bdl_diagnostics_row(d, row);
    bdl_result r = bdl_csv_row(rs->csv, row);
    if (r == BDL_OK && rs->species_csv) {
        bdl_species_row(rs->world, rs->species_row);
        r = bdl_csv_row(rs->species_csv, rs->species_row);
    }
    if (r == BDL_OK && rs->profile_csv) {
        bdl_profile_row(rs->world, rs->profile_row);
        r = bdl_csv_row(rs->profile_csv, rs->profile_row);
    }
    return r;
}

static bdl_result write_contacts(run_state *rs)
{
    char rel[64], path[1200];
    const bdl_world *w = rs->world;
    snprintf(rel, sizeof rel, "contacts/contacts_%06ld.csv",
             lround(w->time / w->scene.output.contacts_interval));
    path_join(path, sizeof path, rs->out, rel);
    bdl_result r = bdl_contacts_write(w, path);
    if (r != BDL_OK)
        bdl_error("could not write %s", path);
    return r;
}

bdl_result bdl_run_frame(bdl_frames *frames, const bdl_world *w, long index)
{
    bdl_snapshot *slot = bdl_frames_slot(frames);
    return bdl_frames_commit(frames, index, slot && bdl_capture(slot, w));
}

static bdl_result submit_frame(run_state *rs)
{
    return bdl_run_frame(rs->frames, rs->world, rs->frame_index++);
}

/// The first multiple of `interval` after t: a resumed run keeps the first run's output times.
static double next_multiple(double t, double interval)
{
    return interval > 0.0 ? (floor(t / interval + 1e-9) + 1.0) * interval : INFINITY;
}

/// Times are due when the step lands within half a step of them.
static int due(const bdl_world *w, double t) { return w->time >= t - 0.5 * w->dt; }

static bdl_result on_step(void *user, bdl_world *w)
{
    run_state *rs = user;
    const bdl_scene *s = &w->scene;
    int diag = due(w, rs->next_diag);
    int check = w->step % s->guards.check_interval == 0;
    if (diag || check) {
        bdl_diagnostics d;
        bdl_diagnostics_compute(w, rs->energy0, &d);
        atomic_store(&rs->energy_balance, d.energy_balance);
        atomic_store(&rs->energy_in, d.wall_work + d.gas_work + w->inserted_energy);
        atomic_store(&rs->weight_ratio, d.weight_ratio);
        atomic_store(&rs->gas_mass, d.gas_volume_imbalance);
        atomic_store(&rs->momentum, d.momentum_imbalance);
        atomic_store(&rs->particles_out, d.particles_out);
        atomic_store(&rs->measured, 1);
        if (check) {
            bdl_result r = bdl_guards_check(w, &rs->guard, &d, rs->failure, sizeof rs->failure);
            if (r != BDL_OK)
                return r;
        }
        if (diag) {
            bdl_result r = write_diagnostics(rs, &d);
            if (r != BDL_OK)
                return r;
            while (due(w, rs->next_diag))
                rs->next_diag += s->output.diagnostics_interval;
        }
    }
    if (s->output.vtk_interval > 0.0 && due(w, rs->next_vtk)) {
        bdl_result r = write_vtk(rs);
        if (r != BDL_OK)
            return r;
        while (due(w, rs->next_vtk))
            rs->next_vtk += s->output.vtk_interval;
    }
    if (s->output.contacts_interval > 0.0 && due(w, rs->next_contacts)) {
        bdl_result r = write_contacts(rs);
        if (r != BDL_OK)
            return r;
        while (due(w, rs->next_contacts))
            rs->next_contacts += s->output.contacts_interval;
    }
    if (rs->frames && due(w, rs->next_frame)) {
        bdl_result r = submit_frame(rs);
        if (r != BDL_OK)
            return r;
        while (due(w, rs->next_frame))
            rs->next_frame += s->output.frame_interval;
    }
    if (rs->dia) {
        const bdl_particle_view view = bdl_capture_view(w);
        bdl_result r = bdl_dia_run_step(rs->dia, &view);
        if (r != BDL_OK) {
            snprintf(rs->failure, sizeof rs->failure, "synthetic camera images: %s",
                     bdl_result_text(r));
            return r;
        }
    }
    if (s->output.checkpoint_interval > 0.0 && due(w, rs->next_checkpoint)) {
        bdl_result r = write_checkpoint(rs);
        if (r != BDL_OK)
            return r;
        while (due(w, rs->next_checkpoint))
            rs->next_checkpoint += s->output.checkpoint_interval;
    }
    if (stop_requested)
        return BDL_ERR_INTERRUPTED;
    return BDL_OK;
}

static void log_setup(const bdl_world *w, const bdl_run_def *def, int threads, const char *out)
{
    const bdl_scene *s = &w->scene;
    bdl_info("bedlam %s", BDL_VERSION);
    bdl_info("scene: %s", s->path);
    for (int k = 0; k < def->override_count; ++k)
        bdl_info("override: %s", def->overrides[k]);
    bdl_info("output: %s", out);
    bdl_info("threads: %d", threads);
    char gas[256];
    bdl_world_gas_describe(w, gas, sizeof gas);
    bdl_info("modules: dem (%s normal law%s, %s%s), walls: %d, gas: %s",
             w->hertz ? "Hertz" : "linear",
             w->hertz ? (s->damping == BDL_DAMPING_EXACT ? ", exact restitution damping"
                                                         : ", closed-form damping")
                      : "",
             w->friction ? "tangential history + Coulomb friction"
                         : "frictionless, no tangential history",
             w->rolling ? ", rolling resistance" : "", s->wall_count, gas);
    bdl_info("particles: %ld, species: %d", w->particles.count, s->species_count);
    for (int k = 0; k < s->species_count; ++k) {
        const bdl_species_def *sp = &s->species[k];
        const bdl_contact_params *cp = &w->pair_params[k * s->species_count + k];
        bdl_info("species %s: d = %g m, rho = %g kg/m^3, e = %g, mu = %g, mu_r = %g, %s = %g",
                 sp->name, sp->diameter, sp->density, cp->restitution, cp->friction,
                 cp->rolling_friction, w->hertz ? "damping c" : "damping ratio", cp->damping);
    }
    bdl_info("dt = %g s, smallest contact time = %g s (dt = t_c / %.1f), end time = %g s", w->dt,
             w->contact_time, 1.0 / w->contact_time_dt_ratio, s->end_time);
    bdl_info("limits: dt_refuse = %g t_c, dt_warn = %g t_c, max_overlap = %g r, energy_growth = %g",
             s->guards.dt_refuse, s->guards.dt_warn, s->guards.max_overlap,
             s->guards.energy_growth);
}

static void format_hms(double s, char *out, size_t len)
{
    if (!isfinite(s) || s < 0) {
        snprintf(out, len, "--:--:--");
        return;
    }
    long t = (long)(s + 0.5);
    snprintf(out, len, "%02ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
}

/// The run's own errors beside its speed: the energy balance (energy now, less the energy at the
/// start and the work put in by walls, gas and insertion: zero for elastic contacts, the
/// dissipated energy otherwise) and, with a gas, the pressure drop against the bed's weight, the
/// worst cell's gas volume imbalance and the interphase momentum imbalance.
static void error_summary(run_state *rs, int gas, char *out, size_t len)
{
    out[0] = 0;
    if (!atomic_load(&rs->measured))
        return;
    int k = snprintf(out, len, "  energy balance %.2e J (work in %.2e J)",
                     atomic_load(&rs->energy_balance), atomic_load(&rs->energy_in));
    if (gas && k > 0 && (size_t)k < len)
        k += snprintf(out + k, len - (size_t)k, "  dp/weight %.3f  gas volume %.1e  momentum %.1e",
                      atomic_load(&rs->weight_ratio), atomic_load(&rs->gas_mass),
                      atomic_load(&rs->momentum));
    long leaving = atomic_load(&rs->particles_out);
    if (leaving > 0 && k > 0 && (size_t)k < len) // through gas outlets: counted, not lost
        snprintf(out + k, len - (size_t)k, "  out %ld", leaving);
}

static void progress_line(bdl_loop *loop, run_state *rs, double end_time, double t0, int tty,
                          double *last_t, long *last_step, double *last_wall)
{
    const double start_wall = rs->start_wall;
    double t, now = bdl_wall_seconds();
    long step, particles;
    int finished;
    bdl_loop_progress(loop, &t, &step, &particles, &finished);
    double dw = now - *last_wall;
    double rate = dw > 0 ? (double)(step - *last_step) * (double)particles / dw : 0.0;
    double speed = dw > 0 ? (t - *last_t) / dw : 0.0;
    double elapsed = now - start_wall;
    double eta = t > t0 ? (end_time - t) * elapsed / (t - t0) : NAN;
    char e1[16], e2[16], errors[192];
    format_hms(elapsed, e1, sizeof e1);
    format_hms(eta, e2, sizeof e2);
    error_summary(rs, rs->world->gas != NULL, errors, sizeof errors);
    fprintf(stderr,
            "%st = %.4g / %.4g s  step %ld  %ld particles  %.3g particle-steps/s  %.3gx real time  "
            "elapsed %s  ETA %s%s%s",
            tty ? "\r" : "", t, end_time, step, particles, rate, speed, e1, e2, errors,
            tty ? "\033[K" : "\n");
    fflush(stderr);
    *last_t = t;
    *last_step = step;
    *last_wall = now;
}

static int resolve_checkpoint(const char *resume, char *out, size_t len)
{
    struct stat st;
    if (stat(resume, &st) == 0 && S_ISDIR(st.st_mode)) {
        snprintf(out, len, "%s/checkpoint/state.bdlckpt", resume);
        return 1;
    }
    snprintf(out, len, "%s", resume);
    return 0;
}

static void default_out_dir(const char *scene_path, char *out, size_t len)
{
    const char *base = strrchr(scene_path, '/');
    base = base ? base + 1 : scene_path;
    char stem[256];
    snprintf(stem, sizeof stem, "%s", base);
    char *dot = strrchr(stem, '.');
    if (dot)
        *dot = '\0';
    snprintf(out, len, "runs/%s", stem);
}

static int finish(int code, bdl_world *w, FILE *log)
{
    bdl_world_destroy(w);
    if (log) {
        bdl_log_set_file(NULL);
        fclose(log);
    }
    return code;
}

int bdl_run(const bdl_run_def *def)
{
    bdl_scene *scene = calloc(1, sizeof *scene);
    bdl_scene_error err;
    if (!scene)
        return 1;
    if (bdl_scene_load(def->scene_path, def->overrides, def->override_count, scene, &err) !=
        BDL_OK) {
        fprintf(stderr, "error: %s\n", err.message);
        free(scene);
        return 2;
    }
    if (def->until > 0.0)
        scene->end_time = def->until;
    int threads = def->threads > 0 ? def->threads : scene->threads;
    if (threads > 0)
        omp_set_num_threads(threads);
    threads = omp_get_max_threads();
    // Only the solver thread runs a team (it is told `threads` below). The main thread builds the
    // world and then waits on it; a team of its own would leave an idle worker behind, and with
    // more workers than cores libgomp stops spin-waiting, so that every parallel region of the
    // solver sleeps and wakes through the kernel: 2.3x slower on two cores (fluidized_bed.ini).
    omp_set_num_threads(1);

    char out[1024], why[512], ckpt[1200];
    int resume_dir = def->resume ? resolve_checkpoint(def->resume, ckpt, sizeof ckpt) : 0;
    if (def->out_dir)
        snprintf(out, sizeof out, "%s", def->out_dir);
    else if (resume_dir)
        snprintf(out, sizeof out, "%s", def->resume);
    else
        default_out_dir(def->scene_path, out, sizeof out);
    char sub[1200];
    if (bdl_check_writable_dir(out, why, sizeof why) != BDL_OK) {
        fprintf(stderr, "error: output folder '%s' is not writable: %s\n", out, why);
        free(scene);
        return 2;
    }
    path_join(sub, sizeof sub, out, "vtk");
    bdl_mkdir_p(sub);
    if (scene->output.frame_interval > 0.0) {
        path_join(sub, sizeof sub, out, "frames");
        bdl_mkdir_p(sub);
    }
    path_join(sub, sizeof sub, out, "checkpoint");
    bdl_mkdir_p(sub);
    path_join(sub, sizeof sub, out, "run.log");
    FILE *log = fopen(sub, def->resume ? "a" : "w");
    if (log) {
        setvbuf(log, NULL, _IOLBF, 0);
        bdl_log_set_file(log);
    }

    bdl_world *world = NULL;
    bdl_result r = bdl_world_create(scene, &world, &err);
    free(scene);
    if (r != BDL_OK) {
        if (r == BDL_ERR_SCENE)
            bdl_error("%s", err.message);
        else
            bdl_error("cannot build the world: %s", bdl_result_text(r));
        return finish(r == BDL_ERR_SCENE ? 2 : 1, NULL, log);
    }
    char message[1024], warning[1024];
    if (bdl_guards_check_dt(world, message, sizeof message, warning, sizeof warning) != BDL_OK) {
        bdl_error("%s", message);
        return finish(2, world, log);
    }
    if (warning[0])
        bdl_warn("%s", warning);
    if (def->resume) {
        if (bdl_checkpoint_load(world, ckpt, why, sizeof why) != BDL_OK) {
            bdl_error("%s", why);
            return finish(2, world, log);
        }
        bdl_info("resumed from %s at t = %.17g s, step %ld", ckpt, world->time, world->step);
    }
    log_setup(world, def, threads, out);

    run_state rs;
    memset(&rs, 0, sizeof rs);
    rs.out = out;
    rs.world = world;
    rs.start_wall = bdl_wall_seconds();
    bdl_diagnostics d0;
    if (!def->resume) {
        bdl_diagnostics_compute(world, 0.0, &d0);
        world->energy0 = bdl_diagnostics_total_energy(&d0);
    }
    rs.energy0 = world->energy0;
    bdl_diagnostics_compute(world, rs.energy0, &d0);
    bdl_guards_init(&rs.guard, &d0);
    const bdl_output_def *o = &world->scene.output;
    path_join(sub, sizeof sub, out, "diagnostics.csv");
    if (def->resume)
        bdl_csv_truncate_after(sub, world->time);
    rs.csv = bdl_csv_open(sub, bdl_diagnostics_columns, bdl_diagnostics_column_count,
                          def->resume != NULL);
    char species_names[BDL_SPECIES_COLUMNS_MAX][BDL_SPECIES_COLUMN_LEN];
    const int species_columns = bdl_species_columns(world, species_names);
    if (species_columns > 0) {
        const char *names[BDL_SPECIES_COLUMNS_MAX];
        for (int c = 0; c < species_columns; ++c)
            names[c] = species_names[c];
        path_join(sub, sizeof sub, out, "species.csv");
        if (def->resume)
            bdl_csv_truncate_after(sub, world->time);
        rs.species_csv = bdl_csv_open(sub, names, species_columns, def->resume != NULL);
        rs.species_row = malloc(BDL_SPECIES_COLUMNS_MAX * sizeof(double));
        if (!rs.species_csv || !rs.species_row) {
            bdl_error("cannot create output files in '%s'", out);
            return finish(2, world, log);
        }
    }
    const int profile_columns = bdl_profile_columns(world, NULL);
    if (profile_columns > 0) {
        char(*pnames)[BDL_SPECIES_COLUMN_LEN] = malloc((size_t)profile_columns * sizeof *pnames);
        const char **names = malloc((size_t)profile_columns * sizeof *names);
        rs.profile_row = malloc((size_t)profile_columns * sizeof(double));
        if (pnames && names && rs.profile_row) {
            bdl_profile_columns(world, pnames);
            for (int c = 0; c < profile_columns; ++c)
                names[c] = pnames[c];
            path_join(sub, sizeof sub, out, "profile.csv");
            if (def->resume)
                bdl_csv_truncate_after(sub, world->time);
            rs.profile_csv = bdl_csv_open(sub, names, profile_columns, def->resume != NULL);
        }
        free(pnames);
        free(names);
        if (!rs.profile_csv) {
            bdl_error("cannot create output files in '%s'", out);
            return finish(2, world, log);
        }
    }
    if (o->contacts_interval > 0.0) {
        path_join(sub, sizeof sub, out, "contacts");
        if (bdl_mkdir_p(sub) != BDL_OK) {
            bdl_error("cannot create '%s'", sub);
            return finish(2, world, log);
        }
    }
    path_join(sub, sizeof sub, out, "particles.pvd");
    rs.pvd = bdl_pvd_create(sub);
    if (world->gas && o->vtk_interval > 0.0) {
        path_join(sub, sizeof sub, out, "gas.pvd");
        rs.gas_pvd = bdl_pvd_create(sub);
    }
    if (!rs.csv || !rs.pvd) {
        bdl_error("cannot create output files in '%s'", out);
        return finish(2, world, log);
    }
    double t0 = world->time;
    rs.next_diag = t0;
    rs.next_vtk = t0;
    rs.next_checkpoint = next_multiple(t0, o->checkpoint_interval);
    rs.next_contacts = next_multiple(t0, o->contacts_interval);
    if (def->resume) {
        // The rows and frames at t0 were written by the first run already.
        rs.next_diag = next_multiple(t0, o->diagnostics_interval);
        if (o->vtk_interval > 0.0) {
            long k = (long)floor(t0 / o->vtk_interval + 1e-9);
            for (long i = 0; i <= k; ++i) {
                char rel[64];
                snprintf(rel, sizeof rel, "vtk/particles_%06ld.vtp", i);
                bdl_pvd_add(rs.pvd, i * o->vtk_interval, rel);
            }
            rs.vtk_index = k + 1;
            rs.next_vtk = (k + 1) * o->vtk_interval;
        }
    }
    if (!def->resume) {
        bdl_result ir = write_diagnostics(&rs, &d0);
        if (ir == BDL_OK && o->vtk_interval > 0.0)
            ir = write_vtk(&rs);
        if (ir == BDL_OK && o->contacts_interval > 0.0)
            ir = write_contacts(&rs);
        rs.next_diag = t0 + o->diagnostics_interval;
        rs.next_vtk = t0 + o->vtk_interval;
        rs.next_contacts = t0 + o->contacts_interval;
        if (ir != BDL_OK) {
            bdl_error("cannot write outputs in '%s'", out);
            return finish(1, world, log);
        }
    }

    if (o->frame_interval > 0.0) {
        char gl_why[1024];
        path_join(sub, sizeof sub, out, "frames");
        bdl_frames_def fd = {.scene = &world->scene, .folder = sub, .backend = def->gl_backend};
        if (bdl_frames_open(&fd, &rs.frames, gl_why, sizeof gl_why) != BDL_OK) {
            bdl_error("cannot draw frames: %s", gl_why);
            return finish(1, world, log);
        }
        // Frame k is at k frame_interval: a resumed run continues the numbering.
        long k = (long)ceil(t0 / o->frame_interval - 1e-9);
        rs.frame_index = k;
        rs.next_frame = k * o->frame_interval;
        if (def->resume && due(world, rs.next_frame)) { // written by the first run
            rs.frame_index++;
            rs.next_frame += o->frame_interval;
        }
        if (due(world, rs.next_frame)) {
            submit_frame(&rs);
            rs.next_frame += o->frame_interval;
        }
        bdl_info("frames: %dx%d every %g s in %s", o->frame_width, o->frame_height,
                 o->frame_interval, sub);
    }

    if (world->scene.dia_count > 0) {
        char dia_why[1024] = "";
        const bdl_particle_view now = bdl_capture_view(world);
        if (bdl_dia_run_open(&world->scene, &now, out, def->resume != NULL, &rs.dia, dia_why,
                             sizeof dia_why) != BDL_OK) {
            bdl_error("synthetic cameras: %s", dia_why);
            return finish(2, world, log);
        }
        bdl_dia_run_step(rs.dia, &now); // an image due at the start
        for (int k = 0; k < world->scene.dia_count; ++k) {
            const bdl_dia_scene_def *dd = &world->scene.dias[k];
            bdl_info("camera %s: %dx%d %s images every %g s%s in %s/dia/%s", dd->name, dd->width,
                     dd->height, dd->lighting ? "back-lit" : "front-lit", dd->interval,
                     dd->pair_dt > 0.0 ? " (PIV pairs)" : "", out, dd->name);
        }
    }

    stop_requested = 0;
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_sigint;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);

    bdl_loop_def ld = bdl_default_loop_def();
    ld.world = world;
    ld.end_time = world->scene.end_time;
    ld.max_steps = def->max_steps;
    ld.threads = threads;
    ld.on_step = on_step;
    ld.user = &rs;
    bdl_loop *loop = bdl_loop_start(&ld);
    if (!loop) {
        bdl_error("cannot start the solver thread");
        return finish(1, world, log);
    }
    int tty = def->progress && isatty(STDERR_FILENO);
    double last_t = t0, last_wall = rs.start_wall, last_print = rs.start_wall;
    long last_step = world->step;
    double interval = world->scene.output.progress_interval;
    for (;;) {
        double t;
        long step, particles;
        int finished;
        bdl_loop_progress(loop, &t, &step, &particles, &finished);
        if (finished)
            break;
        if (rs.frames)
            bdl_frames_pump(rs.frames, 0.02);
        else
            nanosleep(&(struct timespec){0, 20000000L}, NULL);
        double now = bdl_wall_seconds();
        if (def->progress && now - last_print >= (tty ? interval : 10.0 * interval)) {
            progress_line(loop, &rs, ld.end_time, t0, tty, &last_t, &last_step, &last_wall);
            last_print = now;
        }
    }
    r = bdl_loop_join(loop);
    bdl_loop_destroy(loop);
    if (rs.frames) {
        long written = 0;
        bdl_result fr = bdl_frames_close(rs.frames, &written);
        bdl_info("frames: %ld written", written);
        if (fr != BDL_OK && r == BDL_OK) {
            bdl_error("frames: %s", bdl_result_text(fr));
            r = fr;
        }
    }
    if (rs.dia) {
        bdl_info("synthetic cameras: %ld images written", bdl_dia_run_count(rs.dia));
        bdl_dia_run_close(rs.dia);
        rs.dia = NULL;
    }
    if (tty)
        fputc('\n', stderr);
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);

    // Final row, checkpoint and summary, whatever the outcome.
    bdl_diagnostics d;
    bdl_diagnostics_compute(world, rs.energy0, &d);
    if (r == BDL_OK && !due(world, rs.next_diag - o->diagnostics_interval))
        write_diagnostics(&rs, &d);
    bdl_csv_close(rs.csv);
    if (rs.species_csv)
        bdl_csv_close(rs.species_csv);
    free(rs.species_row);
    if (rs.profile_csv)
        bdl_csv_close(rs.profile_csv);
    free(rs.profile_row);
    bdl_pvd_destroy(rs.pvd);
    bdl_pvd_destroy(rs.gas_pvd);
    bdl_result cr = write_checkpoint(&rs);
    double wall = bdl_wall_seconds() - rs.start_wall;
    int code = 0;
    if (r == BDL_ERR_UNSTABLE) {
        bdl_error("run stopped: %s", rs.failure);
        bdl_error("a checkpoint of the last state is in %s/checkpoint/", out);
        code = 1;
    } else if (r == BDL_ERR_INTERRUPTED) {
        bdl_warn(
            "interrupted at t = %g s (step %ld); state saved in %s/checkpoint/ — continue with "
            "'bedlam run %s --resume %s'",
            world->time, world->step, out, def->scene_path, out);
        code = 1;
    } else if (r != BDL_OK) {
        bdl_error("run failed: %s", bdl_result_text(r));
        code = 1;
    }
    bdl_info("finished at t = %.6g s, step %ld, %ld particles, %.3f s wall, checkpoint %s",
             world->time, world->step, world->particles.count, wall,
             cr == BDL_OK ? "written" : "FAILED");
    if (code == 0 && def->progress)
        fprintf(stderr, "done: t = %g s, %ld steps in %.2f s; outputs in %s\n", world->time,
                world->step, wall, out);
    return finish(code, world, log);
}
