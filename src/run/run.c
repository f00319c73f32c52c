// bedlam — the headless run driver: scene, output folder, world, outputs, solver thread, close.
#define _POSIX_C_SOURCE 200809L
#include "run/run.h"

#include <errno.h>
#include <math.h>
#include <omp.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "core/comm.h"
#include "core/file.h"
#include "core/log.h"
#include "core/timer.h"
#include "output/capture.h"
#include "dist/exchange.h"
#include "output/checkpoint.h"
#include "run/guards.h"
#include "run/loop.h"
#include "run/outputs.h"
#include "solids/phase.h"

/// One run as it goes through its phases.
typedef struct run {
    const bdl_run_def *def;
    bdl_scene *scene;   ///< read from the file; freed once the world holds a copy
    int threads;        ///< solver threads
    FILE *log;          ///< run.log
    bdl_world *world;   ///< what the outputs read: under MPI on the first rank a whole mirror
    bdl_world *divided; ///< under MPI (more than one rank): this rank's part, which steps
    int rank, ranks;    ///< MPI (0 and 1 in one process)
    volatile sig_atomic_t stop_now; ///< MPI: a stop told to any rank (the outputs read it)
    atomic_long particles;          ///< MPI: every rank's particles at the last gather
    bdl_run_outputs outputs;
} run;

/// MPI: the worst of every rank's result (each rank's own in one process).
static bdl_result agree(const run *r, bdl_result res)
{
    return r->ranks > 1 ? (bdl_result)(int)bdl_comm_max((double)res) : res;
}

bdl_run_def bdl_default_run_def(void)
{
    bdl_run_def d;
    memset(&d, 0, sizeof d);
    d.until = -1.0;
    return d;
}

bdl_result bdl_run_frame(bdl_frames *frames, const bdl_world *w, long index)
{
    bdl_snapshot *slot = bdl_frames_slot(frames);
    return bdl_frames_commit(frames, index, slot && bdl_capture(slot, w));
}

int bdl_run_checkpoint_path(const char *resume, char *out, size_t len)
{
    struct stat st;
    if (stat(resume, &st) == 0 && S_ISDIR(st.st_mode)) {
        snprintf(out, len, "%s/checkpoint/state.bdlckpt", resume);
        return 1;
    }
    snprintf(out, len, "%s", resume);
    return 0;
}

/// Phase 1: the scene, its end time, and the solver's thread count.
static bdl_result read_scene(run *r)
{
    const bdl_run_def *def = r->def;
    bdl_scene_error err;
    if (!(r->scene = calloc(1, sizeof *r->scene)))
        return BDL_ERR_NOMEM;
    // Read on the first rank and sent to the others (a scene holds no pointers).
    bdl_result res = BDL_OK;
    if (r->rank == 0)
        res = bdl_scene_load(def->scene_path, def->overrides, def->override_count, r->scene, &err);
    if (res != BDL_OK)
        bdl_error("%s", err.message);
    // --until is checked as [run] end_time is: its range, and the outputs it asks for.
    if (res == BDL_OK && r->rank == 0 && def->until > 0.0 &&
        (res = bdl_scene_set_end_time(r->scene, def->until, &err)) != BDL_OK)
        bdl_error("%s", err.message);
    res = (bdl_result)bdl_comm_broadcast_int((int)res, 0);
    if (res != BDL_OK)
        return res;
    bdl_comm_broadcast(r->scene, sizeof *r->scene, 0);
    int threads = def->threads > 0 ? def->threads : r->scene->threads;
    if (threads > 0)
        omp_set_num_threads(threads);
    r->threads = omp_get_max_threads();
    // Only the solver thread runs a team (it is told `threads`). The main thread builds the world
    // and then waits on it; a team of its own would leave an idle worker behind, and with more
    // workers than cores libgomp stops spin-waiting, so that every parallel region of the solver
    // would sleep and wake through the kernel (docs/performance.md, "Why these thresholds").
    omp_set_num_threads(1);
    return BDL_OK;
}

