// bedlam — particle snapshots as VTK XML PolyData (.vtp), gas fields as ImageData (.vti), and
// time series as ParaView .pvd files.
//
// Snapshots use the binary "appended" raw encoding (UInt64 block headers, little-endian): compact,
// exact, and read directly by ParaView and VTK. Every point also gets a vertex cell so ParaView
// draws the particles without a Glyph filter. All files are written atomically.
#ifndef BDL_VTK_H
#define BDL_VTK_H

#include "core/error.h"
#include "core/vec3.h"

/// Element type of a per-point array.
typedef enum bdl_vtk_type {
    BDL_VTK_FLOAT64, ///< `double` in memory, "Float64" in the file
    BDL_VTK_INT32,   ///< `int32_t` in memory, "Int32" in the file
} bdl_vtk_type;

/// One per-point data array: `components` values per point, point after point (a `bdl_vec3`
/// array is a FLOAT64 array with 3 components). `name` is shown in ParaView.
typedef struct bdl_vtk_array {
    const char *name;
    bdl_vtk_type type;
    int components;   ///< >= 1; 1 for scalars, 3 for vectors
    const void *data; ///< n * components elements; may be NULL when n == 0
} bdl_vtk_array;

/// Writes `n` particles at `positions` [m] with `array_count` per-point arrays to `path`
/// atomically. Returns BDL_ERR_IO on a write failure or invalid arguments (n < 0, missing data,
/// components < 1), BDL_ERR_NOMEM if a scratch buffer cannot be allocated.
bdl_result bdl_vtp_write(const char *path, long n, const bdl_vec3 *positions,
                         const bdl_vtk_array *arrays, int array_count);

/// Writes a uniform grid of n[0] x n[1] x n[2] cells from `origin` with cell size `spacing` [m]
/// as VTK XML ImageData (.vti) with per-cell arrays (FLOAT64 only; x fastest), atomically, in
/// ASCII (grids of the gas are small; the file stays readable). BDL_ERR_IO on failure.
bdl_result bdl_vti_write(const char *path, const int n[3], const double origin[3],
                         const double spacing[3], const bdl_vtk_array *arrays, int array_count);

/// A ParaView collection (.pvd) listing snapshot files with their times.
typedef struct bdl_pvd bdl_pvd;

/// Starts a new, empty collection at `pvd_path` and writes it at once, so the file is valid from
/// the start (an existing file is replaced). Returns NULL if memory is short or the file cannot
/// be written.
bdl_pvd *bdl_pvd_create(const char *pvd_path);

/// For a resumed run: the collection at `pvd_path` as it stands on disk, with the entries of
/// times <= t_keep [s] kept (their files, written before the checkpoint the run resumes from, and
/// their true times) and later ones dropped, written back at once. A missing file gives an empty
/// collection. NULL if memory is short or the file cannot be written.
bdl_pvd *bdl_pvd_continue(const char *pvd_path, double t_keep);

/// Appends a snapshot at simulated `time` [s]. `relative_file` is stored as given and is resolved
/// by ParaView relative to the .pvd's folder (e.g. "vtk/particles_000012.vtp"). The whole .pvd
/// is rewritten atomically, so it is valid after every call. On BDL_ERR_IO the entry is kept and
/// reaches the disk with the next successful add.
bdl_result bdl_pvd_add(bdl_pvd *pvd, double time, const char *relative_file);

/// Frees the collection (the file stays on disk). NULL is allowed.
void bdl_pvd_destroy(bdl_pvd *pvd);

/// Reads a collection for analysis, without writing anything: NULL (with the reason in `why`)
/// when it cannot be read.
bdl_pvd *bdl_pvd_read(const char *pvd_path, char *why, size_t why_len);
/// Entries of a collection, and entry k's time [s] and file (as stored: relative to the .pvd).
long bdl_pvd_count(const bdl_pvd *pvd);
const char *bdl_pvd_file(const bdl_pvd *pvd, long k, double *time);

/// A .vtp file as bedlam writes it (appended raw data, UInt64 headers), loaded for reading its
/// point arrays. Input is untrusted: every array's size is checked against the file.
typedef struct bdl_vtp_file {
    char *data;
    size_t size;
    long points;
    size_t appended; ///< offset of the appended data's first byte
} bdl_vtp_file;

/// Loads and checks the header; BDL_ERR_IO with the reason in `why` otherwise.
bdl_result bdl_vtp_open(const char *path, bdl_vtp_file *f, char *why, size_t why_len);
/// Copies the Float64 or Int32 array `name` ("Points" for the positions, "id" for the particle
/// ids) of `components` components into out (points * components values, as doubles, malloc'ed).
/// BDL_ERR_IO with the reason when it is missing, of another type or shape, or runs past the end of
/// the file.
bdl_result bdl_vtp_array(const bdl_vtp_file *f, const char *name, int components, double **out,
                         char *why, size_t why_len);
void bdl_vtp_close(bdl_vtp_file *f);

#endif
