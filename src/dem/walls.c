#include "dem/walls.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

BDL_CHOICE_WORDS(bdl_wall_kind, BDL_WALL_KINDS);
BDL_CHOICE_WORDS(bdl_motion_kind, BDL_MOTIONS);
BDL_CHOICE_WORDS(bdl_wall_frame, BDL_WALL_FRAMES);

static void add_plane(bdl_walls *walls, int wall, bdl_vec3 point, bdl_vec3 normal)
{
    bdl_wall_prim *p = &walls->prims[walls->prim_count++];
    p->kind = BDL_PRIM_PLANE;
    p->wall = wall;
    p->point = point;
    p->normal = normal;
    p->radius = 0.0;
}

// -------------------------------------------------------------------------------- triangles --

/// Bin index of a point, or -1 outside the bins.
static long bin_of(const bdl_wall_bins *b, bdl_vec3 x)
{
    double c[3] = {(x.x - b->lo.x) / b->size, (x.y - b->lo.y) / b->size, (x.z - b->lo.z) / b->size};
    long index = 0;
    for (int a = 2; a >= 0; --a) {
        if (!(c[a] >= 0.0 && c[a] < b->dims[a]))
            return -1;
        index = index * b->dims[a] + (long)c[a];
    }
    return index;
}

/// Whether triangle t may come within `reach` of bin (i, j, k): the bin's box grown by reach
/// overlaps the triangle's box, and the bin's centre lies within reach plus half the bin's
/// diagonal of the triangle's plane.
static int bin_touches(const bdl_wall_bins *b, const bdl_wall_tri *t, int i, int j, int k,
                       double reach)
{
    bdl_vec3 centre = bdl_v3(b->lo.x + (i + 0.5) * b->size, b->lo.y + (j + 0.5) * b->size,
                             b->lo.z + (k + 0.5) * b->size);
    return fabs(bdl_v3_dot(bdl_v3_sub(centre, t->a), t->normal)) <=
           reach + 0.8660254037844387 * b->size;
}

/// Visits the bins a triangle may reach: counts it in b->start (bin + 1) when `cursor` is NULL,
/// else appends it to each bin's list at the cursor. Returns the bins visited.
static long bin_triangle(bdl_wall_bins *b, const bdl_wall_tri *t, long index, double reach,
                         int32_t *cursor)
{
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
        double mn = fmin(fmin(bdl_v3_comp(t->a, a), bdl_v3_comp(t->b, a)), bdl_v3_comp(t->c, a));
        double mx = fmax(fmax(bdl_v3_comp(t->a, a), bdl_v3_comp(t->b, a)), bdl_v3_comp(t->c, a));
        lo[a] = (int)floor((mn - reach - bdl_v3_comp(b->lo, a)) / b->size);
        hi[a] = (int)floor((mx + reach - bdl_v3_comp(b->lo, a)) / b->size);
        lo[a] = lo[a] < 0 ? 0 : lo[a];
        hi[a] = hi[a] >= b->dims[a] ? b->dims[a] - 1 : hi[a];
    }
    long visits = 0;
    for (int k = lo[2]; k <= hi[2]; ++k)
        for (int j = lo[1]; j <= hi[1]; ++j)
            for (int i = lo[0]; i <= hi[0]; ++i) {
                if (!bin_touches(b, t, i, j, k, reach))
                    continue;
                long bin = ((long)k * b->dims[1] + j) * b->dims[0] + i;
                if (cursor)
                    b->tri[cursor[bin]++] = (int32_t)index;
                else
                    ++b->start[bin + 1];
                ++visits;
            }
    return visits;
}

/// Bins of a size no smaller than reach, grown until there are at most 2^22 of them.
static void size_bins(bdl_wall_bins *b, bdl_vec3 lo, bdl_vec3 hi, double reach)
{
    b->lo = bdl_v3(lo.x - reach, lo.y - reach, lo.z - reach);
    b->size = reach > 0.0 ? reach : 1e-3;
    for (;;) {
        double cells = 1.0;
        for (int a = 0; a < 3; ++a) {
            b->dims[a] =
                (int)ceil((bdl_v3_comp(hi, a) - bdl_v3_comp(lo, a) + 2.0 * reach) / b->size) + 1;
            cells *= b->dims[a];
        }
        if (cells <= 4194304.0)
            return;
        b->size *= 2.0;
    }
}