/// Phase 2: the output folder, its subfolders and run.log (appended to when resuming).
static bdl_result open_folder(run *r)
{
    const char *out = r->def->out_dir;
    if (r->rank > 0) // the first rank writes
        return BDL_OK;
    char why[512], sub[1200];
    if (bdl_check_writable_dir(out, why, sizeof why) != BDL_OK) {
        bdl_error("output folder '%s' is not writable: %s", out, why);
        return BDL_ERR_OUTPUT_DIR;
    }
    // A file where a folder should be is found now, not at the first output hours later.
    static const char *const folders[] = {"vtk", "frames", "checkpoint"};
    for (int k = 0; k < 3; ++k) {
        if (k == 1 && !(r->scene->output.frame_interval > 0.0))
            continue;
        snprintf(sub, sizeof sub, "%s/%s", out, folders[k]);
        if (bdl_mkdir_p(sub) != BDL_OK) {
            bdl_describe_write_error(why, sizeof why, sub, errno);
            bdl_error("output folder '%s' is not writable: %s", out, why);
            return BDL_ERR_OUTPUT_DIR;
        }
    }
    snprintf(sub, sizeof sub, "%s/run.log", out);
    r->log = fopen(sub, r->def->resume ? "a" : "w");
    if (r->log) {
        setvbuf(r->log, NULL, _IOLBF, 0);
        bdl_log_set_file(r->log);
    }
    return BDL_OK;
}

/// The domain, to the last bit (bedlam analyze fields reads it).
static void log_domain(const bdl_scene *s)
{
    bdl_info("domain: %.17g %.17g %.17g to %.17g %.17g %.17g m", s->domain_min.x, s->domain_min.y,
             s->domain_min.z, s->domain_max.x, s->domain_max.y, s->domain_max.z);
}

/// The head of run.log for a world of parcels: what they stand for, how they fill the gas's
/// cells, the step against their stable step (they have no contacts).
static void log_parcels(const bdl_world *w)
{
    const bdl_scene *s = &w->scene;
    bdl_parcels_census c;
    log_domain(s);
    if (bdl_world_parcels_census(w, &c) == BDL_OK)
        bdl_info("parcels: %ld standing for %.4g real particles, species: %d; parcels per filled "
                 "cell: mean %.3g, min %.0f, max %.0f (%ld of %ld gas cells); largest solids "
                 "fraction of a cell %.3g",
                 c.parcels, c.real_particles, s->species_count, c.per_cell_mean, c.per_cell_min,
                 c.per_cell_max, c.filled_cells, c.cells, c.max_solids);
    for (int k = 0; k < s->species_count; ++k) {
        const bdl_species_def *sp = &s->species[k];
        bdl_info("species %s: d = %g m, rho = %g kg/m^3, %.4g real particles and %.4g m^3 of "
                 "solids per parcel (at d)",
                 sp->name, sp->diameter, sp->density, bdl_species_parcel_count(sp, sp->diameter),
                 bdl_species_parcel_volume(sp));
    }
    const bdl_parcels_def *d = &s->parcels.def;
    const double stable = bdl_world_parcels_stable_dt(w);
    bdl_info("dt = %g s, the parcels' stable step %g s (dt = %.3g of it; refused above twice it), "
             "end time = %g s",
             w->dt, stable, w->dt / stable, s->end_time);
    bdl_info("limits: close packing theta_cs = %g (the packing guard holds parcels back above "
             "it), stress at theta_cs - floor = %.4g Pa; energy_growth not checked (the gas's and "
             "the stress's work on the parcels are not booked)",
             d->close_packing, bdl_parcels_stress(d, d->close_packing - d->stress_floor));
}

