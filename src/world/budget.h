// bedlam — what a scene will need, estimated before anything is allocated.
//
// A world is refused when its scene would need more memory than [guards] max_memory or more time
// steps than [guards] max_steps: a count of 1e12, a gas grid of 4096^3 cells or a step of 1e-300 s
// then ends in a message within a second instead of running out of memory or for ever. The
// estimate is made from the scene alone, before a particle, a list or a grid exists, in floating
// point, so that no count overflows however large it is:
//
//   particles   each creator's (dem/create.h bdl_create_expected), pours included
//   per particle  the store's arrays (the table of dem/particles.c), BUDGET_LISTS bytes of
//               neighbour-list entries and scratch; with a gas the coupling's forces and, per
//               kernel point (one for a sphere, BDL_ROD_SATELLITES for a rod), its offsets and
//               weights; with frames or cameras BUDGET_SNAPSHOT bytes of snapshots
//   pairs       BUDGET_PAIRS per particle (a dense packing of equal spheres lists about 7 with the
//               default skin), times a rod's aspect ratio; BUDGET_PAIR bytes each
//   gas         BUDGET_GAS_CELL bytes per cell of the padded grid (the gas's 25 fields, the
//               pressure solver's and the coupling's)
//   images      frames: three RGB buffers and the multisampled colour and depth; a synthetic
//               camera: its grey and truth buffers and samples^2 hits and depths per pixel (two
//               images for PIV pairs)
//   fields      with [output] fields_interval: BUDGET_FIELDS_CELL bytes per cell of the fields'
//               grid (the sums, and the means written from them), of fields_cell or of three
//               times the species' mean diameter
//   steps       end_time / dt, dt as the world takes it (dt, or dt_fraction of the smallest contact
//               time at the reference impact speed)
//
// The figures are an estimate, not a measurement: a run holds about this much (growth slack of
// the lists comes on top), and `bedlam check` prints it beside the limits.
#ifndef BDL_BUDGET_H
#define BDL_BUDGET_H

#include "core/error.h"
#include "scene/scene.h"

struct bdl_world;

typedef struct bdl_budget {
    double particles;                         ///< particles at most over the run
    double create_particles[BDL_MAX_CREATES]; ///< of each creator (a file's rows counted once)
    double pairs;                             ///< neighbour-list pairs
    double gas_cells;                         ///< cells of the padded gas grid
    double particle_bytes;                    ///< particles and their pairs [bytes]
    double gas_bytes;    ///< the gas, its solver and the coupling's grid fields [bytes]
    double image_bytes;  ///< frame and synthetic-camera buffers [bytes]
    double fields_cells; ///< cells of the time-averaged fields' grid (0: none)
    double fields_bytes; ///< their sums and means [bytes]
    double bytes;        ///< all of it [bytes]
    double max_memory;   ///< the limit: [guards] max_memory, or 80 % of physical memory [bytes]
    double dt;           ///< the time step [s]
    double steps;        ///< end_time / dt
} bdl_budget;

/// The cell of the fields' grid the estimate takes: [output] fields_cell, or three times the mean
/// of the species' diameters (a run takes its particles' mean when it has particles) [m].
double bdl_budget_fields_cell(const bdl_scene *s);

/// The estimate for a world whose contacts and walls are built and which holds no particle yet.
void bdl_budget_estimate(const struct bdl_world *w, bdl_budget *b);

/// BDL_OK, or BDL_ERR_SCENE with a message naming the key that asks for the most, the estimate
/// and the limit ("FILE:LINE: [create bed] count = 1e+12: about 3.4e+14 bytes for 1e+12
/// particles, above [guards] max_memory = 1.9e+10 bytes").
bdl_result bdl_budget_check(const struct bdl_world *w, const bdl_budget *b, bdl_scene_error *err);

/// The steps alone, for a time step `dt` (checked again once the world has chosen its step).
bdl_result bdl_budget_check_steps(const struct bdl_world *w, double dt, bdl_scene_error *err);

#endif