/// Bins the triangles first .. tri_count - 1 of one mesh wall.
static bdl_result bin_mesh(bdl_walls *walls, int wall, long first, double reach)
{
    bdl_wall_bins *b = &walls->bins[wall];
    bdl_vec3 lo = walls->tri[first].a, hi = lo;
    for (long t = first; t < walls->tri_count; ++t)
        for (int c = 0; c < 3; ++c) {
            bdl_vec3 v = c == 0 ? walls->tri[t].a : c == 1 ? walls->tri[t].b : walls->tri[t].c;
            lo = bdl_v3(fmin(lo.x, v.x), fmin(lo.y, v.y), fmin(lo.z, v.z));
            hi = bdl_v3(fmax(hi.x, v.x), fmax(hi.y, v.y), fmax(hi.z, v.z));
        }
    size_bins(b, lo, hi, reach);
    long bins = (long)b->dims[0] * b->dims[1] * b->dims[2];
    b->start = calloc((size_t)bins + 1, sizeof *b->start);
    int32_t *cursor = malloc((size_t)bins * sizeof *cursor);
    if (!b->start || !cursor) {
        free(cursor);
        return BDL_ERR_NOMEM;
    }
    long entries = 0;
    for (long t = first; t < walls->tri_count; ++t)
        entries += bin_triangle(b, &walls->tri[t], t, reach, NULL);
    if (entries > INT32_MAX) {
        free(cursor);
        return BDL_ERR_NOMEM;
    }
    for (long k = 0; k < bins; ++k)
        b->start[k + 1] += b->start[k];
    memcpy(cursor, b->start, (size_t)bins * sizeof *cursor);
    b->tri = malloc((size_t)(entries > 0 ? entries : 1) * sizeof *b->tri);
    if (b->tri)
        for (long t = first; t < walls->tri_count; ++t)
            bin_triangle(b, &walls->tri[t], t, reach, cursor);
    free(cursor);
    return b->tri ? BDL_OK : BDL_ERR_NOMEM;
}

bdl_result bdl_wall_mesh_of(const bdl_wall_def *d, bdl_mesh *m, char *why, size_t why_len)
{
    if (d->kind == BDL_WALL_DISK)
        return bdl_mesh_disk(m, d->point, d->normal, d->radius, d->hole_radius, d->segments, why,
                             why_len);
    if (d->kind == BDL_WALL_CONE)
        return bdl_mesh_frustum(m, d->point, d->normal, d->radius, d->radius_top, d->height,
                                d->segments, why, why_len);
    bdl_result r = bdl_mesh_read(d->file, m, why, why_len);
    if (r == BDL_OK)
        bdl_mesh_transform(m, d->scale, d->rotate, d->translate);
    return r;
}

/// Reads, places and bins one mesh wall; its vertex ids follow the earlier meshes'.
static bdl_result add_mesh(bdl_walls *walls, int wall, const bdl_wall_def *d, double reach,
                           char *why, size_t why_len)
{
    bdl_mesh m;
    char reason[400];
    bdl_result r = bdl_wall_mesh_of(d, &m, reason, sizeof reason);
    if (r != BDL_OK) {
        snprintf(why, why_len, "'%s' %s", d->kind == BDL_WALL_MESH ? d->file : d->name, reason);
        return r;
    }
    const long first = walls->tri_count, vert0 = walls->vertex_count;
    bdl_wall_tri *tri = realloc(walls->tri, (size_t)(first + m.tri_count) * sizeof *tri);
    if (!tri) {
        bdl_mesh_free(&m);
        snprintf(why, why_len, "'%s': not enough memory for %ld triangles", d->file, m.tri_count);
        return BDL_ERR_NOMEM;
    }
    walls->tri = tri;
    for (long t = 0; t < m.tri_count; ++t) {
        bdl_wall_tri *w = &tri[first + t];
        w->a = m.vertex[m.tri[t][0]];
        w->b = m.vertex[m.tri[t][1]];
        w->c = m.vertex[m.tri[t][2]];
        w->normal = bdl_v3_normalize(bdl_v3_cross(bdl_v3_sub(w->b, w->a), bdl_v3_sub(w->c, w->a)));
        w->wall = wall;
        for (int c = 0; c < 3; ++c)
            w->vert[c] = (int32_t)(vert0 + m.tri[t][c]);
    }
    walls->tri_count += m.tri_count;
    walls->vertex_count += m.vertex_count;
    bdl_mesh_free(&m);
    r = bin_mesh(walls, wall, first, reach);
    if (r != BDL_OK)
        snprintf(why, why_len, "'%s': not enough memory to bin its triangles", d->file);
    return r;
}

