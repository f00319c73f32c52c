#include "output/diagnostics.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/bubbles.h"
#include "analysis/granular.h"
#include "cfd/gas.h"
#include "core/parallel.h"
#include "dem/contact_law.h"
#include "solids/phase.h"

const char *const bdl_diagnostics_columns[] = {
    "time",
    "step",
    "wall_seconds",
    "particles",
    "kinetic_energy",
    "rotational_energy",
    "potential_energy",
    "elastic_energy",
    "mean_coordination",
    "max_overlap_ratio",
    "wall_work",
    "energy_balance",
    "max_speed",
    "gas_work",
    "pressure_drop",
    "bed_height",
    "gas_volume_imbalance",
    "momentum_imbalance",
    "probe_pressure_drop",
    "weight_ratio",
    "particles_out",
    "mass_out",
    "inlet_velocity",
    "mean_height",
    "multi_contact_ratio",
    "wall_force",
    "spring_work_left",
    "bubble_count",
    "bubble_diameter",
    "segregation",
    "rod_vertical_cos",
    "rod_order",
};
const int bdl_diagnostics_column_count =
    (int)(sizeof bdl_diagnostics_columns / sizeof bdl_diagnostics_columns[0]);

#define BLOCKS 256

typedef struct partial {
    double kinetic, rotational, potential, elastic, contacts, overlap, speed, wall_force;
    bdl_orientation_sums axes; ///< of the rods
} partial;

int bdl_diagnostics_columns_for(const bdl_world *w)
{
    return bdl_diagnostics_column_count - (w->particles.rods ? 0 : 2);
}

/// Upward: against gravity, z without gravity.
static bdl_vec3 up_of(const bdl_world *w)
{
    const double g = bdl_v3_len(w->scene.gravity);
    return g > 0.0 ? bdl_v3_scale(w->scene.gravity, -1.0 / g) : bdl_v3(0, 0, 1);
}

static void particle_terms(const bdl_world *w, long i, partial *s)
{
    const bdl_particles *p = &w->particles;
    const bdl_neighbor *nb = &w->neighbor;
    double m = 1.0 / p->inv_mass[i];
    double v2 = bdl_v3_len2(p->vel[i]);
    s->kinetic += 0.5 * m * v2;
    s->rotational += p->rods ? 0.5 * bdl_v3_dot(p->omega[i], p->ang_mom[i])
                             : 0.5 * bdl_v3_len2(p->omega[i]) / bdl_particle_inv_inertia(p, i);
    s->potential -= m * bdl_v3_dot(w->scene.gravity, p->pos[i]);
    s->contacts += w->coordination ? w->coordination[i] : 0;
    if (v2 > s->speed * s->speed)
        s->speed = sqrt(v2);
    if (p->rods && p->half_length[i] > 0.0)
        bdl_orientation_add(&s->axes, bdl_q_axis_z(p->orient[i]), up_of(w));
    int ns = w->scene.species_count;
    for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k) {
        int32_t j = nb->partner[k];
        bdl_world_contact c;
        if (!bdl_world_pair_contact(w, i, j, &c))
            continue;
        double ratio = c.overlap / fmin(p->radius[i], p->radius[j]);
        if (ratio > s->overlap)
            s->overlap = ratio;
        const bdl_contact_params *cp = &w->pair_params[p->species[i] * ns + p->species[j]];
        const bdl_spring u = {nb->history ? nb->history[k] : bdl_v3_zero(),
                              nb->spring_work ? nb->spring_work[k] : 0.0};
        s->elastic += bdl_contact_elastic_energy(cp, w->hertz, c.overlap, c.r_eff, u);
    }
    for (int32_t k = nb->wall_start[i]; k < nb->wall_start[i + 1]; ++k) {
        bdl_world_contact c;
        if (!bdl_world_wall_contact(w, i, k, &c))
            continue;
        double ratio = c.overlap / p->radius[i];
        if (ratio > s->overlap)
            s->overlap = ratio;
        const bdl_contact_params *cp =
            &w->wall_params[bdl_wall_of(&w->walls, c.prim) * ns + p->species[i]];
        const bdl_spring u = {w->friction ? nb->wall_history[k] : bdl_v3_zero(),
                              nb->wall_spring_work ? nb->wall_spring_work[k] : 0.0};
        s->elastic += bdl_contact_elastic_energy(cp, w->hertz, c.overlap, c.r_eff, u);
        s->wall_force += c.normal;
    }
}

