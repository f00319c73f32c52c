// bedlam — the domain and the walls as thin outlines, so the container reads without hiding the
// bed. Built once from the scene as line segments, one group per wall; each group is drawn
// shifted by its wall's current offset and turned by its turned angle, so a vibrating box moves
// and a mixer's blade turns on screen.
#include <cglm/cglm.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/mesh.h"
#include "render/renderer_internal.h"

#define CIRCLE_SEGS 64

static int push_vertex(bdl_render_outlines *o, bdl_vec3 p)
{
    if (o->line_count == o->line_capacity) {
        int cap = o->line_capacity ? 2 * o->line_capacity : 256;
        float *a = realloc(o->lines, (size_t)cap * 3 * sizeof(float));
        if (!a)
            return 0;
        o->lines = a;
        o->line_capacity = cap;
    }
    float *v = &o->lines[3 * o->line_count++];
    v[0] = (float)p.x;
    v[1] = (float)p.y;
    v[2] = (float)p.z;
    return 1;
}

static void push_segment(bdl_render_outlines *o, bdl_vec3 a, bdl_vec3 b)
{
    push_vertex(o, a);
    push_vertex(o, b);
}

static bdl_vec3 corner(bdl_vec3 lo, bdl_vec3 hi, int k)
{
    return bdl_v3((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
}

static void push_box(bdl_render_outlines *o, bdl_vec3 lo, bdl_vec3 hi)
{
    for (int k = 0; k < 8; ++k)
        for (int axis = 0; axis < 3; ++axis)
            if (!(k & (1 << axis)))
                push_segment(o, corner(lo, hi, k), corner(lo, hi, k | (1 << axis)));
}

/// Two unit vectors spanning the plane normal to n.
static void basis(bdl_vec3 n, bdl_vec3 *u, bdl_vec3 *v)
{
    bdl_vec3 a = fabs(n.x) < 0.9 ? bdl_v3(1, 0, 0) : bdl_v3(0, 1, 0);
    *u = bdl_v3_normalize(bdl_v3_cross(n, a));
    *v = bdl_v3_cross(n, *u);
}

/// The points where the plane through `point` with normal n cuts the edges of the box; returns
/// their number (at most 12).
static int plane_box_hits(bdl_vec3 point, bdl_vec3 n, bdl_vec3 lo, bdl_vec3 hi, bdl_vec3 hits[12])
{
    int count = 0;
    for (int k = 0; k < 8; ++k)
        for (int axis = 0; axis < 3; ++axis) {
            if (k & (1 << axis))
                continue;
            bdl_vec3 a = corner(lo, hi, k), b = corner(lo, hi, k | (1 << axis));
            double da = bdl_v3_dot(bdl_v3_sub(a, point), n);
            double db = bdl_v3_dot(bdl_v3_sub(b, point), n);
            if ((da <= 0.0 && db > 0.0) || (da > 0.0 && db <= 0.0) || (da == 0.0 && db == 0.0))
                hits[count++] =
                    bdl_v3_add(a, bdl_v3_scale(bdl_v3_sub(b, a), da == db ? 0.0 : da / (da - db)));
        }
    return count;
}

/// Sorts points of a plane with normal n by their angle about their centroid.
static void sort_around_centroid(bdl_vec3 n, bdl_vec3 *hits, int count)
{
    bdl_vec3 c = bdl_v3_zero();
    for (int k = 0; k < count; ++k)
        c = bdl_v3_add(c, hits[k]);
    c = bdl_v3_scale(c, 1.0 / count);
    bdl_vec3 u, v;
    basis(n, &u, &v);
    double angle[12];
    for (int k = 0; k < count; ++k) {
        bdl_vec3 q = bdl_v3_sub(hits[k], c);
        angle[k] = atan2(bdl_v3_dot(q, v), bdl_v3_dot(q, u));
    }
    for (int i = 1; i < count; ++i) // insertion sort by angle
        for (int j = i; j > 0 && angle[j] < angle[j - 1]; --j) {
            double ta = angle[j];
            angle[j] = angle[j - 1];
            angle[j - 1] = ta;
            bdl_vec3 th = hits[j];
            hits[j] = hits[j - 1];
            hits[j - 1] = th;
        }
}

/// The polygon where a plane cuts the domain box.
static void push_plane(bdl_render_outlines *o, bdl_vec3 point, bdl_vec3 n, bdl_vec3 lo, bdl_vec3 hi)
{
    bdl_vec3 hits[12];
    int count = plane_box_hits(point, n, lo, hi, hits);
    if (count < 3)
        return;
    sort_around_centroid(n, hits, count);
    for (int k = 0; k < count; ++k)
        push_segment(o, hits[k], hits[(k + 1) % count]);
}

static void push_circle(bdl_render_outlines *o, bdl_vec3 c, bdl_vec3 u, bdl_vec3 v, double radius)
{
    for (int s = 0; s < CIRCLE_SEGS; ++s) {
        double a = 2.0 * BDL_PI * s / CIRCLE_SEGS, b = 2.0 * BDL_PI * (s + 1) / CIRCLE_SEGS;
        push_segment(o,
                     bdl_v3_add(c, bdl_v3_add(bdl_v3_scale(u, radius * cos(a)),
                                              bdl_v3_scale(v, radius * sin(a)))),
                     bdl_v3_add(c, bdl_v3_add(bdl_v3_scale(u, radius * cos(b)),
                                              bdl_v3_scale(v, radius * sin(b)))));
    }
}

/// Circles where the cylinder leaves the domain box, and four lines along it.
static void push_cylinder(bdl_render_outlines *o, bdl_vec3 point, bdl_vec3 axis, double radius,
                          bdl_vec3 lo, bdl_vec3 hi)
{
    double t0 = INFINITY, t1 = -INFINITY;
    for (int k = 0; k < 8; ++k) {
        double t = bdl_v3_dot(bdl_v3_sub(corner(lo, hi, k), point), axis);
        t0 = fmin(t0, t);
        t1 = fmax(t1, t);
    }
    bdl_vec3 u, v;
    basis(axis, &u, &v);
    for (int end = 0; end < 2; ++end)
        push_circle(o, bdl_v3_add(point, bdl_v3_scale(axis, end ? t1 : t0)), u, v, radius);
    for (int s = 0; s < 4; ++s) {
        bdl_vec3 off = bdl_v3_scale(s & 1 ? v : u, s & 2 ? -radius : radius);
        push_segment(o, bdl_v3_add(bdl_v3_add(point, bdl_v3_scale(axis, t0)), off),
                     bdl_v3_add(bdl_v3_add(point, bdl_v3_scale(axis, t1)), off));
    }
}

/// A mesh wall's feature edges: its borders and the folds sharper than 20 degrees (a cone reads
/// by its rim and its outlet, not by every facet). Nothing is drawn when the file cannot be read
/// (the scene check has named the reason already).
static void push_mesh(bdl_render_outlines *o, const bdl_wall_def *d)
{
    bdl_mesh m;
    char why[400];
    if (bdl_mesh_read(d->file, &m, why, sizeof why) != BDL_OK)
        return;
    bdl_mesh_transform(&m, d->scale, d->rotate, d->translate);
    int32_t(*side)[2] = malloc((size_t)m.edge_count * sizeof *side);
    if (side) {
        for (long e = 0; e < m.edge_count; ++e)
            side[e][0] = side[e][1] = -1;
        for (long t = 0; t < m.tri_count; ++t)
            for (int k = 0; k < 3; ++k)
                side[m.tri_edge[t][k]][side[m.tri_edge[t][k]][0] < 0 ? 0 : 1] = (int32_t)t;
        for (long e = 0; e < m.edge_count; ++e) {
            int fold = side[e][1] < 0;
            if (!fold) {
                bdl_vec3 n[2];
                for (int k = 0; k < 2; ++k) {
                    const int32_t *t = m.tri[side[e][k]];
                    n[k] =
                        bdl_v3_normalize(bdl_v3_cross(bdl_v3_sub(m.vertex[t[1]], m.vertex[t[0]]),
                                                      bdl_v3_sub(m.vertex[t[2]], m.vertex[t[0]])));
                }
                fold = fabs(bdl_v3_dot(n[0], n[1])) < cos(20.0 * BDL_PI / 180.0);
            }
            if (fold)
                push_segment(o, m.vertex[m.edge[e][0]], m.vertex[m.edge[e][1]]);
        }
        free(side);
    }
    bdl_mesh_free(&m);
}

/// A disk's rim and hole; a cone's two circles and four lines down its side.
static void push_round(bdl_render_outlines *o, const bdl_wall_def *d)
{
    bdl_vec3 u, v;
    const bdl_vec3 a = bdl_v3_normalize(d->normal);
    basis(a, &u, &v);
    if (d->kind == BDL_WALL_DISK) {
        push_circle(o, d->point, u, v, d->radius);
        if (d->hole_radius > 0.0)
            push_circle(o, d->point, u, v, d->hole_radius);
        return;
    }
    const bdl_vec3 top = bdl_v3_madd(d->point, a, d->height);
    push_circle(o, d->point, u, v, d->radius);
    if (d->radius_top > 0.0)
        push_circle(o, top, u, v, d->radius_top);
    for (int s = 0; s < 4; ++s) {
        const bdl_vec3 dir = bdl_v3_scale(s & 1 ? v : u, s & 2 ? -1.0 : 1.0);
        push_segment(o, bdl_v3_madd(d->point, dir, d->radius),
                     bdl_v3_madd(top, dir, d->radius_top));
    }
}

void bdl_render_outlines_build(bdl_renderer *r)
{
    const bdl_scene *s = &r->scene;
    bdl_render_outlines *o = &r->outlines;
    o->groups[0] = (bdl_line_group){-1, 0, 0};
    push_box(o, s->domain_min, s->domain_max);
    o->groups[0].count = o->line_count;
    o->group_count = 1;
    for (int w = 0; w < s->wall_count; ++w) {
        const bdl_wall_def *d = &s->walls[w];
        int first = o->line_count;
        if (d->kind == BDL_WALL_BOX)
            push_box(o, d->box_min, d->box_max);
        else if (d->kind == BDL_WALL_PLANE)
            push_plane(o, d->point, d->normal, s->domain_min, s->domain_max);
        else if (d->kind == BDL_WALL_MESH)
            push_mesh(o, d);
        else if (d->kind == BDL_WALL_DISK || d->kind == BDL_WALL_CONE)
            push_round(o, d);
        else
            push_cylinder(o, d->point, d->normal, d->radius, s->domain_min, s->domain_max);
        o->groups[o->group_count++] = (bdl_line_group){w, first, o->line_count - first};
    }
}

int bdl_render_outlines_create(bdl_renderer *r, char *why, size_t why_len)
{
    bdl_render_outlines *o = &r->outlines;
    if (!bdl_gl_mesh_create(&o->mesh, "line.vert", "line.frag", why, why_len))
        return 0;
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)o->line_count * 3 * (GLsizeiptr)sizeof(float),
                 o->lines, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 12, (void *)0);
    return 1;
}