int bdl_walls_near(const bdl_walls *walls, int wall, bdl_vec3 x, const int32_t **list)
{
    const bdl_wall_bins *b = &walls->bins[wall];
    long bin = b->start ? bin_of(b, bdl_wall_to_rest(walls, wall, x)) : -1;
    if (bin < 0)
        return 0;
    *list = b->tri + b->start[bin];
    return (int)(b->start[bin + 1] - b->start[bin]);
}

double bdl_wall_tri_gap(const bdl_walls *walls, long index, bdl_vec3 x, double radius, bdl_vec3 *n)
{
    const bdl_wall_tri *t = &walls->tri[index];
    if (walls->gone[t->wall]) {
        *n = bdl_v3_zero();
        return INFINITY;
    }
    const bdl_vec3 p = bdl_wall_to_rest(walls, t->wall, x);
    int face;
    const bdl_vec3 q = bdl_triangle_nearest(t->a, t->b, t->c, p, &face);
    double gap;
    if (face) {
        const double h = bdl_v3_dot(bdl_v3_sub(p, t->a), t->normal);
        *n = h >= 0.0 ? t->normal : bdl_v3_neg(t->normal);
        gap = fabs(h) - radius;
    } else {
        const bdl_vec3 d = bdl_v3_sub(p, q);
        const double dist = bdl_v3_len(d);
        *n = dist > 0.0 ? bdl_v3_scale(d, 1.0 / dist) : t->normal;
        gap = dist - radius;
    }
    if (walls->turns[t->wall])
        *n = bdl_q_rotate(walls->turned[t->wall], *n);
    return gap;
}

/// Whether triangle u lies on or behind the plane of triangle t as a sphere at x (rest frame) sees
/// it (every corner of u not in front of t's plane, to round-off of the corners' distances).
static int behind(const bdl_wall_tri *t, const bdl_wall_tri *u, bdl_vec3 x)
{
    const bdl_vec3 n =
        bdl_v3_dot(bdl_v3_sub(x, t->a), t->normal) >= 0.0 ? t->normal : bdl_v3_neg(t->normal);
    const bdl_vec3 v[3] = {u->a, u->b, u->c};
    for (int k = 0; k < 3; ++k) {
        const bdl_vec3 d = bdl_v3_sub(v[k], t->a);
        if (bdl_v3_dot(d, n) > 1e-12 * bdl_v3_len(d))
            return 0;
    }
    return 1;
}

/// Whether two touched triangles belong to one patch of overlap: they share a vertex and meet
/// flat or convex as the sphere sees them (a concave join, as in the corner of a box, parts two
/// patches that each push).
static int one_patch(const bdl_walls *walls, int32_t a, int32_t b, bdl_vec3 x)
{
    const bdl_wall_tri *s = &walls->tri[a], *t = &walls->tri[b];
    int shared = 0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            shared |= s->vert[i] == t->vert[j];
    if (!shared)
        return 0;
    x = bdl_wall_to_rest(walls, s->wall, x); // the two share a vertex: one wall
    return behind(s, t, x) && behind(t, s, x);
}

#define PATCH_MAX 64

