// bedlam — rheology.csv ([output] rheology_interval): at each of its times the stress of the bulk
// region and what is derived from it (analysis/rheology.h), for a shear cell (shear along x,
// gradient along z: Lees–Edwards boundaries, or walls moving along x).
//
// Columns: time [s]; particles (centres in the region); solids_fraction; shear_rate [1/s];
// temperature [m^2/s^2]; pressure, shear_stress [Pa]; friction (tau/p); inertial_number; n1, n2
// [Pa]; pressure_streaming, pressure_contact, shear_streaming, shear_contact [Pa]; sxx, syy, szz,
// sxz [Pa] (total, positive in compression; sxz the symmetric part); alignment [deg] (rods; NaN
// for spheres); diameter [m], density [kg/m^3] (volume-weighted means of the region's particles).
#ifndef BDL_RHEOLOGY_OUT_H
#define BDL_RHEOLOGY_OUT_H

#include "analysis/rheology.h"
#include "world/world.h"

#define BDL_RHEOLOGY_COLUMNS 22

extern const char *const bdl_rheology_columns[BDL_RHEOLOGY_COLUMNS];

/// The sample of the current state: the region is the domain less [output] rheology_margin at
/// each z face. Returns BDL_ERR_NOMEM when the contacts' arrays cannot be had.
bdl_result bdl_rheology_of_world(const bdl_world *w, bdl_rheology_sample *s);

/// One row of rheology.csv for the current state (BDL_RHEOLOGY_COLUMNS values).
bdl_result bdl_rheology_row(const bdl_world *w, double *row);

#endif
