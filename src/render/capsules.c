// bedlam — the particles of a scene with rods as capsule impostors: each one the points within r
// of the segment x +- a (a sphere when a = 0), drawn as the front faces of a box that holds it,
// on which the fragment shader intersects the view ray with the capsule and writes the hit's
// depth (shaders/capsule.vert, capsule.frag). Its own instance buffer, so that scenes of spheres
// keep theirs (particles.c) as they are.
#include <stdlib.h>
#include <string.h>

#include "core/memory.h"
#include "render/renderer_internal.h"

/// Bytes per instance: centre and radius as 4 floats, the half shaft as 3, the colour as 4 bytes.
#define CAPSULE_BYTES 32

/// The vertices of one box: a triangle strip round a cube (shaders/capsule.vert).
#define BOX_VERTICES 14

int bdl_render_capsules_create(bdl_renderer *r, char *why, size_t why_len)
{
    bdl_render_capsules *c = &r->capsules;
    if (!bdl_gl_mesh_create(&c->mesh, "capsule.vert", "capsule.frag", why, why_len))
        return 0;
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, CAPSULE_BYTES, (void *)0);
    glVertexAttribDivisor(0, 1);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, CAPSULE_BYTES, (void *)16);
    glVertexAttribDivisor(1, 1);
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, CAPSULE_BYTES, (void *)28);
    glVertexAttribDivisor(2, 1);
    return 1;
}

void bdl_render_capsules_destroy(bdl_renderer *r)
{
    bdl_gl_mesh_destroy(&r->capsules.mesh);
    free(r->capsules.instances);
}

static int reserve(bdl_render_capsules *c, long n)
{
    if (n <= c->instance_capacity)
        return 1;
    const long cap = n + n / 4 + 64;
    if (!bdl_grow((void **)&c->instances, cap, CAPSULE_BYTES))
        return 0;
    c->instance_capacity = cap;
    return 1;
}

/// Writes the instance data of the particles the culling left visible; returns their number.
static long fill_instances(bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v)
{
    const uint8_t *visible = r->particles.visible;
    long m = 0;
    for (long i = 0; i < s->count; ++i) {
        if (!visible[i])
            continue;
        uint8_t *out = &r->capsules.instances[CAPSULE_BYTES * m++];
        const float *x = &s->pos[3 * i], *a = &s->axis[3 * i];
        float shape[7] = {x[0], x[1], x[2], s->radius[i], a[0], a[1], a[2]};
        memcpy(out, shape, sizeof shape);
        bdl_render_colors_particle(r, s, v, i, out + 28);
        out[31] = 255;
    }
    return m;
}

long bdl_render_capsules_draw(bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v,
                              const bdl_render_frame *f)
{
    bdl_render_capsules *c = &r->capsules;
    if (!reserve(c, s->count))
        return 0;
    long count = fill_instances(r, s, v);
    if (count == 0)
        return 0;
    bdl_render_particle_uniforms(c->mesh.program, v, f, 0);
    glBindBuffer(GL_ARRAY_BUFFER, c->mesh.vbo);
    // Storage is reallocated only when the particles outgrow it (as for spheres).
    if (count > c->vbo_capacity) {
        c->vbo_capacity = count + count / 4;
        glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)c->vbo_capacity * CAPSULE_BYTES, NULL,
                     GL_DYNAMIC_DRAW);
    }
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)count * CAPSULE_BYTES, c->instances);
    // Only the faces towards the eye: they cover the box's projection once, and lie in front of
    // the capsule, as the shader's conservative depth says.
    glEnable(GL_CULL_FACE);
    glBindVertexArray(c->mesh.vao);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, BOX_VERTICES, (GLsizei)count);
    glDisable(GL_CULL_FACE);
    return count;
}
