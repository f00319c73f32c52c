// bedlam — walls: planes, boxes and cylinders with prescribed motion.
//
// Every wall expands into primitives (a box into six inward-facing planes). A primitive
// moves rigidly with its wall: displacement s(t) = A sin(2 pi f (t - start) + phase) d along
// the unit direction d from the start time on (zero before), velocity s'(t). Contacts treat a wall
// as a body of infinite mass and radius (a cylinder's inside is concave: 1/R* = 1/r - 1/R_cyl).
//
// A mesh wall (core/mesh.h) adds its triangles as surfaces after the primitives: surface index
// prim_count + t is triangle t. A triangle is two-sided; a sphere touches it at the point of the
// triangle nearest its centre, which lies on the face, on one of its edges or at a vertex (the
// feature), with the normal from that point to the centre. A sphere near a join of triangles
// overlaps several of them in one patch: touched triangles that share a vertex and meet flat or
// convex (as the sphere sees them) form a patch, and each patch pushes once, through its
// deepest contact (bdl_wall_tri_counted); a concave join, as in the corner of a box, parts two
// patches. So a sphere rolling over a flat mesh feels the plane throughout, a ridge is felt as
// its edge, a vertex as its point, a corner of a box as its two faces. Triangles are binned per
// mesh wall in its rest frame for the neighbour search.
//
// A triangle wall (mesh, disk, cone) may turn about any axis: its turned angle is state, advanced
// by the live rate each step (bdl_walls_turn) and saved in checkpoints. A sphere is looked at
// from the wall's own frame (its centre turned back by the angle), so the triangles and their
// bins stay at rest; normals are turned forward into the lab. A turn sweeps the surface by at
// most the farthest vertex's distance from the axis times the angle, which the neighbour lists
// count as the wall's shift.
#ifndef BDL_WALLS_H
#define BDL_WALLS_H

#include <stdint.h>

#include "core/error.h"
#include "core/quat.h"
#include "core/vec3.h"
#include "dem/material.h"
#include "core/mesh.h"

#define BDL_MAX_WALLS 16
#define BDL_MAX_PRIMS (6 * BDL_MAX_WALLS)

/// Geometry of a wall ([wall NAME] type).
#define BDL_WALL_KINDS(X)                                                                          \
    X(WALL_PLANE, "plane", "half-space boundary: particles stay on the side `normal` points to")   \
    X(WALL_BOX, "box", "the inside of an axis-aligned box (six planes)")                           \
    X(WALL_CYLINDER, "cylinder",                                                                   \
      "the inside of a cylinder around an axis (infinite unless capped)")                          \
    X(WALL_MESH, "mesh", "triangles from an STL or OBJ file, touched from either side")            \
    X(WALL_DISK, "disk", "a flat disk, or a ring with a hole (an orifice plate), finite")          \
    X(WALL_CONE, "cone", "the side of a cone or frustum, or of a finite tube, open at both ends")
BDL_CHOICES(bdl_wall_kind, BDL_WALL_KINDS);

/// Prescribed motion of a wall ([wall NAME] motion).
#define BDL_MOTIONS(X)                                                                             \
    X(MOTION_NONE, "none", "at rest")                                                              \
    X(MOTION_VIBRATE, "vibrate", "displacement A sin(2 pi f t + phase) along `direction`")         \
    X(MOTION_MOVE, "move", "moves at a constant velocity from `start` to `stop` (a piston)")       \
    X(MOTION_ROTATE, "rotate",                                                                     \
      "turns about an axis at a constant rate: a mesh, disk or cone about any axis (a mixer "      \
      "blade); a cylinder about its own axis (a drum), a plane about its normal")
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
    double radius;             ///< cylinder radius; disk: outer; cone: of the base circle [m]
    double hole_radius;        ///< disk: radius of the hole (0: none) [m]
    double radius_top;         ///< cone: radius of the top circle [m]
    double height;             ///< cone: from the base circle to the top one along axis [m]
    int segments;              ///< disk, cone: sides of the polygons the circles are
    char file[BDL_PATH_LEN];   ///< mesh: STL or OBJ file
    double scale;              ///< mesh: factor on the file's coordinates (to metres)
    bdl_vec3 rotate;           ///< mesh: angles about x, then y, then z [degrees]
    bdl_vec3 translate;        ///< mesh: shift after scaling and rotating [m]
    double open_time;          ///< simulated time the wall is taken away (INFINITY: never) [s]
    bdl_vec3 velocity;         ///< move: velocity [m/s]
    double stop;               ///< move: simulated time the motion ends (INFINITY: never) [s]
    bdl_vec3 rotation_axis;    ///< rotate: unit axis (right hand)
    bdl_vec3 rotation_center;  ///< rotate: a point on the axis [m]
    double angular_velocity;   ///< rotate: rate [rad/s]
    bdl_motion_kind motion;
    bdl_vec3 direction;    ///< vibration direction (unit)
    double amplitude;      ///< A [m]
    double frequency;      ///< f [Hz]
    double phase;          ///< [rad]
    double start;          ///< simulated time the vibration starts; still before [s]
    bdl_wall_frame frame;  ///< lab, or container (every wall and the gas grid move with this one)
    bdl_material material; ///< wall material; fields < 0 fall back to the particle species'
    int periodic[3];       ///< triangle walls: repeats along these periodic axes of the domain
} bdl_wall_def;