/// The head of run.log for a world with a solids phase: the bed, and the step against the gas's
/// expected stable step (there are no particles, so no contact time).
static void log_solids(const bdl_world *w)
{
    const bdl_scene *s = &w->scene;
    log_domain(s);
    char bed[512];
    bdl_world_solids_bed(w, bed, sizeof bed);
    bdl_info("solids: %.4g m^3 (%s), restitution %.4g%s", bdl_solids_volume(w->solids, -1), bed,
             w->solids->def.restitution, w->solids->count > 1 ? " (the first phase's)" : "");
    const double stable = bdl_world_inflow_gas_dt(w);
    if (s->solids.courant > 0.0)
        bdl_info("dt adaptive: Courant number %g, at most %g s, first %g s (the gas's expected "
                 "stable step %g s), end time = %g s",
                 s->solids.courant, s->dt, w->dt, stable, s->end_time);
    else
        bdl_info("dt = %g s, the gas's expected stable step %g s (dt = %.3g of it; refused above "
                 "twice it), end time = %g s",
                 w->dt, stable, w->dt / stable, s->end_time);
    bdl_info("limits: the solids fraction held below packing by the plastic regime from %g; "
             "energy_growth not checked (the solids' energy is not booked)",
             w->solids->def.eps_star);
}

/// The head of run.log: what runs, with which models and limits.
static void log_setup(const run *r)
{
    const bdl_world *w = r->world;
    const bdl_scene *s = &w->scene;
    bdl_info("bedlam %s", BDL_VERSION);
    bdl_info("scene: %s", s->path);
    for (int k = 0; k < r->def->override_count; ++k)
        bdl_info("override: %s", r->def->overrides[k]);
    bdl_info("output: %s", r->def->out_dir);
    bdl_info("threads: %d", r->threads);
    char modules[1536];
    bdl_world_describe(w, modules, sizeof modules);
    bdl_info("modules: %s", modules);
    if (w->parcels) {
        log_parcels(w);
        return;
    }
    if (w->solids) {
        log_solids(w);
        return;
    }
    bdl_info("particles: %ld, species: %d", w->particles.count, s->species_count);
    log_domain(s);
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

/// The checkpoint a run resumes from, restored into the world built from the scene. The run
/// steps with the scene's time step (checked against the contact time already): when the
/// checkpoint's differs, or the scene's contact parameters do, it says so.
static bdl_result resume(run *r)
{
    bdl_world *w = r->world;
    char ckpt[1200], why[1024];
    bdl_checkpoint_info info;
    bdl_run_checkpoint_path(r->def->resume, ckpt, sizeof ckpt);
    if (bdl_check_regular_file(ckpt, NULL, why, sizeof why) != BDL_OK) {
        bdl_error("checkpoint %s %s", ckpt, why); // a FIFO would block the reader
        return BDL_ERR_CHECKPOINT;
    }
    bdl_result res = bdl_checkpoint_load(w, ckpt, &info, why, sizeof why);
    if (res != BDL_OK) {
        bdl_error("%s", why);
        return res;
    }
    bdl_info("resumed from %s at t = %.17g s, step %ld", ckpt, w->time, w->step);
    snprintf(r->outputs.good_path, sizeof r->outputs.good_path, "%s", ckpt);
    if (info.changes[0])
        bdl_warn("the scene's contact parameters differ from the checkpoint's: %s", info.changes);
    if (w->solids && w->scene.solids.courant > 0.0) {
        // An adaptive step: the next one follows from the checkpointed state, as it would have.
    } else if (info.dt != w->dt && w->solids) {
        bdl_warn("the checkpoint was written with dt = %g s; the run continues with the scene's "
                 "dt = %g s. The resumed run does not repeat an uninterrupted one bit for bit",
                 info.dt, w->dt);
    } else if (info.dt != w->dt && w->parcels) {
        bdl_warn("the checkpoint was written with dt = %g s; the run continues with the scene's "
                 "dt = %g s (%.3g of the parcels' stable step %g s). The resumed run does not "
                 "repeat an uninterrupted one bit for bit",
                 info.dt, w->dt, w->dt / bdl_world_parcels_stable_dt(w),
                 bdl_world_parcels_stable_dt(w));
    } else if (info.dt != w->dt) {
        const double limit = w->scene.guards.dt_refuse * w->contact_time;
        char above[160] = "";
        if (info.dt > limit)
            snprintf(above, sizeof above,
                     "; the checkpoint's would be %.3g times the scene's stable "
                     "limit %g s ([guards] dt_refuse = %g of the contact time)",
                     info.dt / limit, limit, w->scene.guards.dt_refuse);
        bdl_warn("the checkpoint was written with dt = %g s; the run continues with the scene's "
                 "dt = %g s (%.3g of its contact time %g s)%s. The resumed run does not repeat an "
                 "uninterrupted one bit for bit",
                 info.dt, w->dt, w->contact_time_dt_ratio, w->contact_time, above);
    }
    return BDL_OK;
}

/// Phase 3 under MPI: every rank builds the world whole (and resumes it), keeps its part; the
/// first also builds the whole mirror its outputs read (bdl_world_dist_mirror).
static bdl_result build_divided(run *r)
{
    bdl_scene_error err;
    bdl_result res = bdl_world_create_whole(r->scene, &r->world, &err);
    if (res == BDL_ERR_SCENE)
        bdl_error("%s", err.message);
    char message[1024], warning[1024] = "";
    if (res == BDL_OK && (res = bdl_guards_check_dt(r->world, message, sizeof message, warning,
                                                    sizeof warning)) != BDL_OK)
        bdl_error("%s", message);
    if (res == BDL_OK && r->def->resume)
        res = resume(r);
    // The division is an exchange between all ranks: only when every rank got this far.
    if ((res = agree(r, res)) == BDL_OK && (res = bdl_world_dist_init(r->world, &err)) != BDL_OK)
        bdl_error("%s", res == BDL_ERR_SCENE ? err.message : bdl_result_text(res));
    r->divided = r->world;
    r->world = NULL;
    if (res == BDL_OK && r->rank == 0 &&
        (res = bdl_world_create_whole(r->scene, &r->world, &err)) != BDL_OK)
        bdl_error("cannot build the whole world on the first rank: %s", bdl_result_text(res));
    free(r->scene);
    r->scene = NULL;
    if ((res = agree(r, res)) != BDL_OK)
        return res;
    if (r->rank == 0) // the energy the resumed run started from (set by the outputs otherwise)
        r->world->energy0 = r->divided->energy0;
    if (warning[0])
        bdl_warn("%s", warning);
    res = bdl_world_dist_mirror(r->divided, r->world, 0); // the checkpoint's state, or the start
    const double own = (double)r->divided->particles.count, most = bdl_comm_max(own);
    double total = own;
    bdl_comm_sum(&total, 1);
    if (res == BDL_OK && r->rank == 0) {
        log_setup(r);
        const bdl_decomp *d = bdl_dist_decomp(r->divided->dist);
        bdl_info("ranks: %d (MPI), boxes %d x %d x %d, ghost margin %.4g m; particles per rank at "
                 "most %.0f, on average %.1f (max/mean %.3f)",
                 r->ranks, d->dims[0], d->dims[1], d->dims[2], d->margin, most, total / r->ranks,
                 most * r->ranks / (total > 0.0 ? total : 1.0));
    }
    return agree(r, res);
}

/// Phase 3: the world, its time step checked against the contact time, and the checkpoint it
/// resumes from.
static bdl_result build_world(run *r)
{
    if (r->ranks > 1)
        return build_divided(r);
    bdl_scene_error err;
    bdl_result res = bdl_world_create(r->scene, &r->world, &err);
    free(r->scene);
    r->scene = NULL;
    if (res != BDL_OK) {
        if (res == BDL_ERR_SCENE)
            bdl_error("%s", err.message);
        else
            bdl_error("cannot build the world: %s", bdl_result_text(res));
        return res;
    }
    char message[1024], warning[1024];
    if ((res = bdl_guards_check_dt(r->world, message, sizeof message, warning, sizeof warning)) !=
        BDL_OK) {
        bdl_error("%s", message);
        return res;
    }
    if (warning[0])
        bdl_warn("%s", warning);
    if (r->def->resume && (res = resume(r)) != BDL_OK)
        return res;
    log_setup(r);
    return BDL_OK;
}

/// The progress the caller is given, from the solver's counters and the outputs' last errors.
static void report_progress(run *r, bdl_loop *loop, double t0, long step0)
{
    bdl_run_status s = {0};
    bdl_loop_progress(loop, &s.time, &s.step, &s.particles, &s.finished);
    if (r->divided) // the loop counts this rank's own
        s.particles = atomic_load(&r->particles);
    s.start_time = t0;
    s.start_step = step0;
    s.end_time = r->world->scene.end_time;
    s.wall_seconds = bdl_wall_seconds() - r->outputs.start_wall;
    s.progress_interval = r->world->scene.output.progress_interval;
    s.gas = r->world->gas != NULL;
    bdl_run_outputs_status(&r->outputs, &s);
    r->def->progress(r->def->user, &s);
}

/// After each step of an MPI run (on every rank): when the first rank's outputs fall due (or a
/// rank is told to stop), the whole state is gathered into its mirror and the outputs written
/// from it; every rank goes on or stops with the first rank's result.
static bdl_result divided_step(void *user, bdl_world *w)
{
    run *r = user;
    double due = 0.0;
    if (r->rank == 0) {
        r->world->time = w->time;
        r->world->step = w->step;
        due = bdl_run_outputs_due(&r->outputs, r->world);
    }
    double flags[2] = {due, r->def->stop && *r->def->stop}; // a stop told to any rank
    bdl_comm_sum(flags, 2);
    if (flags[0] == 0.0 && flags[1] == 0.0)
        return BDL_OK;
    r->stop_now = flags[1] > 0.0; // what the first rank's outputs read
    bdl_result res = bdl_world_dist_mirror(w, r->world, 0);
    if (res == BDL_OK && r->rank == 0) {
        atomic_store(&r->particles, r->world->particles.count);
        res = bdl_run_outputs_step(&r->outputs, r->world);
    }
    return (bdl_result)bdl_comm_broadcast_int((int)agree(r, res), 0);
}

/// Phase 5: the solver thread to the end, while this thread draws queued frames and reports
/// progress.
static bdl_result solve(run *r)
{
    bdl_world *stepped = r->divided ? r->divided : r->world;
    bdl_loop_def ld = bdl_default_loop_def();
    ld.world = stepped;
    ld.end_time = stepped->scene.end_time;
    ld.max_steps = r->def->max_steps;
    ld.threads = r->threads;
    ld.on_step = r->divided ? divided_step : bdl_run_outputs_step;
    ld.user = r->divided ? (void *)r : (void *)&r->outputs;
    // Where the run starts, read before the solver thread owns the world.
    const double t0 = stepped->time, interval = stepped->scene.output.progress_interval;
    const long step0 = stepped->step;
    bdl_loop *loop = bdl_loop_start(&ld);
    if (!loop) {
        bdl_error("cannot start the solver thread");
        return BDL_ERR_NOMEM;
    }
    double last = r->outputs.start_wall;
    for (;;) {
        double t;
        long step, particles;
        int finished;
        bdl_loop_progress(loop, &t, &step, &particles, &finished);
        if (finished) {
            if (r->def->progress && r->rank == 0)
                report_progress(r, loop, t0, step0);
            break;
        }
        if (r->outputs.frames)
            bdl_frames_pump(r->outputs.frames, 0.02);
        else
            bdl_sleep(0.02);
        if (r->def->progress && r->rank == 0 && bdl_wall_seconds() - last >= interval) {
            report_progress(r, loop, t0, step0);
            last = bdl_wall_seconds();
        }
    }
    bdl_result res = bdl_loop_join(loop);
    bdl_loop_destroy(loop);
    return res;
}

/// After an instability: what stopped the run, where its state went, and the checkpoint a resume
/// takes.
static void report_stop(const run *r, int failed_written)
{
    const bdl_run_outputs *o = &r->outputs;
    const char *out = r->def->out_dir;
    bdl_error("run stopped: %s", o->failure);
    if (failed_written)
        bdl_error("the state at the stop is in %s/checkpoint/failed.bdlckpt, for inspection; it "
                  "is not resumed",
                  out);
    if (o->good_path[0])
        bdl_error("the last good checkpoint is %s (t = %.9g s, step %ld): after changing the "
                  "scene, 'bedlam run %s --resume %s' continues from it",
                  o->good_path, o->good_time, o->good_step, r->def->scene_path, out);
    else
        bdl_error("no checkpoint was written before the stop ([output] checkpoint_interval)");
}

/// Phase 6: the last outputs and the summary in the log, whatever the outcome.
static bdl_result finish(run *r, bdl_result res, int solved, bdl_run_report *report)
{
    if (r->divided) { // the last state whole on the first rank; the others are done
        if (solved) {
            const bdl_result gathered = bdl_world_dist_mirror(r->divided, r->world, 0);
            res = res == BDL_OK ? gathered : res;
        }
        if (r->world && r->divided->failure[0]) // why a step failed (the same on every rank)
            snprintf(r->world->failure, sizeof r->world->failure, "%s", r->divided->failure);
        bdl_world_destroy(r->divided);
        r->divided = NULL;
        if (r->rank > 0) {
            free(r->scene);
            return res;
        }
    }
    bdl_world *w = r->world;
    if (solved && !r->outputs.failure[0] && w->failure[0]) // the world's own failure
        snprintf(r->outputs.failure, sizeof r->outputs.failure, "%s", w->failure);
    const int failed_written = w ? bdl_run_outputs_close(&r->outputs, solved, &res) : 0;
    const double wall = w ? bdl_wall_seconds() - r->outputs.start_wall : 0.0;
    if (solved && res == BDL_ERR_UNSTABLE) {
        report_stop(r, failed_written);
    } else if (solved && res == BDL_ERR_INTERRUPTED) {
        bdl_warn("interrupted at t = %g s (step %ld); state saved in %s/checkpoint/ — continue "
                 "with 'bedlam run %s --resume %s'",
                 w->time, w->step, r->def->out_dir, r->def->scene_path, r->def->out_dir);
    } else if (solved && res != BDL_OK) {
        bdl_error("run failed: %s",
                  r->outputs.failure[0] ? r->outputs.failure : bdl_result_text(res));
    }
    if (solved && r->outputs.also[0])
        bdl_error("%s", r->outputs.also);
    if (solved)
        bdl_info("finished at t = %.6g s, step %ld, %ld particles, %.3f s wall, checkpoint %s",
                 w->time, w->step, w->particles.count, wall,
                 r->outputs.final_checkpoint[0] ? r->outputs.final_checkpoint : "NOT written");
    if (solved && w->solids && w->scene.solids.courant > 0.0)
        bdl_info("adaptive step: %ld steps, %.4g s on average; %ld taken back and retaken "
                 "shorter (in this process)",
                 w->step, w->time / (double)(w->step > 0 ? w->step : 1), w->solids_retakes);
    if (solved && w->parcels)
        bdl_info("parcels: %ld held back by the packing guard over the run; after the last step "
                 "%ld touching pairs, %ld side contacts, largest overlap %.3g of R_ep (model B)",
                 w->parcels_held, w->parcel_pairs, w->parcel_walls, w->parcel_overlap);
    if (report && w)
        *report = (bdl_run_report){w->time, w->step, w->particles.count, wall};
    bdl_world_destroy(w);
    free(r->scene);
    if (r->log) {
        bdl_log_set_file(NULL);
        fclose(r->log);
    }
    return res;
}

bdl_result bdl_run(const bdl_run_def *def, bdl_run_report *report)
{
    run r = {.def = def, .rank = bdl_comm_rank(), .ranks = bdl_comm_size()};
    r.outputs.stop = r.ranks > 1 ? &r.stop_now : def->stop;
    bdl_result res = read_scene(&r);
    if (res == BDL_OK)
        res = agree(&r, open_folder(&r));
    if (res == BDL_OK)
        res = build_world(&r);
    if (res == BDL_OK && r.rank == 0)
        res = bdl_run_outputs_open(&r.outputs, r.world, def->out_dir, def->resume != NULL,
                                   def->gl_backend);
    res = agree(&r, res);
    const int solved = res == BDL_OK;
    if (solved)
        res = solve(&r);
    return finish(&r, res, solved, report);
}
