// bedlam — the time-averaged solids fields (analysis/fields.h) of a run, and their files:
//
//   fields.vti   solids_fraction and solids_velocity per cell (VTK ImageData, ParaView), written
//                by a run with [output] fields_interval and by `bedlam analyze fields`
//   fields.sums  the running sums beside a run's checkpoint, for --resume
//
// A sums file is binary, in the machine's byte order, written atomically and read as untrusted
// input: "BDLSUMS1", the format version (u32, 1), the stamp (the step and time of the state it
// belongs to, the settings it was taken with), the grid, the counts, the sums per cell, and a
// CRC-32 of everything before it (u32).
#ifndef BDL_FIELDS_OUT_H
#define BDL_FIELDS_OUT_H

#include "analysis/fields.h"
#include "world/world.h"

/// Writes fields.vti of the samples so far (at least one): solids_fraction and solids_velocity
/// per cell, atomically.
bdl_result bdl_fields_vti_write(const bdl_fields *f, const char *path);

/// Adds the world's particles as one sample (a parcel for its real particles, a rod its
/// spherocylinder). BDL_ERR_NOMEM when scratch memory is short.
bdl_result bdl_fields_add_world(bdl_fields *f, const bdl_world *w);

/// The cell fields_cell stands for when it is not given: three times the mean diameter of the
/// world's particles, or of the scene's species when it holds none yet [m].
double bdl_fields_world_cell(const bdl_world *w);

/// An empty grid over the world's domain for cells of about `cell` [m]; BDL_ERR_SCENE above
/// BDL_MAX_FIELD_CELLS cells ("makes N cells over the domain, more than M" in `why`),
/// BDL_ERR_NOMEM.
bdl_result bdl_fields_create_world(bdl_fields *f, const bdl_world *w, double cell, char *why,
                                   size_t why_len);

/// What a sums file holds the sums of: the state and the settings.
typedef struct bdl_fields_stamp {
    long step;
    double time;     ///< [s]
    double interval; ///< [output] fields_interval [s]
    double start;    ///< [output] fields_start [s]
    double setting;  ///< [output] fields_cell as the scene gives it (< 0: the default) [m]
    double cell;     ///< the cell asked of the grid (the default resolved) [m]
} bdl_fields_stamp;

/// The stamp of the world's state now, for sums on a grid of cells of about `cell` [m].
bdl_fields_stamp bdl_fields_stamp_of(const bdl_world *w, double cell);

/// Writes the sums and their stamp to `path`, atomically; BDL_ERR_IO (errno set) on failure.
bdl_result bdl_fields_sums_save(const bdl_fields *f, const bdl_fields_stamp *stamp,
                                const char *path);

/// Reads a sums file into f (created here; free it with bdl_fields_free) and its stamp.
/// BDL_ERR_CHECKPOINT with the reason in `why` for a file that is missing, damaged or
/// inconsistent (a grid the stamp's cell does not give, a count or sum out of range),
/// BDL_ERR_NOMEM.
bdl_result bdl_fields_sums_load(bdl_fields *f, bdl_fields_stamp *stamp, const char *path, char *why,
                                size_t why_len);

/// Whether sums loaded with `stamp` continue the world's run: the same step and time, the
/// same settings, and the grid the world's domain gives for the stamp's cell. Otherwise 0, with
/// the difference in `why`.
int bdl_fields_stamp_matches(const bdl_fields *f, const bdl_fields_stamp *stamp, const bdl_world *w,
                             char *why, size_t why_len);

#endif
