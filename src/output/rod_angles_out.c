#include "output/rod_angles_out.h"

#include <stdio.h>

static const char *const zone_names[BDL_ROD_ZONES] = {"wall", "bulk"};

int bdl_rod_angle_columns(char names[][BDL_ROD_ANGLE_COLUMN_LEN])
{
    int c = 0;
    snprintf(names[c++], BDL_ROD_ANGLE_COLUMN_LEN, "time");
    snprintf(names[c++], BDL_ROD_ANGLE_COLUMN_LEN, "inlet_velocity");
    const double width = 180.0 / BDL_ROD_ANGLE_BINS;
    for (int z = 0; z < BDL_ROD_ZONES; ++z) {
        snprintf(names[c++], BDL_ROD_ANGLE_COLUMN_LEN, "%s_rods", zone_names[z]);
        snprintf(names[c++], BDL_ROD_ANGLE_COLUMN_LEN, "%s_abs_cos", zone_names[z]);
        for (int b = 0; b < BDL_ROD_ANGLE_BINS; ++b)
            snprintf(names[c++], BDL_ROD_ANGLE_COLUMN_LEN, "%s_at_%g", zone_names[z],
                     -90.0 + (b + 0.5) * width);
    }
    return c;
}

void bdl_rod_angle_row(const bdl_world *w, double *row)
{
    const bdl_particles *p = &w->particles;
    const bdl_rod_set set = {.count = p->rods ? p->count : 0,
                             .pos = p->pos,
                             .axis = p->axis,
                             .half_length = p->half_length,
                             .radius = p->radius,
                             .wall_front = w->scene.domain_min.y,
                             .wall_back = w->scene.domain_max.y};
    bdl_rod_histogram h;
    bdl_rod_histogram_of(&set, &h);
    int c = 0;
    row[c++] = w->time;
    row[c++] = w->gas ? bdl_world_inlet_velocity(w, w->time) : 0.0;
    for (int z = 0; z < BDL_ROD_ZONES; ++z) {
        row[c++] = (double)h.rods[z];
        row[c++] = h.abs_cos[z];
        for (int b = 0; b < BDL_ROD_ANGLE_BINS; ++b)
            row[c++] = (double)h.count[z][b];
    }
}
