// bedlam — the particles as sphere impostors: one screen-space quad per sphere (a point sprite,
// or an instanced quad when a sphere outgrows the driver's point size), on which the fragment
// shader intersects the view ray with the sphere and writes the hit's depth. Spheres the
// occlusion culling proves hidden are left out of the instance buffer. A snapshot with rods'
// axes is drawn by capsules.c instead, after the same culling.
#include <cglm/cglm.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/memory.h"
#include "render/renderer_internal.h"

/// Bytes per instance: centre and radius as 4 floats, then the colour as 4 bytes.
#define INSTANCE_BYTES 20

/// The instance attributes (sphere, colour) of the bound vertex array, read from the bound
/// buffer; per instance, or per vertex for points.
static void instance_attributes(GLuint divisor)
{
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, INSTANCE_BYTES, (void *)0);
    if (divisor)
        glVertexAttribDivisor(0, divisor);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 4, GL_UNSIGNED_BYTE, GL_TRUE, INSTANCE_BYTES, (void *)16);
    if (divisor)
        glVertexAttribDivisor(1, divisor);
}

int bdl_render_particles_create(bdl_renderer *r, char *why, size_t why_len)
{
    bdl_render_particles *p = &r->particles;
    if (!bdl_gl_mesh_create(&p->mesh, "sphere.vert", "sphere.frag", why, why_len))
        return 0;
    instance_attributes(1);
    // The same buffer as one point per particle.
    glGenVertexArrays(1, &p->point_vao);
    glBindVertexArray(p->point_vao);
    instance_attributes(0);
    GLfloat range[2] = {1.0f, 1.0f};
    glGetFloatv(GL_POINT_SIZE_RANGE, range);
    p->point_max = range[1];
    return 1;
}

void bdl_render_particles_destroy(bdl_renderer *r)
{
    bdl_render_particles *p = &r->particles;
    if (p->point_vao)
        glDeleteVertexArrays(1, &p->point_vao);
    bdl_gl_mesh_destroy(&p->mesh);
    bdl_cull_free(&p->cull);
    free(p->visible);
    free(p->instances);
}

/// Room for n particles' visibility, and for their sphere instances unless they are capsules.
static int reserve(bdl_render_particles *p, long n, int spheres)
{
    if (n > p->visible_capacity) {
        uint8_t *a = realloc(p->visible, (size_t)n);
        if (!a)
            return 0;
        p->visible = a;
        p->visible_capacity = n;
    }
    if (!spheres || n <= p->instance_capacity)
        return 1;
    const long cap = n + n / 4 + 64;
    if (!bdl_grow((void **)&p->instances, cap, INSTANCE_BYTES))
        return 0;
    p->instance_capacity = cap;
    return 1;
}

/// Marks the particles that may show a pixel: in front of the clipping plane, on screen and not
/// hidden behind nearer ones.
static void cull(bdl_render_particles *p, const bdl_snapshot *s, const bdl_view *v,
                 const bdl_render_frame *f)
{
    if (v->no_culling) {
        memset(p->visible, 1, (size_t)s->count);
        return;
    }
    float clip[4];
    const float *n = v->clip_normal, *q = v->clip_point;
    clip[0] = n[0], clip[1] = n[1], clip[2] = n[2];
    clip[3] = -(n[0] * q[0] + n[1] * q[1] + n[2] * q[2]);
    bdl_cull_particles(&p->cull, s->pos, s->radius, s->axis, s->count, f->view, f->proj,
                       v->camera.ortho, f->width, f->height, v->clip ? clip : NULL, p->visible);
}

/// Writes the instance data of the visible particles; returns their number.
static long fill_instances(bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v)
{
    bdl_render_particles *p = &r->particles;
    float rmax = 0.0f;
    long m = 0;
    for (long i = 0; i < s->count; ++i) {
        if (!p->visible[i])
            continue;
        rmax = fmaxf(rmax, s->radius[i]);
        uint8_t *out = &p->instances[INSTANCE_BYTES * m++];
        float sphere[4] = {s->pos[3 * i], s->pos[3 * i + 1], s->pos[3 * i + 2], s->radius[i]};
        memcpy(out, sphere, 16);
        bdl_render_colors_particle(r, s, v, i, out + 16);
        out[19] = 255;
    }
    p->max_radius = rmax;
    return m;
}

