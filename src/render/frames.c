#define _POSIX_C_SOURCE 200809L
#include "render/frames.h"

#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/file.h"
#include "core/log.h"
#include "core/memory.h"
#include "io/png.h"
#include "render/renderer.h"

#define SLOTS  3 ///< snapshots waiting to be drawn
#define IMAGES 3 ///< images waiting to be encoded

typedef struct image {
    uint8_t *rgb;
    long index;
} image;

struct bdl_frames {
    char folder[1024];
    bdl_context *context;
    bdl_renderer *renderer;
    bdl_view view;
    int width, height;

    pthread_mutex_t lock;
    pthread_cond_t changed; ///< any queue changed
    bdl_snapshot slots[SLOTS];
    long slot_index[SLOTS];
    int slot_head, slot_count; ///< queued snapshots, in order
    image images[IMAGES];
    int image_head, image_count; ///< queued images, in order
    int closing;
    bdl_result error;
    char failure[1200]; ///< the file a write failed on, and why
    long written;
    pthread_t encoder;
    int encoder_started;
};

static void fail(bdl_frames *f, bdl_result r)
{
    if (f->error == BDL_OK)
        f->error = r;
    pthread_cond_broadcast(&f->changed);
}

static void *encoder_main(void *arg)
{
    bdl_frames *f = arg;
    pthread_mutex_lock(&f->lock);
    for (;;) {
        while (f->image_count == 0 && !f->closing)
            pthread_cond_wait(&f->changed, &f->lock);
        if (f->image_count == 0)
            break;
        image *im = &f->images[f->image_head];
        pthread_mutex_unlock(&f->lock);
        char path[1100];
        snprintf(path, sizeof path, "%s/frame_%06ld.png", f->folder, im->index);
        bdl_result r = bdl_png_write(path, im->rgb, f->width, f->height, 3, 0);
        char why[1200];
        if (r == BDL_ERR_IO)
            bdl_describe_write_error(why, sizeof why, path, errno);
        else if (r != BDL_OK)
            snprintf(why, sizeof why, "%s: %s", path, bdl_result_text(r));
        pthread_mutex_lock(&f->lock);
        if (r != BDL_OK && f->error == BDL_OK)
            memcpy(f->failure, why, sizeof f->failure);
        if (r != BDL_OK)
            fail(f, r);
        else
            f->written++;
        f->image_head = (f->image_head + 1) % IMAGES;
        f->image_count--;
        pthread_cond_broadcast(&f->changed);
    }
    pthread_mutex_unlock(&f->lock);
    return NULL;
}

/// Draws one sphere at the domain's centre and reads it back, so that the driver compiles its
/// shader variants now and not while the solver runs (llvmpipe compiles for a second or more,
/// and a solver sharing the cores with the compiler would wait for it).
static void warm_up(bdl_frames *f, const bdl_scene *scene)
{
    bdl_vec3 c = bdl_v3_scale(bdl_v3_add(scene->domain_min, scene->domain_max), 0.5);
    float pos[3] = {(float)c.x, (float)c.y, (float)c.z}, vel[3] = {0, 0, 0};
    float radius = (float)(0.5 * scene->species[0].diameter);
    uint8_t coordination = 0;
    int32_t species = 0;
    uint32_t id = 0;
    bdl_snapshot s = {.count = 1,
                      .capacity = 1,
                      .pos = pos,
                      .vel = vel,
                      .radius = &radius,
                      .coordination = &coordination,
                      .species = &species,
                      .id = &id};
    bdl_renderer_draw(f->renderer, &s, &f->view, f->width, f->height);
    bdl_renderer_read(f->renderer, f->images[0].rgb);
}

bdl_result bdl_frames_open(const bdl_frames_def *def, bdl_frames **out, char *why, size_t why_len)
{
    *out = NULL;
    bdl_frames *f = calloc(1, sizeof *f);
    if (!f)
        return BDL_ERR_NOMEM;
    const bdl_output_def *o = &def->scene->output;
    snprintf(f->folder, sizeof f->folder, "%s", def->folder);
    f->width = o->frame_width;
    f->height = o->frame_height;
    pthread_mutex_init(&f->lock, NULL);
    pthread_cond_init(&f->changed, NULL);
    size_t bytes = 0; // RGB, three bytes a pixel
    const int sized = bdl_size_mul3((size_t)f->width, (size_t)f->height, 3, &bytes);
    for (int k = 0; k < IMAGES; ++k)
        if (!sized || !(f->images[k].rgb = malloc(bytes))) {
            bdl_frames_close(f, NULL);
            return BDL_ERR_NOMEM;
        }
    bdl_context_def cd = {.backend = def->backend, .width = f->width, .height = f->height};
    bdl_result r = bdl_context_create(&cd, &f->context, why, why_len);
    if (r == BDL_OK) {
        bdl_renderer_def rd = {.scene = def->scene,
                               .headless = 1,
                               .width = f->width,
                               .height = f->height,
                               .samples = o->frame_samples};
        r = bdl_renderer_create(&rd, &f->renderer, why, why_len);
    }
    if (r == BDL_OK && pthread_create(&f->encoder, NULL, encoder_main, f) != 0)
        r = BDL_ERR_NOMEM;
    f->encoder_started = r == BDL_OK;
    if (r != BDL_OK) {
        bdl_frames_close(f, NULL);
        return r;
    }
    bdl_view_from_scene(def->scene, (float)f->width / (float)f->height, &f->view);
    warm_up(f, def->scene);
    *out = f;
    return BDL_OK;
}

