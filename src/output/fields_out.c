// bedlam — the files of the time-averaged solids fields (see fields_out.h).
#include "output/fields_out.h"

#include <stdlib.h>

#include "io/vtk.h"

bdl_result bdl_fields_vti_write(const bdl_fields *f, const char *path)
{
    const long cells = bdl_fields_cells(f);
    double *fraction = malloc((size_t)cells * sizeof(double));
    double *velocity = malloc((size_t)cells * 3 * sizeof(double));
    bdl_result r = BDL_ERR_NOMEM;
    if (fraction && velocity) {
        bdl_fields_means(f, fraction, velocity);
        const bdl_vtk_array arrays[2] = {{"solids_fraction", BDL_VTK_FLOAT64, 1, fraction},
                                         {"solids_velocity", BDL_VTK_FLOAT64, 3, velocity}};
        r = bdl_vti_write(path, f->n, f->lo, f->h, arrays, 2);
    }
    free(fraction);
    free(velocity);
    return r;
}
