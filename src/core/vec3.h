// bedlam — double-precision 3-vectors.
//
// Small value type used everywhere in the solver. All functions are static inline so the
// compiler can keep vectors in registers inside the contact kernels.
#ifndef BDL_VEC3_H
#define BDL_VEC3_H

#include <math.h>

#define BDL_PI 3.14159265358979323846

typedef struct bdl_vec3 {
    double x, y, z;
} bdl_vec3;

static inline bdl_vec3 bdl_v3(double x, double y, double z) { return (bdl_vec3){x, y, z}; }
static inline bdl_vec3 bdl_v3_zero(void) { return (bdl_vec3){0.0, 0.0, 0.0}; }
static inline bdl_vec3 bdl_v3_add(bdl_vec3 a, bdl_vec3 b)
{
    return (bdl_vec3){a.x + b.x, a.y + b.y, a.z + b.z};
}
static inline bdl_vec3 bdl_v3_sub(bdl_vec3 a, bdl_vec3 b)
{
    return (bdl_vec3){a.x - b.x, a.y - b.y, a.z - b.z};
}
static inline bdl_vec3 bdl_v3_scale(bdl_vec3 a, double s)
{
    return (bdl_vec3){a.x * s, a.y * s, a.z * s};
}
static inline bdl_vec3 bdl_v3_neg(bdl_vec3 a) { return (bdl_vec3){-a.x, -a.y, -a.z}; }
static inline double bdl_v3_dot(bdl_vec3 a, bdl_vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
static inline double bdl_v3_len2(bdl_vec3 a) { return bdl_v3_dot(a, a); }
static inline double bdl_v3_len(bdl_vec3 a) { return sqrt(bdl_v3_dot(a, a)); }

static inline bdl_vec3 bdl_v3_cross(bdl_vec3 a, bdl_vec3 b)
{
    return (bdl_vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

/// a + s * b
static inline bdl_vec3 bdl_v3_madd(bdl_vec3 a, bdl_vec3 b, double s)
{
    return (bdl_vec3){a.x + s * b.x, a.y + s * b.y, a.z + s * b.z};
}

/// Unit vector along a; the zero vector stays zero.
static inline bdl_vec3 bdl_v3_normalize(bdl_vec3 a)
{
    double l = bdl_v3_len(a);
    return l > 0.0 ? bdl_v3_scale(a, 1.0 / l) : a;
}

static inline int bdl_v3_isfinite(bdl_vec3 a)
{
    return isfinite(a.x) && isfinite(a.y) && isfinite(a.z);
}

static inline double bdl_v3_comp(bdl_vec3 a, int axis)
{
    return axis == 0 ? a.x : (axis == 1 ? a.y : a.z);
}

/// The axis of v's largest component in magnitude: z on a tie with z, and for the zero vector
/// (the axis "up" is measured along when gravity is v).
static inline int bdl_v3_major_axis(bdl_vec3 v)
{
    int axis = 2;
    for (int a = 0; a < 2; ++a)
        if (fabs(bdl_v3_comp(v, a)) > fabs(bdl_v3_comp(v, axis)))
            axis = a;
    return axis;
}

static inline void bdl_v3_set_comp(bdl_vec3 *a, int axis, double v)
{
    if (axis == 0)
        a->x = v;
    else if (axis == 1)
        a->y = v;
    else
        a->z = v;
}

#endif
