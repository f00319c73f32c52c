// bedlam — a world's particles and gas fields as VTK XML files.
#include "output/world_vtk.h"

#include <stdlib.h>

#include "cfd/gas.h"
#include "io/vtk.h"

bdl_result bdl_world_gas_vti_write(const bdl_world *w, const char *path)
{
    const bdl_gas *gas = w->gas;
    const bdl_grid *g = &gas->grid;
    long cells = (long)g->n[0] * g->n[1] * g->n[2];
    double *eps = malloc((size_t)cells * sizeof(double)),
           *p = malloc((size_t)cells * sizeof(double));
    double *u = malloc((size_t)cells * 3 * sizeof(double));
    bdl_result r = BDL_ERR_NOMEM;
    if (eps && p && u) {
        long c = 0;
        for (int k = 0; k < g->n[2]; ++k)
            for (int j = 0; j < g->n[1]; ++j)
                for (int i = 0; i < g->n[0]; ++i, ++c) {
                    long idx = bdl_grid_index(g, i, j, k);
                    eps[c] = gas->eps[idx];
                    p[c] = gas->p[idx];
                    for (int a = 0; a < 3; ++a)
                        u[3 * c + a] = bdl_gas_cell_velocity(gas, a, i, j, k);
                }
        bdl_vtk_array arrays[] = {{"voidage", BDL_VTK_FLOAT64, 1, eps},
                                  {"pressure", BDL_VTK_FLOAT64, 1, p},
                                  {"gas_velocity", BDL_VTK_FLOAT64, 3, u}};
        double origin[3] = {g->origin[0], g->origin[1], g->origin[2]};
        double spacing[3] = {g->h[0], g->h[1], g->h[2]};
        r = bdl_vti_write(path, g->n, origin, spacing, arrays, 3);
    }
    free(eps);
    free(p);
    free(u);
    return r;
}

/// The unit axes and tip-to-tip lengths of the particles in p (a sphere: axis 0 0 1, length its
/// diameter), for glyphs drawn along the axis.
static void rod_axes(const bdl_particles *p, bdl_vec3 *axis, double *length)
{
    for (long i = 0; i < p->count; ++i) {
        axis[i] = bdl_q_axis_z(p->orient[i]);
        length[i] = 2.0 * (p->half_length[i] + p->radius[i]);
    }
}

bdl_result bdl_world_vtp_write(const bdl_world *w, const char *path)
{
    const bdl_particles *p = &w->particles;
    const long n = p->count, m = n > 0 ? n : 1;
    const int rods = p->rods;
    int32_t *id = malloc((size_t)m * sizeof(int32_t));
    int32_t *coord = malloc((size_t)m * sizeof(int32_t));
    bdl_vec3 *contact = malloc((size_t)m * sizeof(bdl_vec3));
    bdl_vec3 *drag = p->fluid ? malloc((size_t)m * sizeof(bdl_vec3)) : NULL;
    bdl_vec3 *axis = rods ? malloc((size_t)m * sizeof(bdl_vec3)) : NULL;
    double *length = rods ? malloc((size_t)m * sizeof(double)) : NULL;
    bdl_result r = BDL_ERR_NOMEM;
    if (id && coord && contact && (!p->fluid || drag) && (!rods || (axis && length))) {
        for (long i = 0; i < n; ++i) {
            id[i] = (int32_t)p->id[i];
            coord[i] = w->coordination[i];
            contact[i] = p->load[i].force;
            if (drag) // the drag's share of the gas's force on the particle
                drag[i] = bdl_v3_scale(p->drag_accel[i], 1.0 / p->inv_mass[i]);
        }
        if (rods)
            rod_axes(p, axis, length);
        // contact_force: the particle's contacts and walls (and background damping) this step;
        // with a gas, drag_force. Rod scenes add the orientation quaternion (w x y z, body z
        // along the axis), the unit axis (for ParaView's glyph filter) and the tip-to-tip
        // length.
        bdl_vtk_array arrays[11] = {
            {"radius", BDL_VTK_FLOAT64, 1, p->radius},
            {"velocity", BDL_VTK_FLOAT64, 3, p->vel},
            {"omega", BDL_VTK_FLOAT64, 3, p->omega},
            {"id", BDL_VTK_INT32, 1, id},
            {"species", BDL_VTK_INT32, 1, p->species},
            {"coordination", BDL_VTK_INT32, 1, coord},
            {"contact_force", BDL_VTK_FLOAT64, 3, contact},
        };
        int count = 7;
        if (drag)
            arrays[count++] = (bdl_vtk_array){"drag_force", BDL_VTK_FLOAT64, 3, drag};
        if (p->parcels) // the real particles each parcel stands for
            arrays[count++] = (bdl_vtk_array){"parcel_count", BDL_VTK_FLOAT64, 1, p->parcel_count};
        if (rods) {
            arrays[count++] = (bdl_vtk_array){"orientation", BDL_VTK_FLOAT64, 4, p->orient};
            arrays[count++] = (bdl_vtk_array){"axis", BDL_VTK_FLOAT64, 3, axis};
            arrays[count++] = (bdl_vtk_array){"length", BDL_VTK_FLOAT64, 1, length};
        }
        r = bdl_vtp_write(path, n, p->pos, arrays, count);
    }
    free(id);
    free(coord);
    free(contact);
    free(drag);
    free(axis);
    free(length);
    return r;
}
