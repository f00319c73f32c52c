#include "output/rheology_out.h"

#include <math.h>
#include <stdlib.h>

const char *const bdl_rheology_columns[BDL_RHEOLOGY_COLUMNS] = {"time",
                                                                "particles",
                                                                "solids_fraction",
                                                                "shear_rate",
                                                                "temperature",
                                                                "pressure",
                                                                "shear_stress",
                                                                "friction",
                                                                "inertial_number",
                                                                "n1",
                                                                "n2",
                                                                "pressure_streaming",
                                                                "pressure_contact",
                                                                "shear_streaming",
                                                                "shear_contact",
                                                                "sxx",
                                                                "syy",
                                                                "szz",
                                                                "sxz",
                                                                "alignment",
                                                                "diameter",
                                                                "density"};

/// The touching pairs of the lists: particles, separations and forces.
typedef struct contact_arrays {
    long count;
    long *ci, *cj;
    bdl_vec3 *branch, *force;
} contact_arrays;

static bdl_result collect_contacts(const bdl_world *w, contact_arrays *c)
{
    const bdl_particles *p = &w->particles;
    const bdl_neighbor *nb = &w->neighbor;
    const long pairs = nb->count == p->count ? nb->pair_count : 0;
    c->count = 0;
    c->ci = malloc((size_t)(pairs + 1) * sizeof *c->ci);
    c->cj = malloc((size_t)(pairs + 1) * sizeof *c->cj);
    c->branch = malloc((size_t)(pairs + 1) * sizeof *c->branch);
    c->force = malloc((size_t)(pairs + 1) * sizeof *c->force);
    if (!c->ci || !c->cj || !c->branch || !c->force)
        return BDL_ERR_NOMEM;
    for (long i = 0; i < (pairs ? p->count : 0); ++i)
        for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k) {
            const bdl_vec3 f = bdl_world_pair_force(w, i, k);
            if (f.x == 0.0 && f.y == 0.0 && f.z == 0.0)
                continue;
            const long j = nb->partner[k];
            c->ci[c->count] = i;
            c->cj[c->count] = j;
            c->branch[c->count] = bdl_neighbor_delta(nb, p->pos[i], p->pos[j]);
            c->force[c->count] = f;
            c->count++;
        }
    return BDL_OK;
}

bdl_result bdl_rheology_of_world(const bdl_world *w, bdl_rheology_sample *s)
{
    const bdl_particles *p = &w->particles;
    const bdl_scene *sc = &w->scene;
    const long n = p->count;
    contact_arrays c = {0};
    double *mass = malloc((size_t)(n + 1) * sizeof *mass);
    double *volume = malloc((size_t)(n + 1) * sizeof *volume);
    double *diameter = malloc((size_t)(n + 1) * sizeof *diameter);
    bdl_result r = mass && volume && diameter ? collect_contacts(w, &c) : BDL_ERR_NOMEM;
    if (r == BDL_OK) {
        for (long i = 0; i < n; ++i) {
            mass[i] = 1.0 / p->inv_mass[i];
            volume[i] = bdl_particle_volume(p, i);
            diameter[i] = cbrt(6.0 * volume[i] / 3.14159265358979323846);
        }
        const bdl_rheology_input in = {.count = n,
                                       .pos = p->pos,
                                       .vel = p->vel,
                                       .mass = mass,
                                       .volume = volume,
                                       .diameter = diameter,
                                       .axis = p->rods ? p->axis : NULL,
                                       .contacts = c.count,
                                       .ci = c.ci,
                                       .cj = c.cj,
                                       .branch = c.branch,
                                       .force = c.force,
                                       .x_length = sc->domain_max.x - sc->domain_min.x,
                                       .y_length = sc->domain_max.y - sc->domain_min.y,
                                       .z_lo = sc->domain_min.z + sc->output.rheology_margin,
                                       .z_hi = sc->domain_max.z - sc->output.rheology_margin,
                                       .bins = sc->output.rheology_bins,
                                       .rate = sc->shear_rate != 0.0 ? sc->shear_rate : NAN};
        bdl_rheology_measure(&in, s);
    }
    free(mass);
    free(volume);
    free(diameter);
    free(c.ci);
    free(c.cj);
    free(c.branch);
    free(c.force);
    return r;
}

bdl_result bdl_rheology_row(const bdl_world *w, double *row)
{
    bdl_rheology_sample s;
    const bdl_result r = bdl_rheology_of_world(w, &s);
    if (r != BDL_OK)
        return r;
    const double v[BDL_RHEOLOGY_COLUMNS] = {w->time,
                                            (double)s.particles,
                                            s.solids_fraction,
                                            s.shear_rate,
                                            s.temperature,
                                            s.pressure,
                                            s.shear_stress,
                                            s.friction,
                                            s.inertial_number,
                                            s.n1,
                                            s.n2,
                                            s.pressure_streaming,
                                            s.pressure_contact,
                                            s.shear_streaming,
                                            s.shear_contact,
                                            s.stress[0][0],
                                            s.stress[1][1],
                                            s.stress[2][2],
                                            0.5 * (s.stress[0][2] + s.stress[2][0]),
                                            s.alignment,
                                            s.diameter,
                                            s.density};
    for (int k = 0; k < BDL_RHEOLOGY_COLUMNS; ++k)
        row[k] = v[k];
    return BDL_OK;
}
