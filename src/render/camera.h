// bedlam — an orbit camera: a target point, a distance, yaw and pitch, a projection.
//
// Forward (eye to target) is f = (-sin(yaw) cos(pitch), cos(yaw) cos(pitch), -sin(pitch)): yaw 0
// looks along +y, yaw 90 along -x, and a positive pitch puts the eye above the target. +z is up
// on screen. The orthographic projection shows a height of 2 distance tan(fov/2), the height the
// perspective one shows at the target, so switching between them keeps the framing.
#ifndef BDL_CAMERA_H
#define BDL_CAMERA_H

#include "scene/scene.h"

typedef struct bdl_camera {
    float target[3]; ///< [m]
    float distance;  ///< eye to target [m]; 0 = fit the box given to bdl_camera_fit
    float yaw;       ///< [deg]
    float pitch;     ///< [deg], within [-90, 90]
    float fov;       ///< vertical field of view [deg]
    int ortho;       ///< orthographic projection
} bdl_camera;

/// The scene's [camera]: the view preset, then any yaw, pitch, target, distance given.
void bdl_camera_from_scene(const bdl_scene *scene, bdl_camera *cam);
/// Yaw and pitch of a preset (the target, distance and projection stay).
void bdl_camera_preset(bdl_view_preset preset, bdl_camera *cam);
/// Sets the distance so the box [lo, hi] fills the view at this aspect (width / height).
void bdl_camera_fit(bdl_camera *cam, const float lo[3], const float hi[3], float aspect);

/// View and projection matrices (column-major, as OpenGL wants them). Near and far planes are
/// chosen from the distance and `depth` (the size of the scene [m]).
void bdl_camera_matrices(const bdl_camera *cam, float aspect, float depth, float view[16],
                         float proj[16]);
/// Half the visible height at the target [m].
float bdl_camera_half_height(const bdl_camera *cam);

void bdl_camera_orbit(bdl_camera *cam, float dyaw, float dpitch); ///< [deg]
/// Moves the target by a fraction of the visible height, right and up on screen.
void bdl_camera_pan(bdl_camera *cam, float right, float up);
void bdl_camera_zoom(bdl_camera *cam, float factor); ///< distance *= factor

#endif