/// Sun's (2007) segregation percentage of a bed of two species (eqs. 5.22-5.25): S_p = <h_small>
/// / <h_large>, the species' volume-weighted mean heights above the floor, against its value
/// when fully segregated, S_p,max = (2 - x) / (1 - x) with x the small species' share of the
/// solids volume (the large below, the small above, both at one packing): s_p = (S_p - 1) /
/// (S_p,max - 1), 0 mixed, 1 segregated. From each species' volume, sum of volume x height and
/// (volume-weighted) size; NAN unless both are present, of different sizes, and the large
/// species' mean height is above 0.
static double segregation_index(const double volume[2], const double height[2],
                                const double size[2])
{
    if (!(volume[0] > 0.0 && volume[1] > 0.0) || size[0] == size[1])
        return NAN;
    const int small = size[0] < size[1] ? 0 : 1, large = 1 - small;
    const double x = volume[small] / (volume[0] + volume[1]);
    if (!(height[large] > 0.0))
        return NAN; // the large species' centres on the floor's plane (no floor there)
    const double ratio = (height[small] / volume[small]) / (height[large] / volume[large]);
    return (ratio - 1.0) / ((2.0 - x) / (1.0 - x) - 1.0);
}

/// The segregation percentage of a scene with exactly two species or two solids phases.
static double segregation(const bdl_world *w)
{
    double volume[2] = {0.0, 0.0}, height[2] = {0.0, 0.0}, size[2] = {0, 0};
    if (w->solids) {
        const bdl_solids *so = w->solids;
        if (so->count != 2)
            return NAN;
        for (int m = 0; m < 2; ++m) {
            volume[m] = bdl_solids_volume(so, m);
            height[m] = volume[m] * bdl_solids_mean_height(so, m, 2);
            size[m] = so->phase[m].def.diameter;
        }
        return segregation_index(volume, height, size);
    }
    const bdl_particles *p = &w->particles;
    if (w->scene.species_count != 2 || p->count == 0)
        return NAN;
    const bdl_vec3 up = up_of(w);
    double base = INFINITY;
    for (int c = 0; c < 8; ++c) { // the lowest corner of the domain along up
        const bdl_vec3 x = {c & 1 ? w->scene.domain_max.x : w->scene.domain_min.x,
                            c & 2 ? w->scene.domain_max.y : w->scene.domain_min.y,
                            c & 4 ? w->scene.domain_max.z : w->scene.domain_min.z};
        base = fmin(base, bdl_v3_dot(up, x));
    }
    for (long i = 0; i < p->count; ++i) {
        const int s = p->species[i];
        const double v = bdl_particle_solids_volume(p, i);
        volume[s] += v;
        height[s] += v * (bdl_v3_dot(up, p->pos[i]) - base);
        size[s] += v * p->radius[i];
    }
    for (int s = 0; s < 2; ++s)
        size[s] = volume[s] > 0.0 ? size[s] / volume[s] : 0.0;
    return segregation_index(volume, height, size);
}

static double layer_pressure(const bdl_gas *gas, int a, int m)
{
    return bdl_grid_layer_mean(&gas->grid, gas->p, a, m);
}

/// Layer-mean pressure at `height` above the domain's floor along the up axis: linear between
/// the layers' centres, the nearest layer beyond the first and last centre.
static double pressure_at_height(const bdl_world *w, int a, double up, double height)
{
    const bdl_grid *g = &w->gas->grid;
    const int n = g->n[a];
    double x = height / g->h[a] - 0.5; // in layer units from the lowest layer's centre
    int lo = (int)floor(x);
    if (lo < 0)
        return layer_pressure(w->gas, a, up > 0.0 ? 0 : n - 1);
    if (lo >= n - 1)
        return layer_pressure(w->gas, a, up > 0.0 ? n - 1 : 0);
    double f = x - lo;
    int m0 = up > 0.0 ? lo : n - 1 - lo, m1 = up > 0.0 ? lo + 1 : n - 2 - lo;
    return (1.0 - f) * layer_pressure(w->gas, a, m0) + f * layer_pressure(w->gas, a, m1);
}

