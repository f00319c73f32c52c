#include "analysis/rod_angles.h"

#include <math.h>
#include <string.h>

double bdl_rod_plane_angle(bdl_vec3 u)
{
    double a = atan2(u.x, u.z) * (180.0 / BDL_PI); // in [-180, 180]
    if (a > 90.0)
        a -= 180.0;
    else if (a <= -90.0)
        a += 180.0;
    return a;
}

int bdl_rod_angle_bin(double a, int bins)
{
    const int b = (int)floor((a + 90.0) * bins / 180.0);
    return b < 0 ? 0 : b >= bins ? bins - 1 : b;
}

/// Near-wall: the centre within one rod length of the front or the back wall.
static int zone_of(const bdl_rod_set *set, long i)
{
    const double length = 2.0 * (set->half_length[i] + set->radius[i]);
    const double y = set->pos[i].y;
    const int near = y - set->wall_front < length || set->wall_back - y < length;
    return near ? BDL_ROD_ZONE_WALL : BDL_ROD_ZONE_BULK;
}

void bdl_rod_histogram_of(const bdl_rod_set *set, bdl_rod_histogram *h)
{
    memset(h, 0, sizeof *h);
    for (long i = 0; i < set->count; ++i) {
        if (!(set->half_length[i] > 0.0))
            continue;
        const int z = zone_of(set, i);
        const bdl_vec3 u = set->axis[i];
        h->count[z][bdl_rod_angle_bin(bdl_rod_plane_angle(u), BDL_ROD_ANGLE_BINS)]++;
        h->rods[z]++;
        h->abs_cos[z] += fabs(u.z) / bdl_v3_len(u);
    }
    for (int z = 0; z < BDL_ROD_ZONES; ++z)
        h->abs_cos[z] = h->rods[z] > 0 ? h->abs_cos[z] / (double)h->rods[z] : NAN;
}

bdl_rod_angle_average bdl_rod_angle_pdf(const bdl_rod_angle_series *s, long first, long end,
                                        double from, double to, double *const pdf[BDL_ROD_ZONES])
{
    bdl_rod_angle_average a = {0};
    double cos_sum[BDL_ROD_ZONES] = {0};
    for (int z = 0; z < BDL_ROD_ZONES; ++z)
        for (int b = 0; b < s->bins; ++b)
            pdf[z][b] = 0.0;
    for (long r = first; r < end; ++r) {
        if (!(s->time[r] >= from && s->time[r] <= to))
            continue;
        a.rows++;
        for (int z = 0; z < BDL_ROD_ZONES; ++z) {
            const double *row = s->count[z] + r * s->bins;
            double rods = 0.0;
            for (int b = 0; b < s->bins; ++b) {
                pdf[z][b] += row[b];
                rods += row[b];
            }
            a.rods[z] += rods;
            if (rods > 0.0)
                cos_sum[z] += rods * s->abs_cos[z][r];
        }
    }
    const double width = 180.0 / s->bins;
    for (int z = 0; z < BDL_ROD_ZONES; ++z) {
        a.abs_cos[z] = a.rods[z] > 0.0 ? cos_sum[z] / a.rods[z] : NAN;
        for (int b = 0; b < s->bins; ++b)
            pdf[z][b] = a.rods[z] > 0.0 ? pdf[z][b] / (a.rods[z] * width) : NAN;
    }
    return a;
}
