// bedlam — walls: planes, boxes and cylinders with prescribed motion.
//
// Every wall expands into primitives (a box into six inward-facing planes). A primitive
// moves rigidly with its wall: displacement s(t) = A sin(2 pi f (t - start) + phase) d along
// the unit direction d from the start time on (zero before), velocity s'(t). Contacts treat a wall
// as a body of infinite mass and radius (a cylinder's inside is concave: 1/R* = 1/r - 1/R_cyl).
#ifndef BDL_WALLS_H
#define BDL_WALLS_H

#include "core/vec3.h"
#include "dem/material.h"

#define BDL_MAX_WALLS 16
#define BDL_MAX_PRIMS (6 * BDL_MAX_WALLS)

/// Geometry of a wall ([wall NAME] type).
#define BDL_WALL_KINDS(X)                                                                          \
    X(WALL_PLANE, "plane", "half-space boundary: particles stay on the side `normal` points to")   \
    X(WALL_BOX, "box", "the inside of an axis-aligned box (six planes)")                           \
    X(WALL_CYLINDER, "cylinder", "the inside of a cylinder around an axis (infinite unless capped)")
BDL_CHOICES(bdl_wall_kind, BDL_WALL_KINDS);

/// Prescribed motion of a wall ([wall NAME] motion).
#define BDL_MOTIONS(X)                                                                             \
    X(MOTION_NONE, "none", "at rest")                                                              \
    X(MOTION_VIBRATE, "vibrate", "displacement A sin(2 pi f t + phase) along `direction`")
BDL_CHOICES(bdl_motion_kind, BDL_MOTIONS);

/// The frame a vibrating wall is seen from ([wall NAME] frame).
#define BDL_WALL_FRAMES(X)                                                                         \
    X(FRAME_LAB, "lab", "the wall moves through the fixed domain")                                 \
    X(FRAME_CONTAINER, "container",                                                                \
      "the whole container moves with it; the run is done in its frame")
BDL_CHOICES(bdl_wall_frame, BDL_WALL_FRAMES);

typedef struct bdl_wall_def {
    char name[BDL_NAME_LEN];
    bdl_wall_kind kind;
    bdl_vec3 point;            ///< plane: a point on it; cylinder: a point on the axis [m]
    bdl_vec3 normal;           ///< plane: unit normal into the particle side; cylinder: unit axis
    bdl_vec3 box_min, box_max; ///< box corners [m]
    double radius;             ///< cylinder radius [m]
    bdl_motion_kind motion;
    bdl_vec3 direction;    ///< vibration direction (unit)
    double amplitude;      ///< A [m]
    double frequency;      ///< f [Hz]
    double phase;          ///< [rad]
    double start;          ///< simulated time the vibration starts; still before [s]
    bdl_wall_frame frame;  ///< lab, or container (every wall and the gas grid move with this one)
    bdl_material material; ///< wall material; fields < 0 fall back to the particle species'
} bdl_wall_def;

typedef enum bdl_prim_kind { BDL_PRIM_PLANE, BDL_PRIM_CYLINDER } bdl_prim_kind;

typedef struct bdl_wall_prim {
    bdl_prim_kind kind;
    int wall;        ///< index of the wall it belongs to
    bdl_vec3 point;  ///< rest position of a point on the plane / axis [m]
    bdl_vec3 normal; ///< plane: unit normal into the particle side; cylinder: unit axis
    double radius;   ///< cylinder radius [m]
} bdl_wall_prim;

typedef struct bdl_walls {
    int prim_count;
    bdl_wall_prim prims[BDL_MAX_PRIMS];
    int wall_count;
    bdl_motion_kind motion[BDL_MAX_WALLS];
    bdl_vec3 direction[BDL_MAX_WALLS];
    double amplitude[BDL_MAX_WALLS], omega[BDL_MAX_WALLS], phase[BDL_MAX_WALLS];
    double start[BDL_MAX_WALLS]; ///< time the vibration starts [s]
    // Live values, refreshed by bdl_walls_update; scaled by the live amplitude factor of commands.
    bdl_vec3 offset[BDL_MAX_WALLS];   ///< displacement from rest [m]
    bdl_vec3 velocity[BDL_MAX_WALLS]; ///< [m/s]
} bdl_walls;

/// Expands `count` wall definitions into primitives, at rest at time 0.
void bdl_walls_build(const bdl_wall_def *defs, int count, bdl_walls *walls);

/// Sets offset and velocity of every wall at time t [s].
void bdl_walls_update(bdl_walls *walls, double t);

/// Distance-to-contact query. Returns the gap s = (distance from the surface) - radius along the
/// normal n pointing from the wall into the particle (s < 0: overlap -s), for a sphere at x.
static inline double bdl_wall_gap(const bdl_walls *walls, int prim, bdl_vec3 x, double radius,
                                  bdl_vec3 *n)
{
    const bdl_wall_prim *w = &walls->prims[prim];
    bdl_vec3 q = bdl_v3_sub(x, bdl_v3_add(w->point, walls->offset[w->wall]));
    if (w->kind == BDL_PRIM_PLANE) {
        *n = w->normal;
        return bdl_v3_dot(q, w->normal) - radius;
    }
    bdl_vec3 perp = bdl_v3_madd(q, w->normal, -bdl_v3_dot(q, w->normal));
    double rho = bdl_v3_len(perp);
    *n = rho > 0.0 ? bdl_v3_scale(perp, -1.0 / rho) : bdl_v3_zero();
    return w->radius - rho - radius;
}

/// Effective radius of a sphere of radius r touching primitive `prim`.
static inline double bdl_wall_r_eff(const bdl_walls *walls, int prim, double r)
{
    const bdl_wall_prim *w = &walls->prims[prim];
    if (w->kind == BDL_PRIM_CYLINDER && w->radius > r)
        return r * w->radius / (w->radius - r);
    return r;
}

/// Largest displacement any wall has made since the offsets in `ref` were taken [m].
double bdl_walls_max_shift(const bdl_walls *walls, const bdl_vec3 *ref);

/// Largest speed any wall reaches over a cycle [m/s].
double bdl_walls_max_speed(const bdl_walls *walls);

#endif
