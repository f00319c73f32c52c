#include "run/loop.h"

#include <omp.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/log.h"
#include "core/timer.h"
#include "output/capture.h"

#define QUEUE_SIZE 64
#define DIRTY      4

struct bdl_loop {
    bdl_loop_def def;
    pthread_t thread;
    pthread_mutex_t lock; ///< guards the command queue and the pause state
    pthread_cond_t wake;
    bdl_command queue[QUEUE_SIZE];
    int queue_head, queue_count;
    int paused, pending_steps, stop;

    bdl_snapshot slots[3];
    int back, front;
    atomic_int middle; ///< slot index | DIRTY when newer than the reader's

    _Atomic double progress_time;
    atomic_long progress_step;
    atomic_long progress_particles;
    atomic_int finished;
    bdl_result result;
    double speed_time;          ///< wall clock of the last speed estimate [s]
    long speed_step;            ///< step at that time
    double speed;               ///< steps per wall second
    _Atomic double speed_limit; ///< simulated seconds per wall second; 0: as fast as it goes
};

bdl_loop_def bdl_default_loop_def(void)
{
    bdl_loop_def d;
    memset(&d, 0, sizeof d);
    d.end_time = 1.0;
    d.publish_interval = 1.0 / 60.0;
    return d;
}

static void publish(bdl_loop *loop)
{
    bdl_snapshot *s = &loop->slots[loop->back];
    if (!bdl_capture(s, loop->def.world))
        return;
    // The solver's speed over the last quarter second or more.
    double now = bdl_wall_seconds();
    if (now - loop->speed_time >= 0.25) {
        if (loop->speed_time > 0.0)
            loop->speed = (double)(s->step - loop->speed_step) / (now - loop->speed_time);
        loop->speed_time = now;
        loop->speed_step = s->step;
    }
    s->steps_per_second = loop->speed;
    int prev = atomic_exchange(&loop->middle, loop->back | DIRTY);
    loop->back = prev & 3;
}

const bdl_snapshot *bdl_loop_acquire(bdl_loop *loop)
{
    if (atomic_load(&loop->middle) & DIRTY) {
        int prev = atomic_exchange(&loop->middle, loop->front);
        loop->front = prev & 3;
    }
    const bdl_snapshot *s = &loop->slots[loop->front];
    return s->capacity > 0 ? s : NULL;
}

static void apply_command(bdl_loop *loop, const bdl_command *c)
{
    bdl_world *w = loop->def.world;
    switch (c->kind) {
    case BDL_CMD_PAUSE:
        loop->paused = 1;
        bdl_info("step %ld: command pause", w->step);
        break;
    case BDL_CMD_RESUME:
        loop->paused = 0;
        bdl_info("step %ld: command resume", w->step);
        break;
    case BDL_CMD_STEP:
        loop->pending_steps++;
        bdl_info("step %ld: command step", w->step);
        break;
    case BDL_CMD_SET:
        if (bdl_world_set_parameter(w, c->key, c->value))
            bdl_info("step %ld: command set %s = %g", w->step, c->key, c->value);
        else
            bdl_warn("step %ld: command set: unknown parameter '%s' ignored", w->step, c->key);
        break;
    case BDL_CMD_STOP:
        loop->stop = 1;
        bdl_info("step %ld: command stop", w->step);
        break;
    }
}

/// Applies queued commands; blocks while paused with nothing to do. Returns 0 to stop.
static int take_commands(bdl_loop *loop)
{
    pthread_mutex_lock(&loop->lock);
    for (;;) {
        while (loop->queue_count > 0) {
            bdl_command c = loop->queue[loop->queue_head];
            loop->queue_head = (loop->queue_head + 1) % QUEUE_SIZE;
            loop->queue_count--;
            apply_command(loop, &c);
        }
        if (loop->stop || !loop->paused || loop->pending_steps > 0)
            break;
        pthread_cond_wait(&loop->wake, &loop->lock);
    }
    int go = !loop->stop;
    if (go && loop->paused)
        loop->pending_steps--;
    pthread_mutex_unlock(&loop->lock);
    return go;
}

