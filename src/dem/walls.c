#include "dem/walls.h"

#include <math.h>

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

void bdl_walls_build(const bdl_wall_def *defs, int count, bdl_walls *walls)
{
    walls->prim_count = 0;
    walls->wall_count = count;
    for (int w = 0; w < count; ++w) {
        const bdl_wall_def *d = &defs[w];
        switch (d->kind) {
        case BDL_WALL_PLANE:
            add_plane(walls, w, d->point, bdl_v3_normalize(d->normal));
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
        }
        // A container wall stands still: the run is done in its frame (see world/world.h).
        const int moves = d->motion == BDL_MOTION_VIBRATE && d->frame != BDL_FRAME_CONTAINER;
        walls->motion[w] = moves ? d->motion : BDL_MOTION_NONE;
        walls->direction[w] = bdl_v3_normalize(d->direction);
        walls->amplitude[w] = moves ? d->amplitude : 0.0;
        walls->omega[w] = 2.0 * PI * d->frequency;
        walls->phase[w] = d->phase;
        walls->start[w] = d->start;
    }
    bdl_walls_update(walls, 0.0);
}

void bdl_walls_update(bdl_walls *walls, double t)
{
    for (int w = 0; w < walls->wall_count; ++w) {
        if (walls->motion[w] == BDL_MOTION_NONE || t < walls->start[w]) {
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

double bdl_walls_max_shift(const bdl_walls *walls, const bdl_vec3 *ref)
{
    double m = 0.0;
    for (int w = 0; w < walls->wall_count; ++w) {
        double d = bdl_v3_len(bdl_v3_sub(walls->offset[w], ref[w]));
        if (d > m)
            m = d;
    }
    return m;
}

double bdl_walls_max_speed(const bdl_walls *walls)
{
    double m = 0.0;
    for (int w = 0; w < walls->wall_count; ++w) {
        double v = walls->amplitude[w] * walls->omega[w];
        if (v > m)
            m = v;
    }
    return m;
}