int bdl_wall_tri_counted(const bdl_walls *walls, const int32_t *surfaces, int count, int self,
                         bdl_vec3 x, double radius)
{
    const long first = walls->prim_count;
    if (surfaces[self] < first)
        return 1;
    // The touched triangles of the list (the first PATCH_MAX of them), with their gaps.
    int32_t tri[PATCH_MAX];
    double gap[PATCH_MAX];
    int m = 0, me = -1;
    for (int k = 0; k < count && m < PATCH_MAX; ++k) {
        bdl_vec3 n;
        double g;
        if (surfaces[k] < first ||
            (g = bdl_wall_tri_gap(walls, surfaces[k] - first, x, radius, &n)) >= 0.0)
            continue;
        me = k == self ? m : me;
        tri[m] = (int32_t)(surfaces[k] - first);
        gap[m++] = g;
    }
    if (me < 0)
        return 1; // beyond the first PATCH_MAX touched: counted on its own
    // Grow self's patch; self counts when no triangle of it is touched deeper (ties: the first).
    int in[PATCH_MAX] = {0}, queue[PATCH_MAX], head = 0, tail = 0;
    in[me] = 1;
    queue[tail++] = me;
    while (head < tail) {
        const int a = queue[head++];
        for (int b = 0; b < m; ++b)
            if (!in[b] && one_patch(walls, tri[a], tri[b], x)) {
                if (gap[b] < gap[me] || (gap[b] == gap[me] && b < me))
                    return 0;
                in[b] = 1;
                queue[tail++] = b;
            }
    }
    return 1;
}

/// The farthest a vertex of mesh wall `wall` (triangles first ..) lies from its axis [m].
static double reach_from_axis(const bdl_walls *walls, int wall, long first)
{
    double far = 0.0;
    const bdl_vec3 a = walls->axis[wall], c = walls->center[wall];
    for (long t = first; t < walls->tri_count; ++t)
        for (int k = 0; k < 3; ++k) {
            const bdl_wall_tri *u = &walls->tri[t];
            const bdl_vec3 q = bdl_v3_sub(k == 0 ? u->a : k == 1 ? u->b : u->c, c);
            far = fmax(far, bdl_v3_len(bdl_v3_madd(q, a, -bdl_v3_dot(q, a))));
        }
    return far;
}

bdl_result bdl_walls_build(const bdl_wall_def *defs, int count, double reach, bdl_walls *walls,
                           char *why, size_t why_len)
{
    memset(walls, 0, sizeof *walls);
    walls->wall_count = count;
    for (int w = 0; w < count; ++w) {
        const bdl_wall_def *d = &defs[w];
        switch (d->kind) {
        case BDL_WALL_PLANE:
            walls->plane_normal[w] = bdl_v3_normalize(d->normal);
            add_plane(walls, w, d->point, walls->plane_normal[w]);
            break;
        case BDL_WALL_BOX:
            for (int axis = 0; axis < 3; ++axis) {
                bdl_vec3 n = bdl_v3_zero();
                bdl_v3_set_comp(&n, axis, 1.0);
                add_plane(walls, w, d->box_min, n);
                add_plane(walls, w, d->box_max, bdl_v3_neg(n));
            }
            break;
        case BDL_WALL_CYLINDER: {
            bdl_wall_prim *p = &walls->prims[walls->prim_count++];
            p->kind = BDL_PRIM_CYLINDER;
            p->wall = w;
            p->point = d->point;
            p->normal = bdl_v3_normalize(d->normal);
            p->radius = d->radius;
            break;
        }
        case BDL_WALL_MESH:
        case BDL_WALL_DISK:
        case BDL_WALL_CONE:
            break; // triangles, added below
        }
        // A container wall stands still: the run is done in its frame (see world/world.h).
        const int moves = d->motion == BDL_MOTION_VIBRATE && d->frame != BDL_FRAME_CONTAINER;
        walls->motion[w] = moves ? d->motion : BDL_MOTION_NONE;
        walls->direction[w] = bdl_v3_normalize(d->direction);
        walls->amplitude[w] = moves ? d->amplitude : 0.0;
        walls->omega[w] = 2.0 * PI * d->frequency;
        walls->phase[w] = d->phase;
        walls->start[w] = d->start;
        walls->open_time[w] = d->open_time;
        if (d->motion == BDL_MOTION_MOVE) {
            walls->motion[w] = BDL_MOTION_MOVE;
            walls->drive[w] = d->velocity;
            walls->stop[w] = d->stop;
        }
        if (d->motion == BDL_MOTION_ROTATE) {
            walls->motion[w] = BDL_MOTION_ROTATE;
            walls->center[w] = d->rotation_center;
            walls->axis[w] = bdl_v3_normalize(d->rotation_axis);
            walls->turn[w] = bdl_v3_scale(walls->axis[w], d->angular_velocity);
            walls->radius[w] = d->kind == BDL_WALL_CYLINDER ? d->radius : 0.0;
            walls->omega[w] = 1.0; // the live factor on the rate (bdl_world_apply_live)
        }
        walls->turned[w] = bdl_q_identity();
    }
    for (int w = 0; w < count; ++w) {
        if (defs[w].kind != BDL_WALL_MESH && defs[w].kind != BDL_WALL_DISK &&
            defs[w].kind != BDL_WALL_CONE)
            continue;
        const long first = walls->tri_count;
        bdl_result r = add_mesh(walls, w, &defs[w], reach, why, why_len);
        if (r != BDL_OK) {
            bdl_walls_free(walls);
            return r;
        }
        if (walls->motion[w] == BDL_MOTION_ROTATE) {
            walls->turns[w] = 1;
            walls->radius[w] = reach_from_axis(walls, w, first);
        }
    }
    bdl_walls_update(walls, 0.0);
    return BDL_OK;
}