typedef enum bdl_prim_kind { BDL_PRIM_PLANE, BDL_PRIM_CYLINDER } bdl_prim_kind;

typedef struct bdl_wall_prim {
    bdl_prim_kind kind;
    int wall;        ///< index of the wall it belongs to
    bdl_vec3 point;  ///< rest position of a point on the plane / axis [m]
    bdl_vec3 normal; ///< plane: unit normal into the particle side; cylinder: unit axis
    double radius;   ///< cylinder radius [m]
} bdl_wall_prim;

/// A triangle of a mesh wall, at rest, with the welded ids of its vertices (global over all
/// meshes: triangles that share a vertex id meet there).
typedef struct bdl_wall_tri {
    bdl_vec3 a, b, c;
    bdl_vec3 normal; ///< unit, (b - a) x (c - a) normalised
    int32_t wall;
    int32_t vert[3];
} bdl_wall_tri;

/// The triangles of one mesh wall in cubic bins (rest frame): a bin lists every triangle that
/// comes within `reach` of it.
typedef struct bdl_wall_bins {
    bdl_vec3 lo;
    double size;
    int dims[3];
    int32_t *start; ///< bins + 1 offsets into tri
    int32_t *tri;
} bdl_wall_bins;

typedef struct bdl_walls {
    int prim_count;
    bdl_wall_prim prims[BDL_MAX_PRIMS];
    long tri_count, vertex_count;
    bdl_wall_tri *tri;                 ///< surfaces prim_count .. prim_count + tri_count - 1
    bdl_wall_bins bins[BDL_MAX_WALLS]; ///< of mesh walls (start NULL for the others)
    int wall_count;
    bdl_motion_kind motion[BDL_MAX_WALLS];
    bdl_vec3 direction[BDL_MAX_WALLS];
    double amplitude[BDL_MAX_WALLS], omega[BDL_MAX_WALLS], phase[BDL_MAX_WALLS];
    double start[BDL_MAX_WALLS];     ///< time the vibration starts [s]
    double open_time[BDL_MAX_WALLS]; ///< time the wall is taken away [s]
    bdl_vec3 center[BDL_MAX_WALLS];  ///< rotate: a point on the axis [m]
    bdl_vec3 turn[BDL_MAX_WALLS];    ///< rotate: axis times the rate (set, before live scaling)
    bdl_vec3 axis[BDL_MAX_WALLS];    ///< rotate: unit axis
    double radius[BDL_MAX_WALLS];    ///< rotate: the cylinder's radius, or a triangle wall's
                                     ///< farthest vertex from the axis (0 for a plane) [m]
    uint8_t turns[BDL_MAX_WALLS];    ///< rotate: a triangle wall, whose triangles turn with it
    double angle[BDL_MAX_WALLS];     ///< rotate: the angle turned since the start (state) [rad]
    bdl_quat turned[BDL_MAX_WALLS];  ///< rotate: the turn by `angle` about the axis
    bdl_vec3 spin[BDL_MAX_WALLS];    ///< live angular velocity (zero before the start) [rad/s]
    bdl_vec3 drive[BDL_MAX_WALLS];   ///< move: velocity [m/s]
    double stop[BDL_MAX_WALLS];      ///< move: time the motion ends [s]
    uint8_t gone[BDL_MAX_WALLS];     ///< taken away (open_time passed): touches nothing
    /// A plane wall's unit normal (zero for the other shapes): moving along itself, an infinite
    /// plane stays where it is for the neighbour lists (a shear cell's driving walls).
    bdl_vec3 plane_normal[BDL_MAX_WALLS];
    /// A triangle wall that repeats along periodic axes of the domain (wrap_length > 0 on them):
    /// a particle meets it at its rest-frame position taken modulo the length into
    /// [wrap_origin, wrap_origin + wrap_length), so that the wall may move along the axis for
    /// ever (the corrugated floor of a shear cell). Its triangles must repeat with that period.
    bdl_vec3 wrap_origin[BDL_MAX_WALLS], wrap_length[BDL_MAX_WALLS];
    // Live values, refreshed by bdl_walls_update; scaled by the live amplitude factor of commands.
    bdl_vec3 offset[BDL_MAX_WALLS];   ///< displacement from rest [m]
    bdl_vec3 velocity[BDL_MAX_WALLS]; ///< [m/s]
} bdl_walls;

/// Expands `count` wall definitions into primitives, at rest at time 0; mesh walls are read
/// from their files (why: the file and the reason on failure). `reach`: the largest distance at
/// which a surface is looked for (the largest particle's diameter plus the neighbour skin) [m].
bdl_result bdl_walls_build(const bdl_wall_def *defs, int count, double reach, bdl_walls *walls,
                           char *why, size_t why_len);
