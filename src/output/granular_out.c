#include "output/granular_out.h"

#include <stdio.h>
#include <stdlib.h>

#include "analysis/granular.h"
#include "cfd/gas.h"
#include "core/file.h"
#include "solids/phase.h"

/// Cells with fewer particles than this are left out of the Lacey indices: a cell of one or two
/// particles has a fraction of 0, 1/2 or 1 whatever the mixing.
#define LACEY_MIN_COUNT 5

int bdl_species_columns(const bdl_world *w, char names[][BDL_SPECIES_COLUMN_LEN])
{
    const bdl_scene *s = &w->scene;
    if (s->species_count < 2)
        return 0;
    int c = 0;
    snprintf(names[c++], BDL_SPECIES_COLUMN_LEN, "time");
    static const char *const what[] = {"count", "mean_height", "top_height", "coordination"};
    for (int k = 0; k < s->species_count; ++k)
        for (int q = 0; q < 4; ++q)
            snprintf(names[c++], BDL_SPECIES_COLUMN_LEN, "%s_%s", what[q], s->species[k].name);
    if (s->species_count == 2) {
        snprintf(names[c++], BDL_SPECIES_COLUMN_LEN, "lacey");
        snprintf(names[c++], BDL_SPECIES_COLUMN_LEN, "lacey_horizontal");
        snprintf(names[c++], BDL_SPECIES_COLUMN_LEN, "lacey_vertical");
    }
    return c;
}

static void mixing_cells(const bdl_world *w, int cells[3])
{
    const bdl_scene *s = &w->scene;
    bdl_vec3 c = s->output.mixing_cells;
    if (c.x < 1.0)
        c = s->gas.enabled ? s->gas.cells : (bdl_vec3){10, 10, 10};
    cells[0] = (int)c.x, cells[1] = (int)c.y, cells[2] = (int)c.z;
}

void bdl_species_row(const bdl_world *w, double *row)
{
    const bdl_scene *s = &w->scene;
    const bdl_particles *p = &w->particles;
    const int ns = s->species_count;
    double up;
    const int a = bdl_world_vertical_axis(w, &up);
    const double base = up > 0.0 ? bdl_v3_comp(s->domain_min, a) : -bdl_v3_comp(s->domain_max, a);
    long count[BDL_MAX_SPECIES] = {0};
    double sum[BDL_MAX_SPECIES] = {0}, top[BDL_MAX_SPECIES] = {0}, z[BDL_MAX_SPECIES] = {0};
    for (long i = 0; i < p->count; ++i) {
        const int k = p->species[i];
        const double h = up * bdl_v3_comp(p->pos[i], a) - base;
        top[k] = count[k] == 0 || h > top[k] ? h : top[k];
        count[k]++;
        sum[k] += h;
        z[k] += w->coordination ? w->coordination[i] : 0;
    }
    int c = 0;
    row[c++] = w->time;
    for (int k = 0; k < ns; ++k) {
        row[c++] = (double)count[k];
        row[c++] = count[k] > 0 ? sum[k] / (double)count[k] : NAN;
        row[c++] = count[k] > 0 ? top[k] : NAN;
        row[c++] = count[k] > 0 ? z[k] / (double)count[k] : NAN;
    }
    if (ns != 2)
        return;
    uint8_t *is_a = malloc((size_t)(p->count > 0 ? p->count : 1));
    if (!is_a) {
        row[c] = row[c + 1] = row[c + 2] = NAN;
        return;
    }
    for (long i = 0; i < p->count; ++i)
        is_a[i] = p->species[i] == 0;
    int cells[3], columns[3], layers[3] = {1, 1, 1};
    mixing_cells(w, cells);
    for (int q = 0; q < 3; ++q)
        columns[q] = q == a ? 1 : cells[q];
    layers[a] = cells[a];
    row[c++] =
        bdl_lacey(p->pos, is_a, p->count, s->domain_min, s->domain_max, cells, LACEY_MIN_COUNT);
    row[c++] =
        bdl_lacey(p->pos, is_a, p->count, s->domain_min, s->domain_max, columns, LACEY_MIN_COUNT);
    row[c++] =
        bdl_lacey(p->pos, is_a, p->count, s->domain_min, s->domain_max, layers, LACEY_MIN_COUNT);
    free(is_a);
}

