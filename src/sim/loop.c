#include "sim/loop.h"

#include <omp.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cfd/gas.h"
#include "core/log.h"
#include "core/timer.h"

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

int bdl_world_set_parameter(bdl_world *w, const char *key, double value)
{
    if (strcmp(key, "gas.inlet_scale") == 0 && w->gas) {
        w->live.inlet_scale = value;
        bdl_world_apply_live(w);
        return 1;
    }
    for (int k = 0; k < w->scene.wall_count; ++k) {
        char a[96], f[96];
        snprintf(a, sizeof a, "wall.%s.amplitude_scale", w->scene.walls[k].name);
        snprintf(f, sizeof f, "wall.%s.frequency_scale", w->scene.walls[k].name);
        if (strcmp(key, a) == 0)
            w->live.amplitude_scale[k] = value;
        else if (strcmp(key, f) == 0)
            w->live.frequency_scale[k] = value;
        else
            continue;
        bdl_world_apply_live(w);
        return 1;
    }
    return 0;
}

static int snapshot_reserve(bdl_snapshot *s, long n)
{
    if (n <= s->capacity)
        return 1;
    long cap = n + n / 4 + 64;
    void *a = realloc(s->pos, (size_t)cap * 3 * sizeof(float));
    if (!a)
        return 0;
    s->pos = a;
    if (!(a = realloc(s->vel, (size_t)cap * 3 * sizeof(float))))
        return 0;
    s->vel = a;
    if (!(a = realloc(s->radius, (size_t)cap * sizeof(float))))
        return 0;
    s->radius = a;
    if (!(a = realloc(s->coordination, (size_t)cap)))
        return 0;
    s->coordination = a;
    if (!(a = realloc(s->species, (size_t)cap * sizeof(int32_t))))
        return 0;
    s->species = a;
    if (!(a = realloc(s->id, (size_t)cap * sizeof(uint32_t))))
        return 0;
    s->id = a;
    s->capacity = cap;
    return 1;
}

static int reserve_slice(bdl_snapshot *s, long count)
{
    if (count <= s->slice_capacity)
        return 1;
    float *a = realloc(s->slice, (size_t)count * sizeof(float));
    if (!a)
        return 0;
    s->slice = a;
    s->slice_capacity = count;
    return 1;
}

/// The [camera] gas_field on its slice: the layer of cells the slice position falls in.
static int fill_slice(bdl_snapshot *s, const bdl_world *w)
{
    const bdl_camera_def *cam = &w->scene.camera;
    s->slice_n[0] = s->slice_n[1] = 0;
    if (!w->gas || cam->gas_field == BDL_GAS_FIELD_NONE)
        return 1;
    const bdl_gas *gas = w->gas;
    const bdl_grid *g = &gas->grid;
    const int a = cam->gas_slice_axis, b = (a + 1) % 3, c = (a + 2) % 3;
    if (!reserve_slice(s, (long)g->n[b] * g->n[c]))
        return 0;
    int m = (int)floor(cam->gas_slice_position * g->n[a]);
    m = m < 0 ? 0 : m >= g->n[a] ? g->n[a] - 1 : m;
    for (int jc = 0; jc < g->n[c]; ++jc)
        for (int jb = 0; jb < g->n[b]; ++jb) {
            int ix[3];
            ix[a] = m, ix[b] = jb, ix[c] = jc;
            const long idx = bdl_grid_index(g, ix[0], ix[1], ix[2]);
            double v = gas->eps[idx];
            if (cam->gas_field == BDL_GAS_FIELD_PRESSURE) {
                v = gas->p[idx];
            } else if (cam->gas_field == BDL_GAS_FIELD_SPEED) {
                double sum = 0.0;
                for (int d = 0; d < 3; ++d) {
                    double u = bdl_gas_cell_velocity(gas, d, ix[0], ix[1], ix[2]);
                    sum += u * u;
                }
                v = sqrt(sum);
            }
            s->slice[(long)jc * g->n[b] + jb] = (float)v;
        }
    s->slice_field = (int)cam->gas_field;
    s->slice_axis = a;
    for (int d = 0; d < 3; ++d) {
        s->slice_lo[d] = (float)g->origin[d];
        s->slice_hi[d] = (float)(g->origin[d] + g->n[d] * g->h[d]);
    }
    s->slice_at =
        s->slice_lo[a] + (float)cam->gas_slice_position * (s->slice_hi[a] - s->slice_lo[a]);
    s->slice_n[0] = g->n[b];
    s->slice_n[1] = g->n[c];
    return 1;
}

