// bedlam — the view a scene's [camera] asks for: what frames of a run show, and what the viewer
// starts from before its keys and mouse change it.
#include <string.h>

#include "render/renderer.h"

void bdl_view_from_scene(const bdl_scene *scene, float aspect, bdl_view *view)
{
    const bdl_camera_def *d = &scene->camera;
    memset(view, 0, sizeof *view);
    bdl_camera_from_scene(scene, &view->camera);
    if (view->camera.distance <= 0.0f) {
        float lo[3] = {(float)scene->domain_min.x, (float)scene->domain_min.y,
                       (float)scene->domain_min.z};
        float hi[3] = {(float)scene->domain_max.x, (float)scene->domain_max.y,
                       (float)scene->domain_max.z};
        bdl_camera_fit(&view->camera, lo, hi, aspect);
    }
    view->color = d->color;
    view->range_fixed = d->has_color_min && d->has_color_max;
    view->range[0] = (float)d->color_min;
    view->range[1] = (float)d->color_max;
    view->clip = d->clip;
    bdl_vec3 cp = d->has_clip_point ? d->clip_point
                                    : bdl_v3(view->camera.target[0], view->camera.target[1],
                                             view->camera.target[2]);
    view->clip_point[0] = (float)cp.x;
    view->clip_point[1] = (float)cp.y;
    view->clip_point[2] = (float)cp.z;
    view->clip_normal[0] = (float)d->clip_normal.x;
    view->clip_normal[1] = (float)d->clip_normal.y;
    view->clip_normal[2] = (float)d->clip_normal.z;
    view->lighting = d->lighting;
    view->overlay = d->overlay;
    view->outlines = d->outlines;
    view->background[0] = (float)d->background.x;
    view->background[1] = (float)d->background.y;
    view->background[2] = (float)d->background.z;
    view->gas_opacity = d->gas_field != BDL_GAS_FIELD_NONE ? (float)d->gas_opacity : 0.0f;
}