/// A solids phase on the grid (its bed along z): mean height sum(eps z) / sum(eps), the height
/// below which 95 % of the solids lie (interpolated within the layer that crosses it), the
/// weight less buoyancy per unit base area against the pressure drop, the kinetic energy and the
/// largest cell speed.
static void solids_terms(const bdl_world *w, bdl_diagnostics *d)
{
    const bdl_solids *s = w->solids;
    const bdl_grid *g = &s->grid;
    const double cell = g->h[0] * g->h[1] * g->h[2];
    double total = 0.0, kinetic = 0.0, speed = 0.0, weight = 0.0;
    for (int m = 0; m < s->count; ++m) {
        const bdl_solids_phase *p = &s->phase[m];
        const double rho = p->def.density;
        double phase = 0.0;
        for (int k = 0; k < g->n[2]; ++k)
            for (int j = 0; j < g->n[1]; ++j)
                for (int i = 0; i < g->n[0]; ++i) {
                    const double e = p->eps[bdl_grid_index(g, i, j, k)];
                    double v2 = 0.0;
                    for (int a = 0; a < 3; ++a)
                        v2 += pow(bdl_solids_cell_velocity(s, m, a, i, j, k), 2.0);
                    phase += e;
                    kinetic += 0.5 * rho * e * cell * v2;
                    speed = e > s->def.dilute ? fmax(speed, sqrt(v2)) : speed;
                }
        total += phase;
        weight += phase * cell * (rho - w->gas->def.density);
    }
    d->mean_height = bdl_solids_mean_height(s, -1, 2);
    d->kinetic_energy = kinetic;
    d->max_speed = speed;
    double below = 0.0;
    for (int k = 0; k < g->n[2] && total > 0.0; ++k) {
        const double layer = bdl_grid_layer_mean(g, s->eps, 2, k) * g->n[0] * g->n[1];
        if (below + layer >= 0.95 * total) {
            d->bed_height = (k + (0.95 * total - below) / layer) * g->h[2];
            break;
        }
        below += layer;
    }
    const double g_len = bdl_v3_len(w->scene.gravity), area = g->n[0] * g->h[0] * g->n[1] * g->h[1];
    weight = weight * g_len / area;
    const double column = w->gas->def.density * g_len * (g->n[2] - 1) * g->h[2];
    d->weight_ratio = weight > 0.0 ? (d->pressure_drop - column) / weight : NAN;
}

/// The bubbles of the gas's voidage field (the voidage the particles leave, or 1 - eps of a solids
/// phase), the vertical axis a pointing up along the sign of `up`.
static void bubble_terms(const bdl_world *w, int a, double up, bdl_diagnostics *d)
{
    const bdl_grid *g = &w->gas->grid;
    const long cells = (long)g->n[0] * g->n[1] * g->n[2];
    double *f = malloc((size_t)cells * sizeof *f);
    if (!f)
        return;
    long c = 0;
    for (int k = 0; k < g->n[2]; ++k)
        for (int j = 0; j < g->n[1]; ++j)
            for (int i = 0; i < g->n[0]; ++i)
                f[c++] = w->gas->eps[bdl_grid_index(g, i, j, k)];
    bdl_bubble_grid bg = {.up = a, .up_sign = up > 0.0 ? 1 : -1};
    for (int b = 0; b < 3; ++b) {
        bg.n[b] = g->n[b];
        bg.h[b] = g->h[b];
        bg.periodic[b] = g->periodic[b];
    }
    bdl_bubbles s;
    if (bdl_bubbles_find(f, &bg, w->scene.gas.bubble_voidage, &s) == BDL_OK) {
        d->bubble_count = s.count;
        d->bubble_diameter = s.mean_diameter;
    }
    free(f);
}