int bdl_snapshot_fill(bdl_snapshot *s, const bdl_world *w)
{
    const bdl_particles *p = &w->particles;
    if (!snapshot_reserve(s, p->count))
        return 0;
    for (long i = 0; i < p->count; ++i) {
        s->pos[3 * i] = (float)p->pos[i].x;
        s->pos[3 * i + 1] = (float)p->pos[i].y;
        s->pos[3 * i + 2] = (float)p->pos[i].z;
        s->vel[3 * i] = (float)p->vel[i].x;
        s->vel[3 * i + 1] = (float)p->vel[i].y;
        s->vel[3 * i + 2] = (float)p->vel[i].z;
        s->radius[i] = (float)p->radius[i];
    }
    memcpy(s->coordination, w->coordination, (size_t)p->count);
    memcpy(s->species, p->species, (size_t)p->count * sizeof(int32_t));
    memcpy(s->id, p->id, (size_t)p->count * sizeof(uint32_t));
    s->count = p->count;
    s->time = w->time;
    s->step = w->step;
    s->wall_count = w->walls.wall_count;
    for (int k = 0; k < w->walls.wall_count; ++k) {
        s->wall_offset[k][0] = (float)w->walls.offset[k].x;
        s->wall_offset[k][1] = (float)w->walls.offset[k].y;
        s->wall_offset[k][2] = (float)w->walls.offset[k].z;
    }
    return fill_slice(s, w);
}

int bdl_snapshot_copy(bdl_snapshot *dst, const bdl_snapshot *src)
{
    if (!snapshot_reserve(dst, src->count))
        return 0;
    long n = src->count;
    memcpy(dst->pos, src->pos, (size_t)n * 3 * sizeof(float));
    memcpy(dst->vel, src->vel, (size_t)n * 3 * sizeof(float));
    memcpy(dst->radius, src->radius, (size_t)n * sizeof(float));
    memcpy(dst->coordination, src->coordination, (size_t)n);
    memcpy(dst->species, src->species, (size_t)n * sizeof(int32_t));
    memcpy(dst->id, src->id, (size_t)n * sizeof(uint32_t));
    dst->count = n;
    dst->time = src->time;
    dst->step = src->step;
    dst->wall_count = src->wall_count;
    memcpy(dst->wall_offset, src->wall_offset, sizeof dst->wall_offset);
    dst->steps_per_second = src->steps_per_second;
    long cells = (long)src->slice_n[0] * src->slice_n[1];
    if (!reserve_slice(dst, cells))
        return 0;
    if (cells > 0)
        memcpy(dst->slice, src->slice, (size_t)cells * sizeof(float));
    dst->slice_field = src->slice_field;
    dst->slice_axis = src->slice_axis;
    dst->slice_at = src->slice_at;
    memcpy(dst->slice_lo, src->slice_lo, sizeof dst->slice_lo);
    memcpy(dst->slice_hi, src->slice_hi, sizeof dst->slice_hi);
    memcpy(dst->slice_n, src->slice_n, sizeof dst->slice_n);
    return 1;
}

void bdl_snapshot_free(bdl_snapshot *s)
{
    free(s->slice);
    free(s->pos);
    free(s->vel);
    free(s->radius);
    free(s->coordination);
    free(s->species);
    free(s->id);
    memset(s, 0, sizeof *s);
}

static void publish(bdl_loop *loop)
{
    bdl_snapshot *s = &loop->slots[loop->back];
    if (!bdl_snapshot_fill(s, loop->def.world))
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