/// Whether every sphere fits in a point sprite: its projected size, bounded from the nearest
/// particle depth, with room for the stretch of off-axis spheres in perspective.
static int points_fit(const bdl_render_particles *p, const bdl_snapshot *s, const bdl_view *v,
                      const float *view, int height)
{
    float half = bdl_camera_half_height(&v->camera);
    float ppm = 0.5f * (float)height / half; // pixels per metre at the target's depth
    float size;
    if (v->camera.ortho) {
        size = 2.0f * p->max_radius * ppm;
    } else {
        float nearest = INFINITY;
        for (long i = 0; i < s->count; ++i) {
            const float *x = &s->pos[3 * i];
            float z = -(view[2] * x[0] + view[6] * x[1] + view[10] * x[2] + view[14]);
            nearest = fminf(nearest, z);
        }
        float depth = nearest - p->max_radius;
        if (!(depth > 0.0f))
            return 0;
        size = 2.0f * 1.5f * p->max_radius * ppm * v->camera.distance / depth;
    }
    return size + 2.0f < p->point_max;
}

/// The light comes from above-left of the viewer (view space, towards the light).
static void light_direction(float l[3])
{
    vec3 d = {-0.35f, 0.55f, 0.76f};
    glm_vec3_normalize(d);
    memcpy(l, d, sizeof d);
}

void bdl_shade(const float base[3], const float n[3], const float view[3], float out[3])
{
    float l[3];
    light_direction(l);
    vec3 h = {l[0] + view[0], l[1] + view[1], l[2] + view[2]};
    glm_vec3_normalize(h);
    float diffuse = fmaxf(n[0] * l[0] + n[1] * l[1] + n[2] * l[2], 0.0f);
    float specular = powf(fmaxf(n[0] * h[0] + n[1] * h[1] + n[2] * h[2], 0.0f), 48.0f);
    for (int k = 0; k < 3; ++k)
        out[k] = base[k] * (0.35f + 0.65f * diffuse) + 0.22f * specular;
}

void bdl_render_particle_uniforms(GLuint prog, const bdl_view *v, const bdl_render_frame *f,
                                  int points)
{
    glUseProgram(prog);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_view"), 1, GL_FALSE, f->view);
    glUniformMatrix4fv(glGetUniformLocation(prog, "u_proj"), 1, GL_FALSE, f->proj);
    glUniform1i(glGetUniformLocation(prog, "u_ortho"), v->camera.ortho);
    glUniform2f(glGetUniformLocation(prog, "u_viewport"), (float)f->width, (float)f->height);
    glUniform1i(glGetUniformLocation(prog, "u_lighting"), v->lighting);
    glUniform1i(glGetUniformLocation(prog, "u_clip_on"), v->clip);
    const float *n = v->clip_normal, *q = v->clip_point;
    glUniform4f(glGetUniformLocation(prog, "u_clip"), n[0], n[1], n[2],
                -(n[0] * q[0] + n[1] * q[1] + n[2] * q[2]));
    vec3 light;
    light_direction(light);
    glUniform3f(glGetUniformLocation(prog, "u_light"), light[0], light[1], light[2]);
    glUniform1i(glGetUniformLocation(prog, "u_points"), points);
}

static void draw_spheres(bdl_render_particles *p, const bdl_snapshot *s, long count,
                         const bdl_view *v, const bdl_render_frame *f)
{
    int points = points_fit(p, s, v, f->view, f->height);
    bdl_render_particle_uniforms(p->mesh.program, v, f, points);
    glBindBuffer(GL_ARRAY_BUFFER, p->mesh.vbo);
    // Storage is reallocated only when the particles outgrow it: a fresh allocation each frame
    // costs page faults in a software driver.
    if (count > p->vbo_capacity) {
        p->vbo_capacity = count + count / 4;
        glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)p->vbo_capacity * INSTANCE_BYTES, NULL,
                     GL_DYNAMIC_DRAW);
    }
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)count * INSTANCE_BYTES, p->instances);
    if (points) {
        glEnable(GL_PROGRAM_POINT_SIZE);
        glBindVertexArray(p->point_vao);
        glDrawArrays(GL_POINTS, 0, (GLsizei)count);
    } else {
        glBindVertexArray(p->mesh.vao);
        glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, (GLsizei)count);
    }
}

long bdl_render_particles_draw(bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v,
                               const bdl_render_frame *f)
{
    bdl_render_particles *p = &r->particles;
    if (s->count <= 0 || !reserve(p, s->count, s->axis == NULL))
        return 0;
    cull(p, s, v, f);
    bdl_render_colors_prepare(r, s, v);
    if (s->axis)
        return bdl_render_capsules_draw(r, s, v, f);
    long count = fill_instances(r, s, v);
    if (count > 0)
        draw_spheres(p, s, count, v, f);
    return count;
}