static void gas_terms(const bdl_world *w, bdl_diagnostics *d)
{
    const bdl_gas *gas = w->gas;
    const bdl_grid *g = &gas->grid;
    double up;
    const int a = bdl_world_vertical_axis(w, &up);
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    const double first = layer_pressure(gas, a, 0), last = layer_pressure(gas, a, g->n[a] - 1);
    d->pressure_drop = up > 0.0 ? first - last : last - first;
    const bdl_gas_scene *gs = &w->scene.gas;
    d->probe_pressure_drop = gs->has_probe_low ? pressure_at_height(w, a, up, gs->probe_low) -
                                                     pressure_at_height(w, a, up, gs->probe_high)
                                               : NAN;
    const long n = w->particles.count;
    double *h = n > 0 ? malloc((size_t)n * sizeof(double)) : NULL;
    if (h) {
        double base =
            up > 0.0 ? bdl_v3_comp(w->scene.domain_min, a) : -bdl_v3_comp(w->scene.domain_max, a);
        double sum = 0.0;
        for (long i = 0; i < n; ++i) {
            h[i] = up * bdl_v3_comp(w->particles.pos[i], a) - base;
            sum += h[i];
        }
        d->mean_height = sum / (double)n;
        d->bed_height = bdl_height_quantile(h, n, 0.95);
        free(h);
    }
    d->gas_work = w->gas_work; // with the work of the gas step under way
    for (long i = 0; i < n; ++i)
        d->gas_work += bdl_world_gas_work_pending(w, i);
    d->gas_volume_imbalance = gas->mass_imbalance;
    // The bed's weight less buoyancy per unit base area, against the pressure drop less the gas
    // column's own weight (along a periodic gravity axis there is no column to measure).
    const double g_len = bdl_v3_len(w->scene.gravity), rho = gas->def.density;
    if (!g->periodic[a] && g_len > 0.0) {
        double weight = 0.0;
        for (long i = 0; i < n; ++i) {
            const double m = 1.0 / w->particles.inv_mass[i];
            weight += (m - rho * bdl_particle_solids_volume(&w->particles, i)) * g_len;
        }
        const double area = g->n[b] * g->h[b] * g->n[c] * g->h[c];
        const double column = rho * g_len * (g->n[a] - 1) * g->h[a]; // between the layer centres
        d->weight_ratio = weight > 0.0 ? (d->pressure_drop - column) / (weight / area) : NAN;
    }
    double sum = 0.0, mag = 0.0;
    for (int k = 0; k < 3; ++k) {
        if (g->n[k] == 1 && !g->periodic[k])
            continue; // one cell between walls: the gas cannot move, the walls take that drag
        sum += pow(w->particle_drag[k] + w->gas_drag[k], 2.0);
        mag += pow(w->particle_drag[k], 2.0);
    }
    d->momentum_imbalance = mag > 0.0 ? sqrt(sum / mag) : 0.0;
    bubble_terms(w, a, up, d);
    if (w->solids)
        solids_terms(w, d);
}

