// bedlam — synthetic camera (DIA) images with exact ground truth.
//
// A camera looks at the particles as a digital image analysis (DIA) rig would: through the front
// wall of a pseudo-2D bed, front-lit (bright particles on a dark background) or back-lit
// (silhouettes on a bright one). Images are ray-cast on the CPU, particle by particle (spheres,
// and rods as capsules), with several rays per pixel: the same code gives the image and,
// exactly, which particle every ray hit, so the ground truth beside each image (which particles
// are visible, the covered area per image cell, the solids fraction behind it, the velocities PIV
// should find) is computed rather than estimated.
//
// Image coordinates: column u to the right, row v down, pixel (i, j) covers [i, i+1) x [j, j+1)
// and its centre is (i + 0.5, j + 0.5). World to pixel is bdl_dia_project; pixel to world (on a
// plane of given depth) is bdl_dia_unproject; both exact.
#ifndef BDL_DIA_H
#define BDL_DIA_H

#include <stdint.h>

#include "core/error.h"
#include "core/vec3.h"
#include "scene/scene.h"

// The projections and the lightings (front: lights on the camera's side, bright spheres on a dark
// background; back: a light panel behind the bed, dark silhouettes on a bright background) are
// the scene's choices: bdl_dia_projection and bdl_dia_lighting in scene/scene.h.

#define BDL_DIA_MAX_LIGHTS 4

typedef struct bdl_dia_def {
    bdl_dia_projection projection;
    bdl_vec3 position;   ///< perspective: the pinhole; orthographic: the centre of the view [m]
    bdl_vec3 target;     ///< the point the optical axis goes through [m]
    bdl_vec3 up;         ///< world direction that appears up in the image
    int width, height;   ///< [px]
    double pixel_size;   ///< orthographic: metres per pixel at the object; perspective: the
                         ///< sensor's pixel pitch [m]
    double focal_length; ///< perspective only [m]
    int samples;         ///< rays per pixel along each axis (samples^2 per pixel)
    bdl_dia_lighting lighting;
    int light_count;
    bdl_vec3 light_position[BDL_DIA_MAX_LIGHTS]; ///< point lights (front-lit) [m]
    double light_intensity[BDL_DIA_MAX_LIGHTS];  ///< [-], 1 = full scale on a surface facing it
    double ambient;                              ///< light every visible surface gets [-]
    double dark;        ///< front-lit: the background; back-lit: a silhouette [0, 1]
    double bright;      ///< front-lit: a fully lit surface; back-lit: the light panel [0, 1]
    double fade_start;  ///< front-lit: depth where the light starts to fade [m]
    double fade_length; ///< front-lit: e-folding depth of the fade behind fade_start [m]; 0 none
                        ///< (particles behind the front layer get less light, as in a bed)
    double blur;        ///< Gaussian defocus blur, sigma [px]; 0 none
    double noise;       ///< sensor noise, sigma as a fraction of full scale
    double gamma;       ///< stored value = linear^(1/gamma)
    int bits;           ///< 8 or 16 bits per pixel
    uint64_t seed;      ///< for the noise
} bdl_dia_def;

/// The camera's frame, derived from its definition.
typedef struct bdl_dia_camera {
    bdl_dia_def def;
    bdl_vec3 right, down, forward; ///< unit image axes in the world
} bdl_dia_camera;

/// Derives the frame; BDL_ERR_SCENE when target = position or up is parallel to the view.
bdl_result bdl_dia_camera_init(bdl_dia_camera *c, const bdl_dia_def *def);

/// World point to continuous pixel coordinates (u right, v down) and its depth along the optical
/// axis [m] (distance in front of the pinhole, or along forward from position when orthographic).
void bdl_dia_project(const bdl_dia_camera *c, bdl_vec3 x, double *u, double *v, double *depth);
/// Pixel coordinates and a depth back to the world point (the exact inverse of bdl_dia_project).
bdl_vec3 bdl_dia_unproject(const bdl_dia_camera *c, double u, double v, double depth);
/// Metres per pixel at a given depth (constant when orthographic).
double bdl_dia_scale(const bdl_dia_camera *c, double depth);

