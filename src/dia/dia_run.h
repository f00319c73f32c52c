// bedlam — the synthetic cameras of a run: images and ground truth in dia/NAME/ at their times.
//
// Per camera: camera.json (the mapping between world and pixels, the lighting and the truth
// grid), frames.csv (one row per image: frame, time, file), and per frame frame_NNNNNN.png (or
// frame_NNNNNN_a.png and _b.png for PIV pairs), frame_NNNNNN_particles.csv (every particle: id,
// position, velocity, radius, pixel position, depth, visible samples) and frame_NNNNNN_cells.csv
// (per image cell: visible area fraction, solids fraction over the depth and the first layer,
// visible particles, mean visible velocity in m/s and px/s). Formats: docs/dia.md.
#ifndef BDL_DIA_RUN_H
#define BDL_DIA_RUN_H

#include "core/error.h"
#include "dia/dia.h"
#include "io/snapshot.h"
#include "scene/scene.h"

typedef struct bdl_dia_run bdl_dia_run;

/// Opens every [camera NAME] of the scene under out_dir/dia/NAME for a run that stands at `now`
/// (its time and step length; a resumed run drops the index rows of images after its checkpoint
/// and continues the numbering). NULL *out when the scene has none. On failure `why` says what.
bdl_result bdl_dia_run_open(const bdl_scene *scene, const bdl_particle_view *now,
                            const char *out_dir, int resume, bdl_dia_run **out, char *why,
                            size_t len);
/// After a step: renders and writes the images that are due.
bdl_result bdl_dia_run_step(bdl_dia_run *r, const bdl_particle_view *v);
/// Whether an image is due at the view's time (bdl_dia_run_step would take one).
int bdl_dia_run_due(const bdl_dia_run *r, const bdl_particle_view *v);
/// Every camera's frames.csv flushed and on the disk (before a checkpoint). BDL_ERR_IO on failure.
bdl_result bdl_dia_run_sync(bdl_dia_run *r);
/// After BDL_ERR_IO from a write: the file's path and why ("PATH: no space left on device ...").
const char *bdl_dia_run_failure(const bdl_dia_run *r);
/// Images written so far.
long bdl_dia_run_count(const bdl_dia_run *r);
void bdl_dia_run_close(bdl_dia_run *r);

#endif