void bdl_walls_free(bdl_walls *walls)
{
    free(walls->tri);
    for (int w = 0; w < BDL_MAX_WALLS; ++w) {
        free(walls->bins[w].start);
        free(walls->bins[w].tri);
    }
    walls->tri = NULL;
    walls->tri_count = walls->vertex_count = 0;
    memset(walls->bins, 0, sizeof walls->bins);
}

void bdl_walls_update(bdl_walls *walls, double t)
{
    for (int w = 0; w < walls->wall_count; ++w) {
        walls->gone[w] = t >= walls->open_time[w];
        walls->spin[w] = walls->motion[w] == BDL_MOTION_ROTATE && t >= walls->start[w]
                             ? bdl_v3_scale(walls->turn[w], walls->omega[w])
                             : bdl_v3_zero();
        if (walls->turns[w])
            walls->turned[w] = bdl_q_axis_angle(walls->axis[w], walls->angle[w]);
        if (walls->motion[w] == BDL_MOTION_MOVE && t >= walls->start[w]) {
            const double end = fmin(t, walls->stop[w]);
            walls->offset[w] = bdl_v3_scale(walls->drive[w], end - walls->start[w]);
            walls->velocity[w] = t < walls->stop[w] ? walls->drive[w] : bdl_v3_zero();
            continue;
        }
        if (walls->motion[w] != BDL_MOTION_VIBRATE || t < walls->start[w]) {
            walls->offset[w] = bdl_v3_zero();
            walls->velocity[w] = bdl_v3_zero();
            continue;
        }
        double arg = walls->omega[w] * (t - walls->start[w]) + walls->phase[w];
        double a = walls->amplitude[w];
        walls->offset[w] = bdl_v3_scale(walls->direction[w], a * sin(arg));
        walls->velocity[w] = bdl_v3_scale(walls->direction[w], a * walls->omega[w] * cos(arg));
    }
}

void bdl_walls_turn(bdl_walls *walls, double dt)
{
    for (int w = 0; w < walls->wall_count; ++w)
        if (walls->turns[w])
            walls->angle[w] += bdl_v3_dot(walls->spin[w], walls->axis[w]) * dt;
}

double bdl_walls_max_shift(const bdl_walls *walls, const bdl_vec3 *ref, const double *ref_angle)
{
    double m = 0.0;
    for (int w = 0; w < walls->wall_count; ++w) {
        const bdl_vec3 shift = bdl_v3_sub(walls->offset[w], ref[w]);
        const bdl_vec3 n = walls->plane_normal[w];
        const double along =
            n.x == 0.0 && n.y == 0.0 && n.z == 0.0 ? bdl_v3_len(shift) : fabs(bdl_v3_dot(shift, n));
        double d =
            along + walls->radius[w] * fabs(walls->angle[w] - ref_angle[w]) * walls->turns[w];
        if (d > m)
            m = d;
    }
    return m;
}

double bdl_walls_max_speed(const bdl_walls *walls)
{
    double m = 0.0;
    for (int w = 0; w < walls->wall_count; ++w) {
        double v = walls->motion[w] == BDL_MOTION_ROTATE
                       ? bdl_v3_len(walls->turn[w]) * walls->omega[w] * walls->radius[w]
                   : walls->motion[w] == BDL_MOTION_MOVE ? bdl_v3_len(walls->drive[w])
                                                         : walls->amplitude[w] * walls->omega[w];
        if (v > m)
            m = v;
    }
    return m;
}
