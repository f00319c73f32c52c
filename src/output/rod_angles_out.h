// bedlam — orientation.csv of a run with rods ([output] orientation_interval): at each of its
// times the histogram of the rods' in-plane angle near the front and back walls and in the bulk
// (analysis/rod_angles.h).
//
// Columns: time [s]; inlet_velocity [m/s] (the sweep's stage; 0 without a gas); then for each
// zone, wall and bulk: ZONE_rods (rods in the zone), ZONE_abs_cos (their mean |cos| of the 3D
// angle to the vertical z) and ZONE_at_A, the rods whose in-plane angle lies in the bin centred at
// A degrees, for the BDL_ROD_ANGLE_BINS bins over [-90, 90].
#ifndef BDL_ROD_ANGLES_OUT_H
#define BDL_ROD_ANGLES_OUT_H

#include "analysis/rod_angles.h"
#include "world/world.h"

#define BDL_ROD_ANGLE_COLUMNS    (2 + BDL_ROD_ZONES * (2 + BDL_ROD_ANGLE_BINS))
#define BDL_ROD_ANGLE_COLUMN_LEN 24

/// The column names of orientation.csv into names; returns their count.
int bdl_rod_angle_columns(char names[][BDL_ROD_ANGLE_COLUMN_LEN]);

/// One row of orientation.csv for the current state (BDL_ROD_ANGLE_COLUMNS values).
void bdl_rod_angle_row(const bdl_world *w, double *row);

#endif