void bdl_diagnostics_compute(const bdl_world *w, double energy0, bdl_diagnostics *d)
{
    partial blocks[BLOCKS];
    memset(blocks, 0, sizeof blocks);
    long n = w->particles.count;
    long per = (n + BLOCKS - 1) / BLOCKS;
    if (per < 1)
        per = 1;
    BDL_PARALLEL_FOR(
        n >= w->parallel_min, for (int b = 0; b < BLOCKS; ++b) {
            long lo = b * per, hi = lo + per < n ? lo + per : n;
            for (long i = lo; i < hi; ++i)
                particle_terms(w, i, &blocks[b]);
        });
    partial s;
    memset(&s, 0, sizeof s);
    for (int b = 0; b < BLOCKS; ++b) {
        s.kinetic += blocks[b].kinetic;
        s.rotational += blocks[b].rotational;
        s.potential += blocks[b].potential;
        s.elastic += blocks[b].elastic;
        s.contacts += blocks[b].contacts;
        s.overlap = fmax(s.overlap, blocks[b].overlap);
        s.speed = fmax(s.speed, blocks[b].speed);
        s.wall_force += blocks[b].wall_force;
        bdl_orientation_merge(&s.axes, &blocks[b].axes);
    }
    memset(d, 0, sizeof *d);
    d->probe_pressure_drop = NAN; // without [gas] probe_low and probe_high
    d->mean_height = NAN;         // with a gas
    d->weight_ratio = NAN;
    d->time = w->time;
    d->step = w->step;
    d->particle_count = n;
    d->kinetic_energy = s.kinetic;
    d->rotational_energy = s.rotational;
    d->potential_energy = s.potential;
    d->elastic_energy = s.elastic;
    d->spring_work_left = bdl_exact_value(w->neighbor.spring_work_left);
    d->mean_coordination = n > 0 ? s.contacts / (double)n : 0.0;
    d->multi_contact_ratio =
        w->coordination ? bdl_coordination(w->coordination, n).multi_contact_ratio : 0.0;
    d->max_overlap_ratio = s.overlap;
    d->max_speed = s.speed;
    d->wall_force = s.wall_force;
    d->wall_work = w->wall_work;
    d->rod_vertical_cos = bdl_orientation_vertical(&s.axes);
    d->rod_order = bdl_orientation_order(&s.axes);
    d->segregation = segregation(w);
    if (w->gas)
        gas_terms(w, d);
    d->inlet_velocity = w->gas ? bdl_world_inlet_velocity(w, w->time) : 0.0;
    d->particles_out = w->removed;
    d->mass_out = w->removed_mass;
    d->energy_balance = bdl_diagnostics_total_energy(d) + w->removed_energy + d->spring_work_left -
                        energy0 - w->wall_work - w->inserted_energy - d->gas_work;
}

int bdl_diagnostics_may_be_undefined(int column)
{
    // By name, so that a column added to bdl_diagnostics_columns cannot shift the set.
    static const char *const undefined[] = {"probe_pressure_drop", "weight_ratio",
                                            "mean_height",         "segregation",
                                            "rod_vertical_cos",    "rod_order"};
    if (column < 0 || column >= bdl_diagnostics_column_count)
        return 0;
    for (size_t k = 0; k < sizeof undefined / sizeof undefined[0]; ++k)
        if (strcmp(bdl_diagnostics_columns[column], undefined[k]) == 0)
            return 1;
    return 0;
}

double bdl_diagnostics_total_energy(const bdl_diagnostics *d)
{
    return d->kinetic_energy + d->rotational_energy + d->potential_energy + d->elastic_energy;
}

void bdl_diagnostics_row(const bdl_diagnostics *d, double *v)
{
    v[0] = d->time;
    v[1] = (double)d->step;
    v[2] = d->wall_seconds;
    v[3] = (double)d->particle_count;
    v[4] = d->kinetic_energy;
    v[5] = d->rotational_energy;
    v[6] = d->potential_energy;
    v[7] = d->elastic_energy;
    v[8] = d->mean_coordination;
    v[9] = d->max_overlap_ratio;
    v[10] = d->wall_work;
    v[11] = d->energy_balance;
    v[12] = d->max_speed;
    v[13] = d->gas_work;
    v[14] = d->pressure_drop;
    v[15] = d->bed_height;
    v[16] = d->gas_volume_imbalance;
    v[17] = d->momentum_imbalance;
    v[18] = d->probe_pressure_drop;
    v[19] = d->weight_ratio;
    v[20] = (double)d->particles_out;
    v[21] = d->mass_out;
    v[22] = d->inlet_velocity;
    v[23] = d->mean_height;
    v[24] = d->multi_contact_ratio;
    v[25] = d->wall_force;
    v[26] = d->spring_work_left;
    v[27] = d->bubble_count;
    v[28] = d->bubble_diameter;
    v[29] = d->segregation;
    v[30] = d->rod_vertical_cos;
    v[31] = d->rod_order;
}