static void *solver_main(void *arg)
{
    bdl_loop *loop = arg;
    bdl_world *w = loop->def.world;
    // The thread count is a per-thread OpenMP setting: set it on the thread that runs the loops.
    if (loop->def.threads > 0)
        omp_set_num_threads(loop->def.threads);
    double last_publish = -1e30;
    loop->result = BDL_OK;
    if (loop->def.publish)
        publish(loop);
    // Stop within half a step of the end time, so rounding of t never adds a step.
    long steps = 0;
    double limit_seen = -1.0, ref_wall = 0.0, ref_time = 0.0;
    while (w->time < loop->def.end_time - 0.5 * w->dt) {
        if (!take_commands(loop))
            break;
        double limit = atomic_load(&loop->speed_limit);
        if (limit > 0.0 && !loop->paused) {
            // Keep simulated time within limit x wall time of a reference point, which moves
            // whenever the limit changes or the loop fell behind by more than a tenth second.
            double now = bdl_wall_seconds();
            double ahead = (w->time - ref_time) / limit - (now - ref_wall);
            if (limit != limit_seen || ahead < -0.1) {
                ref_wall = now;
                ref_time = w->time;
                limit_seen = limit;
            } else if (ahead > 0.0) {
                double pause = ahead < 0.05 ? ahead : 0.05;
                bdl_sleep(pause);
                continue;
            }
        }
        if (loop->def.max_steps > 0 && steps++ >= loop->def.max_steps)
            break;
        bdl_result r = bdl_world_step(w);
        if (r == BDL_OK && loop->def.on_step)
            r = loop->def.on_step(loop->def.user, w);
        atomic_store(&loop->progress_time, w->time);
        atomic_store(&loop->progress_step, w->step);
        atomic_store(&loop->progress_particles, w->particles.count);
        if (r != BDL_OK) {
            if (loop->def.log_failures && w->failure[0])
                bdl_error("%s", w->failure);
            loop->result = r;
            break;
        }
        if (loop->def.publish) {
            double now = bdl_wall_seconds();
            if (now - last_publish >= loop->def.publish_interval || loop->paused) {
                publish(loop);
                last_publish = now;
            }
        }
    }
    if (loop->def.publish)
        publish(loop);
    atomic_store(&loop->finished, 1);
    return NULL;
}

bdl_loop *bdl_loop_start(const bdl_loop_def *def)
{
    bdl_loop *loop = calloc(1, sizeof *loop);
    if (!loop)
        return NULL;
    loop->def = *def;
    loop->paused = def->start_paused;
    loop->back = 0;
    loop->front = 1;
    atomic_init(&loop->middle, 2);
    atomic_init(&loop->progress_time, def->world->time);
    atomic_init(&loop->progress_step, def->world->step);
    atomic_init(&loop->progress_particles, def->world->particles.count);
    atomic_init(&loop->finished, 0);
    pthread_mutex_init(&loop->lock, NULL);
    pthread_cond_init(&loop->wake, NULL);
    if (pthread_create(&loop->thread, NULL, solver_main, loop) != 0) {
        pthread_mutex_destroy(&loop->lock);
        pthread_cond_destroy(&loop->wake);
        free(loop);
        return NULL;
    }
    return loop;
}

void bdl_loop_command(bdl_loop *loop, const bdl_command *cmd)
{
    pthread_mutex_lock(&loop->lock);
    if (loop->queue_count < QUEUE_SIZE) {
        loop->queue[(loop->queue_head + loop->queue_count) % QUEUE_SIZE] = *cmd;
        loop->queue_count++;
    }
    pthread_cond_signal(&loop->wake);
    pthread_mutex_unlock(&loop->lock);
}

void bdl_loop_set_speed_limit(bdl_loop *loop, double sim_per_wall)
{
    atomic_store(&loop->speed_limit, sim_per_wall > 0.0 ? sim_per_wall : 0.0);
    bdl_info("speed limit: %g simulated seconds per second", sim_per_wall);
}

void bdl_loop_progress(bdl_loop *loop, double *time, long *step, long *particles, int *finished)
{
    *time = atomic_load(&loop->progress_time);
    *step = atomic_load(&loop->progress_step);
    *particles = atomic_load(&loop->progress_particles);
    *finished = atomic_load(&loop->finished);
}

bdl_result bdl_loop_join(bdl_loop *loop)
{
    pthread_join(loop->thread, NULL);
    return loop->result;
}

void bdl_loop_destroy(bdl_loop *loop)
{
    if (!loop)
        return;
    for (int k = 0; k < 3; ++k)
        bdl_snapshot_free(&loop->slots[k]);
    pthread_mutex_destroy(&loop->lock);
    pthread_cond_destroy(&loop->wake);
    free(loop);
}
