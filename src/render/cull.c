#include "render/cull.h"

#include <math.h>
#include <stdlib.h>

#define CELL   1     ///< grid cell [px]
#define MARGIN 0.05f ///< added around bounding boxes for rounding [px]

/// A sphere on screen: pixel position of the centre, inner radius (a disk surely inside the
/// projection), bounding box, near and far view depths.
typedef struct projected {
    float x, y, inner;
    float x0, y0, x1, y1;
    float near_z, far_z;
} projected;

/// Returns 0 when the sphere reaches behind the eye (then it is drawn, never culled).
static int project(const float *p, float r, const float *v, const float *pr, int ortho, int w,
                   int h, projected *out)
{
    float cx = v[0] * p[0] + v[4] * p[1] + v[8] * p[2] + v[12];
    float cy = v[1] * p[0] + v[5] * p[1] + v[9] * p[2] + v[13];
    float cz = -(v[2] * p[0] + v[6] * p[1] + v[10] * p[2] + v[14]); // depth, > 0 ahead
    float sx = 0.5f * (float)w * pr[0], sy = 0.5f * (float)h * pr[5];
    out->near_z = cz - r;
    out->far_z = cz + r;
    if (ortho) {
        out->x = 0.5f * (float)w * (1.0f + pr[12]) + sx * cx;
        out->y = 0.5f * (float)h * (1.0f + pr[13]) + sy * cy;
        out->inner = 0.99f * r * sx;
        out->x0 = out->x - r * sx - MARGIN, out->x1 = out->x + r * sx + MARGIN;
        out->y0 = out->y - r * sy - MARGIN, out->y1 = out->y + r * sy + MARGIN;
        return 1;
    }
    float den = cz * cz - r * r;
    if (out->near_z <= 0.0f || den <= 0.0f)
        return 0;
    // Exact bounding box of the projection (see shaders/sphere.vert).
    float mx = cx * cz / den, my = cy * cz / den;
    float hx = r * sqrtf(cx * cx + den) / den, hy = r * sqrtf(cy * cy + den) / den;
    out->x0 = 0.5f * (float)w + sx * (mx - hx) - MARGIN;
    out->x1 = 0.5f * (float)w + sx * (mx + hx) + MARGIN;
    out->y0 = 0.5f * (float)h + sy * (my - hy) - MARGIN;
    out->y1 = 0.5f * (float)h + sy * (my + hy) + MARGIN;
    // The projection contains the disk of radius f r / |c| about the projected centre (the
    // silhouette cone's cross-section, seen from its apex, widens off the axis); 0.99 for
    // rounding.
    float dist = sqrtf(cx * cx + cy * cy + cz * cz);
    out->x = 0.5f * (float)w + sx * cx / cz;
    out->y = 0.5f * (float)h + sy * cy / cz;
    out->inner = 0.99f * sx * r / dist;
    return 1;
}

static int grid_reserve(bdl_cull *c, int w, int h)
{
    c->cols = (w + CELL - 1) / CELL;
    c->rows = (h + CELL - 1) / CELL;
    int need = c->cols * c->rows;
    if (need > c->capacity) {
        float *d = realloc(c->depth, (size_t)need * sizeof(float));
        if (!d)
            return 0;
        c->depth = d;
        c->capacity = need;
    }
    for (int k = 0; k < need; ++k)
        c->depth[k] = INFINITY;
    return 1;
}

static int clipped(const float *clip, const float *p)
{
    return clip && clip[0] * p[0] + clip[1] * p[1] + clip[2] * p[2] + clip[3] > 0.0f;
}

/// Writes the sphere's far depth into the cells wholly inside its inner disk: per row of cells,
/// the chord of the disk at the row's edge farther from the centre bounds the cells.
static void occlude(bdl_cull *c, const projected *q)
{
    float r = q->inner;
    int j0 = (int)ceilf((q->y - r) / CELL), j1 = (int)floorf((q->y + r) / CELL) - 1;
    j0 = j0 < 0 ? 0 : j0;
    j1 = j1 >= c->rows ? c->rows - 1 : j1;
    for (int j = j0; j <= j1; ++j) {
        // The row's edge farther from the centre has the shorter chord.
        float y = fmaxf(fabsf((float)(j * CELL) - q->y), fabsf((float)((j + 1) * CELL) - q->y));
        float half = r * r - y * y;
        if (half <= 0.0f)
            continue;
        half = sqrtf(half);
        int i0 = (int)ceilf((q->x - half) / CELL), i1 = (int)floorf((q->x + half) / CELL) - 1;
        i0 = i0 < 0 ? 0 : i0;
        i1 = i1 >= c->cols ? c->cols - 1 : i1;
        float *row = &c->depth[j * c->cols];
        for (int i = i0; i <= i1; ++i)
            row[i] = q->far_z < row[i] ? q->far_z : row[i];
    }
}