/// What the particles are, for imaging: positions, radii, velocities, ids, and in scenes with rods
/// the rods' axes. A rod is a capsule (spherocylinder): the points within its radius of the segment
/// pos -/+ half_length axis.
typedef struct bdl_dia_scene {
    long count;
    const bdl_vec3 *pos, *vel;
    const double *radius;
    const uint32_t *id;
    const bdl_vec3 *axis;      ///< with rods: each particle's unit axis; else NULL
    const double *half_length; ///< with rods: half the shaft length, 0 for spheres [m]; else NULL
} bdl_dia_scene;

/// Area of particle i's outline in the image, in samples (samples^2 per pixel): a sphere's disc
/// pi r^2 at the depth of its centre; a capsule's adds the shaft's side view 2 r 2 h |u x sight|,
/// the sight line being the view direction (orthographic) or the ray to the centre (perspective).
double bdl_dia_outline_area(const bdl_dia_camera *c, const bdl_dia_scene *s, long i, int samples);

/// A rendered image and, per sample, which particle it shows.
typedef struct bdl_dia_image {
    int width, height, samples;
    float *value;  ///< width x height grey values in [0, 1], linear light, before blur and noise
    int32_t *hit;  ///< (width samples) x (height samples): particle index, -1 for background
    float *depth;  ///< per sample, the depth of the hit [m]
    double *final; ///< width x height: after blur, gamma and noise, in [0, 1]
} bdl_dia_image;

void bdl_dia_image_free(bdl_dia_image *im);

/// Ray-casts the particles (spheres, and capsules exactly: dia/capsule.h); `frame` varies the noise
/// from image to image.
bdl_result bdl_dia_render(const bdl_dia_camera *c, const bdl_dia_scene *s, long frame,
                          bdl_dia_image *im);

/// Writes the final image as an 8- or 16-bit grey PNG, atomically.
bdl_result bdl_dia_write_png(const bdl_dia_image *im, int bits, const char *path);

/// Ground truth on a grid of image cells (cells[0] across, cells[1] down, each covering a block
/// of pixels), between the depths front and back [m] (the bed's walls along the view).
typedef struct bdl_dia_cell_truth {
    double u0, v0, u1, v1;  ///< the cell in pixels
    double area_fraction;   ///< covered samples / samples: the visible 2D solids fraction
    double solids_depth;    ///< 3D solids fraction over the whole depth (front to back)
    double solids_layer;    ///< 3D solids fraction over the first layer (front to front + d)
    long visible_particles; ///< particles with at least one visible sample here
    bdl_vec3 velocity;      ///< mean velocity of what is seen, weighted by visible samples [m/s]
    double du, dv;          ///< the same projected on the image [px/s]
} bdl_dia_cell_truth;

typedef struct bdl_dia_truth_def {
    int cells[2];
    double front, back; ///< depths of the front and back walls along the view [m]
    double layer;       ///< depth of the first layer [m] (a particle diameter)
} bdl_dia_truth_def;

/// Cell truth (cells[0] x cells[1], row by row from the top) and, per particle, the number of
/// samples where it is visible (`visible`, count entries). Either output may be NULL. Solids:
/// spheres by bdl_dia_sphere_box_volume, capsules by bdl_dia_capsule_grid_volume (dia/capsule.h).
bdl_result bdl_dia_truth(const bdl_dia_camera *c, const bdl_dia_scene *s, const bdl_dia_image *im,
                         const bdl_dia_truth_def *t, bdl_dia_cell_truth *cells, long *visible);

/// Volume of the sphere (centre x, radius r) inside the box lo..hi [m^3], by Gauss-Legendre
/// quadrature in angle variables (exact to ~1e-6 of the sphere for any cut).
double bdl_dia_sphere_box_volume(bdl_vec3 x, double r, bdl_vec3 lo, bdl_vec3 hi);

#endif