void bdl_render_outlines_destroy(bdl_renderer *r)
{
    bdl_render_outlines *o = &r->outlines;
    bdl_gl_mesh_destroy(&o->mesh);
    free(o->lines);
}

void bdl_render_outlines_draw(bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v,
                              const bdl_render_frame *f)
{
    const bdl_render_outlines *o = &r->outlines;
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(o->mesh.program);
    glBindVertexArray(o->mesh.vao);
    GLint offset_at = glGetUniformLocation(o->mesh.program, "u_view_proj");
    GLint color_at = glGetUniformLocation(o->mesh.program, "u_color");
    float light = v->background[0] + v->background[1] + v->background[2] < 1.5f;
    for (int g = 0; g < o->group_count; ++g) {
        const bdl_line_group *lg = &o->groups[g];
        mat4 m;
        memcpy(m, f->view_proj, sizeof m);
        if (lg->wall >= 0 && lg->wall < s->wall_count) {
            glm_translate(m, (float *)s->wall_offset[lg->wall]);
            const bdl_wall_def *d = &r->scene.walls[lg->wall];
            if (s->wall_angle[lg->wall] != 0.0f && d->motion == BDL_MOTION_ROTATE) {
                vec3 c = {(float)d->rotation_center.x, (float)d->rotation_center.y,
                          (float)d->rotation_center.z};
                vec3 a = {(float)d->rotation_axis.x, (float)d->rotation_axis.y,
                          (float)d->rotation_axis.z};
                glm_normalize(a);
                glm_rotate_at(m, c, s->wall_angle[lg->wall], a);
            }
        }
        glUniformMatrix4fv(offset_at, 1, GL_FALSE, (const float *)m);
        // The domain box is faint; walls are clearer.
        float a = lg->wall < 0 ? 0.35f : 0.8f;
        float c = light ? 0.85f : 0.25f;
        glUniform4f(color_at, c, c, c, a);
        glDrawArrays(GL_LINES, lg->first, lg->count);
    }
    glDisable(GL_BLEND);
}