/// Whether every cell under the bounding box is occluded nearer than the sphere's near side.
static int hidden(const bdl_cull *c, const projected *q)
{
    int i0 = (int)floorf(q->x0 / CELL), i1 = (int)floorf(q->x1 / CELL);
    int j0 = (int)floorf(q->y0 / CELL), j1 = (int)floorf(q->y1 / CELL);
    i0 = i0 < 0 ? 0 : i0;
    j0 = j0 < 0 ? 0 : j0;
    i1 = i1 >= c->cols ? c->cols - 1 : i1;
    j1 = j1 >= c->rows ? c->rows - 1 : j1;
    for (int j = j0; j <= j1; ++j) // an empty range (off screen) is hidden
        for (int i = i0; i <= i1; ++i)
            if (!(c->depth[j * c->cols + i] < q->near_z))
                return 0;
    return 1;
}

/// The frame the particles are projected into.
typedef struct frame {
    const float *view, *proj; ///< column-major
    int ortho, width, height;
} frame;

static int project_ball(const frame *f, const float *p, float r, projected *out)
{
    return project(p, r, f->view, f->proj, f->ortho, f->width, f->height, out);
}

/// A rod occludes with balls of its radius along its shaft, at most a radius apart: each lies
/// inside it, and their inner disks overlap into a band along the shaft's image.
static void occlude_rod(bdl_cull *c, const frame *f, const float *p, float r, const float *a)
{
    float h = sqrtf(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    int n = r > 0.0f ? (int)ceilf(h / r) : 0;
    projected q;
    for (int k = -n; k <= n; ++k) {
        float s = n > 0 ? (float)k / (float)n : 0.0f;
        float x[3] = {p[0] + s * a[0], p[1] + s * a[1], p[2] + s * a[2]};
        if (project_ball(f, x, r, &q))
            occlude(c, &q);
    }
}

/// A rod's bounds on screen: the rod is the convex hull of its two end balls, so its image lies
/// in the union of theirs and its nearest point is one of theirs. 0 when an end reaches behind
/// the eye.
static int project_rod(const frame *f, const float *p, float r, const float *a, projected *out)
{
    float lo[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    float hi[3] = {p[0] + a[0], p[1] + a[1], p[2] + a[2]};
    projected e;
    if (!project_ball(f, lo, r, out) || !project_ball(f, hi, r, &e))
        return 0;
    out->x0 = fminf(out->x0, e.x0), out->x1 = fmaxf(out->x1, e.x1);
    out->y0 = fminf(out->y0, e.y0), out->y1 = fmaxf(out->y1, e.y1);
    out->near_z = fminf(out->near_z, e.near_z);
    return 1;
}

static void occlude_all(bdl_cull *c, const frame *f, const float *pos, const float *radius,
                        const float *axis, long count, const float *clip)
{
    projected q;
    for (long i = 0; i < count; ++i) {
        const float *p = &pos[3 * i];
        if (clipped(clip, p))
            continue;
        if (axis)
            occlude_rod(c, f, p, radius[i], &axis[3 * i]);
        else if (project_ball(f, p, radius[i], &q))
            occlude(c, &q);
    }
}

long bdl_cull_particles(bdl_cull *c, const float *pos, const float *radius, const float *axis,
                        long count, const float view[16], const float proj[16], int ortho,
                        int width, int height, const float *clip, uint8_t *visible)
{
    if (!grid_reserve(c, width, height)) {
        for (long i = 0; i < count; ++i)
            visible[i] = !clipped(clip, &pos[3 * i]);
        return count;
    }
    const frame f = {view, proj, ortho, width, height};
    occlude_all(c, &f, pos, radius, axis, count, clip);
    long shown = 0;
    projected q;
    for (long i = 0; i < count; ++i) {
        const float *p = &pos[3 * i];
        int on_screen = axis ? project_rod(&f, p, radius[i], &axis[3 * i], &q)
                             : project_ball(&f, p, radius[i], &q);
        int v = !clipped(clip, p) && (!on_screen || !hidden(c, &q));
        visible[i] = (uint8_t)v;
        shown += v;
    }
    return shown;
}

void bdl_cull_free(bdl_cull *c)
{
    free(c->depth);
    c->depth = NULL;
    c->capacity = 0;
}