int bdl_profile_columns(const bdl_world *w, char (*names)[BDL_SPECIES_COLUMN_LEN])
{
    if (!w->gas)
        return 0;
    double up;
    const int a = bdl_world_vertical_axis(w, &up);
    const bdl_grid *g = &w->gas->grid;
    const int phases = w->solids && w->solids->count > 1 ? w->solids->count : 0;
    if (names) {
        snprintf(names[0], BDL_SPECIES_COLUMN_LEN, "time");
        for (int k = 0; k < g->n[a]; ++k)
            snprintf(names[k + 1], BDL_SPECIES_COLUMN_LEN, "phi_at_%.6g", (k + 0.5) * g->h[a]);
        for (int m = 0; m < phases; ++m)
            for (int k = 0; k < g->n[a]; ++k)
                snprintf(names[1 + (m + 1) * g->n[a] + k], BDL_SPECIES_COLUMN_LEN,
                         "phase_%s_at_%.6g", w->scene.solids.phases[m].name, (k + 0.5) * g->h[a]);
    }
    return (phases + 1) * g->n[a] + 1;
}

void bdl_profile_row(const bdl_world *w, double *row)
{
    double up;
    const int a = bdl_world_vertical_axis(w, &up);
    const int n = w->gas->grid.n[a];
    row[0] = w->time;
    for (int k = 0; k < n; ++k)
        row[k + 1] =
            1.0 - bdl_grid_layer_mean(&w->gas->grid, w->gas->eps, a, up > 0.0 ? k : n - 1 - k);
    for (int m = 0; w->solids && w->solids->count > 1 && m < w->solids->count; ++m)
        for (int k = 0; k < n; ++k)
            row[1 + (m + 1) * n + k] = bdl_grid_layer_mean(&w->gas->grid, w->solids->phase[m].eps,
                                                           a, up > 0.0 ? k : n - 1 - k);
}

static void write_contact(FILE *f, const bdl_particles *p, long i, long j_label, int sj,
                          bdl_vec3 xj, double overlap, double fn)
{
    fprintf(f, "%ld,%ld,%d,%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", (long)p->id[i], j_label,
            p->species[i], sj, p->pos[i].x, p->pos[i].y, p->pos[i].z, xj.x, xj.y, xj.z, overlap,
            fn);
}

bdl_result bdl_contacts_write(const bdl_world *w, const char *path)
{
    bdl_atomic_file af;
    bdl_result r = bdl_atomic_open(&af, path);
    if (r != BDL_OK)
        return r;
    FILE *f = af.file;
    const bdl_particles *p = &w->particles;
    const bdl_neighbor *nb = &w->neighbor;
    fprintf(f, "# time = %.9g s\ni,j,species_i,species_j,x_i,y_i,z_i,x_j,y_j,z_j,overlap,fn\n",
            w->time);
    for (long i = 0; i < p->count; ++i) {
        bdl_world_contact c;
        for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k) {
            const int32_t j = nb->partner[k];
            if (bdl_world_pair_contact(w, i, j, &c))
                write_contact(f, p, i, (long)p->id[j], p->species[j], p->pos[j], c.overlap,
                              c.normal);
        }
        for (int32_t k = nb->wall_start[i]; k < nb->wall_start[i + 1]; ++k)
            if (bdl_world_wall_contact(w, i, k, &c))
                write_contact(f, p, i, -1L - bdl_wall_of(&w->walls, c.prim), -1, c.point, c.overlap,
                              c.normal);
    }
    if (ferror(f)) {
        bdl_atomic_abort(&af);
        return BDL_ERR_IO;
    }
    return bdl_atomic_commit(&af);
}