void bdl_walls_free(bdl_walls *walls);

/// The triangles of a mesh, disk or cone wall, placed (a mesh file read, scaled, turned and
/// shifted; a disk or cone made as polygons of `segments` sides).
bdl_result bdl_wall_mesh_of(const bdl_wall_def *d, bdl_mesh *m, char *why, size_t why_len);

/// Surfaces: primitives and triangles.
static inline long bdl_wall_surfaces(const bdl_walls *walls)
{
    return walls->prim_count + walls->tri_count;
}

/// The wall a surface belongs to.
static inline int bdl_wall_of(const bdl_walls *walls, long surface)
{
    return surface < walls->prim_count ? walls->prims[surface].wall
                                       : walls->tri[surface - walls->prim_count].wall;
}

/// The triangles of mesh wall `wall` that may lie within reach of x (0 and none outside its
/// bins, or for another kind of wall); *list receives global triangle indices, ascending.
int bdl_walls_near(const bdl_walls *walls, int wall, bdl_vec3 x, const int32_t **list);

/// Gap and normal as bdl_wall_gap, for triangle t (its face, or the nearest of its edges and
/// corners).
double bdl_wall_tri_gap(const bdl_walls *walls, long t, bdl_vec3 x, double radius, bdl_vec3 *n);

/// Whether the touching contact of a sphere (x, radius) with surface `surfaces[self]` counts:
/// always for a primitive; for a triangle, when no triangle of its patch among the list is
/// touched deeper (on a tie, when it comes first).
int bdl_wall_tri_counted(const bdl_walls *walls, const int32_t *surfaces, int count, int self,
                         bdl_vec3 x, double radius);

/// Sets offset and velocity of every wall at time t [s], and takes away those whose open_time
/// has come.
void bdl_walls_update(bdl_walls *walls, double t);

/// Advances the turned angle of every turning wall by its present spin over dt [s] (call before
/// bdl_walls_update for the new time).
void bdl_walls_turn(bdl_walls *walls, double dt);

/// A point of the lab as wall `wall` sees it at rest: less the wall's offset, turned back by its
/// turned angle about its axis (triangle walls only).
static inline bdl_vec3 bdl_wall_to_rest(const bdl_walls *walls, int wall, bdl_vec3 x)
{
    bdl_vec3 p = bdl_v3_sub(x, walls->offset[wall]);
    const bdl_vec3 len = walls->wrap_length[wall], o = walls->wrap_origin[wall];
    if (len.x > 0.0)
        p.x -= len.x * floor((p.x - o.x) / len.x);
    if (len.y > 0.0)
        p.y -= len.y * floor((p.y - o.y) / len.y);
    if (len.z > 0.0)
        p.z -= len.z * floor((p.z - o.z) / len.z);
    if (!walls->turns[wall])
        return p;
    const bdl_vec3 c = walls->center[wall];
    return bdl_v3_add(c, bdl_q_unrotate(walls->turned[wall], bdl_v3_sub(p, c)));
}

/// Distance-to-contact query. Returns the gap s = (distance from the surface) - radius along the
/// normal n pointing from the wall into the particle (s < 0: overlap -s), for a sphere at x.
static inline double bdl_wall_gap(const bdl_walls *walls, int prim, bdl_vec3 x, double radius,
                                  bdl_vec3 *n)
{
    if (prim >= walls->prim_count)
        return bdl_wall_tri_gap(walls, prim - walls->prim_count, x, radius, n);
    const bdl_wall_prim *w = &walls->prims[prim];
    if (walls->gone[w->wall]) {
        *n = bdl_v3_zero();
        return INFINITY;
    }
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
    if (prim >= walls->prim_count)
        return r;
    const bdl_wall_prim *w = &walls->prims[prim];
    if (w->kind == BDL_PRIM_CYLINDER && w->radius > r)
        return r * w->radius / (w->radius - r);
    return r;
}

/// Velocity of wall `wall`'s surface at point x: its translation plus its spin about its axis.
static inline bdl_vec3 bdl_wall_velocity_at(const bdl_walls *walls, int wall, bdl_vec3 x)
{
    const bdl_vec3 s = walls->spin[wall];
    if (s.x == 0.0 && s.y == 0.0 && s.z == 0.0)
        return walls->velocity[wall];
    return bdl_v3_add(walls->velocity[wall], bdl_v3_cross(s, bdl_v3_sub(x, walls->center[wall])));
}

/// Largest displacement any wall's surface has made since the offsets in `ref` and the turned
/// angles in `ref_angle` were taken [m].
double bdl_walls_max_shift(const bdl_walls *walls, const bdl_vec3 *ref, const double *ref_angle);

/// Largest speed any wall reaches over a cycle [m/s].
double bdl_walls_max_speed(const bdl_walls *walls);

#endif