bdl_snapshot *bdl_frames_slot(bdl_frames *f)
{
    pthread_mutex_lock(&f->lock);
    while (f->slot_count == SLOTS && f->error == BDL_OK)
        pthread_cond_wait(&f->changed, &f->lock);
    // The slot after the queue is not drawn until it is committed, and only this thread queues.
    bdl_snapshot *slot =
        f->error == BDL_OK ? &f->slots[(f->slot_head + f->slot_count) % SLOTS] : NULL;
    pthread_mutex_unlock(&f->lock);
    return slot;
}

bdl_result bdl_frames_commit(bdl_frames *f, long index, int filled)
{
    pthread_mutex_lock(&f->lock);
    bdl_result r = f->error;
    if (r == BDL_OK && !filled)
        fail(f, r = BDL_ERR_NOMEM);
    if (r == BDL_OK) {
        f->slot_index[(f->slot_head + f->slot_count) % SLOTS] = index;
        f->slot_count++;
        pthread_cond_broadcast(&f->changed);
    }
    pthread_mutex_unlock(&f->lock);
    return r;
}

const char *bdl_frames_failure(const bdl_frames *f) { return f->failure; }

bdl_result bdl_frames_sync(bdl_frames *f)
{
    pthread_mutex_lock(&f->lock);
    // The caller's thread draws the queued snapshots and the encoder writes them; both signal.
    while ((f->slot_count > 0 || f->image_count > 0) && f->error == BDL_OK)
        pthread_cond_wait(&f->changed, &f->lock);
    const bdl_result r = f->error;
    pthread_mutex_unlock(&f->lock);
    return r;
}

static void deadline_after(struct timespec *ts, double seconds)
{
    clock_gettime(CLOCK_REALTIME, ts);
    long ns = ts->tv_nsec + (long)(seconds * 1e9);
    ts->tv_sec += ns / 1000000000L;
    ts->tv_nsec = ns % 1000000000L;
}

/// Draws the oldest queued snapshot and queues its image. Called with the lock held.
static void draw_one(bdl_frames *f)
{
    int k = f->slot_head;
    while (f->image_count == IMAGES && f->error == BDL_OK)
        pthread_cond_wait(&f->changed, &f->lock);
    if (f->error != BDL_OK)
        return;
    image *im = &f->images[(f->image_head + f->image_count) % IMAGES];
    pthread_mutex_unlock(&f->lock);
    bdl_renderer_draw(f->renderer, &f->slots[k], &f->view, f->width, f->height);
    bdl_result r = bdl_renderer_read(f->renderer, im->rgb);
    pthread_mutex_lock(&f->lock);
    if (r != BDL_OK) {
        bdl_error("frame %ld: reading the pixels back failed", f->slot_index[k]);
        fail(f, r);
        return;
    }
    im->index = f->slot_index[k];
    f->image_count++;
    f->slot_head = (f->slot_head + 1) % SLOTS;
    f->slot_count--;
    pthread_cond_broadcast(&f->changed);
}

int bdl_frames_pump(bdl_frames *f, double timeout)
{
    struct timespec deadline;
    deadline_after(&deadline, timeout);
    int drawn = 0;
    pthread_mutex_lock(&f->lock);
    while (f->slot_count == 0 && f->error == BDL_OK)
        if (pthread_cond_timedwait(&f->changed, &f->lock, &deadline) == ETIMEDOUT)
            break;
    while (f->slot_count > 0 && f->error == BDL_OK) {
        draw_one(f);
        drawn++;
    }
    pthread_mutex_unlock(&f->lock);
    return drawn;
}

bdl_result bdl_frames_close(bdl_frames *f, long *written)
{
    if (!f)
        return BDL_OK;
    if (f->renderer)
        bdl_frames_pump(f, 0.0);
    pthread_mutex_lock(&f->lock);
    f->closing = 1;
    pthread_cond_broadcast(&f->changed);
    pthread_mutex_unlock(&f->lock);
    if (f->encoder_started)
        pthread_join(f->encoder, NULL);
    bdl_result r = f->error;
    if (written)
        *written = f->written;
    bdl_renderer_destroy(f->renderer);
    bdl_context_destroy(f->context);
    for (int k = 0; k < SLOTS; ++k)
        bdl_snapshot_free(&f->slots[k]);
    for (int k = 0; k < IMAGES; ++k)
        free(f->images[k].rgb);
    pthread_mutex_destroy(&f->lock);
    pthread_cond_destroy(&f->changed);
    free(f);
    return r;
}
