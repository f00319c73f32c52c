#include "render/camera.h"

#include <cglm/cglm.h>
#include <math.h>
#include <string.h>

static float radians(float deg) { return deg * (float)(BDL_PI / 180.0); }

static void frame(const bdl_camera *cam, vec3 forward, vec3 right, vec3 up)
{
    float y = radians(cam->yaw), p = radians(cam->pitch);
    forward[0] = -sinf(y) * cosf(p);
    forward[1] = cosf(y) * cosf(p);
    forward[2] = -sinf(p);
    right[0] = cosf(y);
    right[1] = sinf(y);
    right[2] = 0.0f;
    glm_vec3_cross(right, forward, up);
}

void bdl_camera_preset(bdl_view_preset preset, bdl_camera *cam)
{
    static const float angles[][2] = {
        [BDL_VIEW_ISO] = {30.0f, 25.0f},
        [BDL_VIEW_FRONT] = {0.0f, 0.0f},
        [BDL_VIEW_SIDE] = {90.0f, 0.0f},
        [BDL_VIEW_TOP] = {0.0f, 90.0f},
    };
    cam->yaw = angles[preset][0];
    cam->pitch = angles[preset][1];
}

void bdl_camera_from_scene(const bdl_scene *scene, bdl_camera *cam)
{
    const bdl_camera_def *d = &scene->camera;
    memset(cam, 0, sizeof *cam);
    bdl_vec3 t = d->has_target
                     ? d->target
                     : bdl_v3_scale(bdl_v3_add(scene->domain_min, scene->domain_max), 0.5);
    cam->target[0] = (float)t.x;
    cam->target[1] = (float)t.y;
    cam->target[2] = (float)t.z;
    cam->fov = (float)d->fov;
    cam->ortho = d->projection == BDL_PROJ_ORTHOGRAPHIC;
    bdl_camera_preset(d->view, cam);
    if (d->has_yaw)
        cam->yaw = (float)d->yaw;
    if (d->has_pitch)
        cam->pitch = (float)d->pitch;
    cam->distance = (float)d->distance;
}

float bdl_camera_half_height(const bdl_camera *cam)
{
    return cam->distance * tanf(radians(0.5f * cam->fov));
}

void bdl_camera_fit(bdl_camera *cam, const float lo[3], const float hi[3], float aspect)
{
    vec3 f, r, u;
    frame(cam, f, r, u);
    float tan_half = tanf(radians(0.5f * cam->fov));
    float need = 0.0f;
    for (int k = 0; k < 8; ++k) {
        vec3 c = {(k & 1) ? hi[0] : lo[0], (k & 2) ? hi[1] : lo[1], (k & 4) ? hi[2] : lo[2]};
        vec3 q;
        glm_vec3_sub(c, (float *)cam->target, q);
        float x = fabsf(glm_vec3_dot(q, r)), y = fabsf(glm_vec3_dot(q, u));
        float toward = -glm_vec3_dot(q, f); // how far the corner is in front of the target
        // Orthographic: the half height must cover the corner; perspective: the corner's cone.
        // Across, the middle 82 % only: the colour bar and its labels take the right edge.
        float dx = x / (tan_half * aspect * 0.82f), dy = y / tan_half;
        float d = fmaxf(dx, dy) + (cam->ortho ? 0.0f : toward);
        need = fmaxf(need, d);
    }
    cam->distance = 1.06f * need;
}

void bdl_camera_matrices(const bdl_camera *cam, float aspect, float depth, float view[16],
                         float proj[16])
{
    vec3 f, r, u, eye;
    frame(cam, f, r, u);
    glm_vec3_scale(f, -cam->distance, eye);
    glm_vec3_add(eye, (float *)cam->target, eye);
    mat4 v, p;
    glm_lookat(eye, (float *)cam->target, u, v);
    float near_plane = fmaxf(cam->distance - depth, 1e-3f * cam->distance);
    float far_plane = cam->distance + depth;
    if (cam->ortho) {
        float h = bdl_camera_half_height(cam);
        glm_ortho(-h * aspect, h * aspect, -h, h, near_plane, far_plane, p);
    } else {
        glm_perspective(radians(cam->fov), aspect, near_plane, far_plane, p);
    }
    memcpy(view, v, sizeof v);
    memcpy(proj, p, sizeof p);
}

void bdl_camera_orbit(bdl_camera *cam, float dyaw, float dpitch)
{
    cam->yaw = fmodf(cam->yaw + dyaw, 360.0f);
    cam->pitch = fminf(90.0f, fmaxf(-90.0f, cam->pitch + dpitch));
}

void bdl_camera_pan(bdl_camera *cam, float right, float up)
{
    vec3 f, r, u;
    frame(cam, f, r, u);
    float h = bdl_camera_half_height(cam);
    for (int k = 0; k < 3; ++k)
        cam->target[k] += 2.0f * h * (right * r[k] + up * u[k]);
}

void bdl_camera_zoom(bdl_camera *cam, float factor) { cam->distance *= factor; }
