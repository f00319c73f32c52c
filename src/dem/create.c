#include "dem/create.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

BDL_CHOICE_WORDS(bdl_create_kind, BDL_CREATE_KINDS);

// A bucket grid over a region for overlap tests while placing particles.
typedef struct placement_grid {
    bdl_vec3 lo;
    double cell;
    int dims[3];
    long *head; ///< first particle index per cell, -1 if empty
    long *next; ///< next particle in the same cell
    long next_capacity;
} placement_grid;

static int grid_init(placement_grid *g, bdl_vec3 lo, bdl_vec3 hi, double cell)
{
    memset(g, 0, sizeof *g);
    g->lo = lo;
    // Keep the cell count modest for very large regions.
    for (;;) {
        long total = 1;
        for (int a = 0; a < 3; ++a) {
            double len = bdl_v3_comp(hi, a) - bdl_v3_comp(lo, a);
            g->dims[a] = (int)(len / cell) + 1;
            total *= g->dims[a];
        }
        if (total <= 8000000)
            break;
        cell *= 1.5;
    }
    g->cell = cell;
    long total = (long)g->dims[0] * g->dims[1] * g->dims[2];
    g->head = malloc((size_t)total * sizeof(long));
    if (!g->head)
        return 0;
    for (long c = 0; c < total; ++c)
        g->head[c] = -1;
    return 1;
}

static void grid_free(placement_grid *g)
{
    free(g->head);
    free(g->next);
}

static long grid_cell(const placement_grid *g, bdl_vec3 x, int c[3])
{
    for (int a = 0; a < 3; ++a) {
        int k = (int)floor((bdl_v3_comp(x, a) - bdl_v3_comp(g->lo, a)) / g->cell);
        if (k < 0 || k >= g->dims[a])
            return -1;
        c[a] = k;
    }
    return c[0] + (long)g->dims[0] * (c[1] + (long)g->dims[1] * c[2]);
}

static int grid_insert(placement_grid *g, const bdl_particles *p, long i)
{
    if (i >= g->next_capacity) {
        long cap = p->capacity > i + 1 ? p->capacity : i + 1;
        long *q = realloc(g->next, (size_t)cap * sizeof(long));
        if (!q)
            return 0;
        g->next = q;
        g->next_capacity = cap;
    }
    int c[3];
    long cell = grid_cell(g, p->pos[i], c);
    if (cell < 0)
        return 1; // outside the placement region: cannot interfere
    g->next[i] = g->head[cell];
    g->head[cell] = i;
    return 1;
}

/// True when a sphere at x with radius r overlaps a particle in the grid. Particles are at most
/// `reach` = r + r_max apart to touch, so the search covers ceil(reach / cell) cells.
static int grid_overlaps(const placement_grid *g, const bdl_particles *p, bdl_vec3 x, double r,
                         double r_max)
{
    int c[3];
    for (int a = 0; a < 3; ++a)
        c[a] = (int)floor((bdl_v3_comp(x, a) - bdl_v3_comp(g->lo, a)) / g->cell);
    int reach = (int)ceil((r + r_max) / g->cell);
    for (int z = c[2] - reach; z <= c[2] + reach; ++z) {
        if (z < 0 || z >= g->dims[2])
            continue;
        for (int y = c[1] - reach; y <= c[1] + reach; ++y) {
            if (y < 0 || y >= g->dims[1])
                continue;
            for (int xx = c[0] - reach; xx <= c[0] + reach; ++xx) {
                if (xx < 0 || xx >= g->dims[0])
                    continue;
                long cell = xx + (long)g->dims[0] * (y + (long)g->dims[1] * z);
                for (long j = g->head[cell]; j >= 0; j = g->next[j]) {
                    double cut = r + p->radius[j];
                    if (bdl_v3_len2(bdl_v3_sub(x, p->pos[j])) < cut * cut)
                        return 1;
                }
            }
        }
    }
    return 0;
}

static int inside_walls(const bdl_walls *walls, bdl_vec3 x, double r)
{
    for (int w = 0; w < walls->prim_count; ++w) {
        bdl_vec3 n;
        if (bdl_wall_gap(walls, w, x, r, &n) < 0.0)
            return 0;
    }
    return 1;
}

/// The largest radius of any species: particles of all species share the placement grid.
static double largest_radius(const bdl_create_context *ctx)
{
    double r = 0.0;
    for (int s = 0; s < ctx->species_count; ++s) {
        double d = bdl_species_max_diameter(&ctx->species[s]);
        if (0.5 * d > r)
            r = 0.5 * d;
    }
    return r;
}

/// A placement grid over the region, holding the existing particles near it.
static int grid_for_region(placement_grid *g, const bdl_particles *p, bdl_vec3 lo, bdl_vec3 hi,
                           double r_max)
{
    bdl_vec3 pad = bdl_v3(2.0 * r_max, 2.0 * r_max, 2.0 * r_max);
    if (!grid_init(g, bdl_v3_sub(lo, pad), bdl_v3_add(hi, pad), 2.0 * r_max))
        return 0;
    for (long i = 0; i < p->count; ++i)
        if (!grid_insert(g, p, i))
            return 0;
    return 1;
}

/// Draws a centre uniformly in the creator's region (a whole sphere inside it); true when the
/// sphere overlaps no wall and no particle.
static int try_place(const bdl_create_def *c, const bdl_walls *walls, const placement_grid *g,
                     const bdl_particles *p, double r, double r_max, bdl_rng *rng, bdl_vec3 *x)
{
    // One draw per statement: argument evaluation order is unspecified in C.
    x->x = bdl_rng_range(rng, c->region_min.x + r, c->region_max.x - r);
    x->y = bdl_rng_range(rng, c->region_min.y + r, c->region_max.y - r);
    x->z = bdl_rng_range(rng, c->region_min.z + r, c->region_max.z - r);
    return inside_walls(walls, *x, r) && !grid_overlaps(g, p, *x, r, r_max);
}

static bdl_vec3 draw_velocity(const bdl_create_def *c, bdl_rng *rng)
{
    if (c->velocity_jitter <= 0.0)
        return c->velocity;
    bdl_vec3 d;
    d.x = bdl_rng_normal(rng);
    d.y = bdl_rng_normal(rng);
    d.z = bdl_rng_normal(rng);
    return bdl_v3_madd(c->velocity, bdl_v3_normalize(d), c->velocity_jitter * bdl_rng_uniform(rng));
}

static double region_volume(const bdl_create_def *c)
{
    bdl_vec3 l = bdl_v3_sub(c->region_max, c->region_min);
    return l.x * l.y * l.z;
}

static long add_checked(bdl_particles *p, placement_grid *g, bdl_vec3 x, bdl_vec3 v, double r,
                        const bdl_create_context *ctx, int species)
{
    long i = bdl_particles_add(p, x, v, r, ctx->species[species].density, species);
    if (i >= 0 && !grid_insert(g, p, i))
        return -1;
    return i;
}

/// A creator that cannot do what it is asked: the reason into `why`.
static bdl_result fail(char *why, size_t why_len, const char *what)
{
    snprintf(why, why_len, "%s", what);
    return BDL_ERR_SCENE;
}

static bdl_result create_random(const bdl_create_def *c, const bdl_create_context *ctx,
                                bdl_particles *p, char *why, size_t why_len)
{
    const bdl_species_def *s = &ctx->species[c->species];
    const bdl_walls *walls = ctx->walls;
    bdl_rng *rng = ctx->rng;
    double r_max = largest_radius(ctx);
    long target = c->count;
    if (target < 0) {
        // Mean particle volume from a sample of the distribution.
        bdl_rng probe = *rng;
        double v = 0.0;
        for (int k = 0; k < 256; ++k) {
            double d = bdl_species_draw_diameter(s, &probe);
            v += PI / 6.0 * d * d * d;
        }
        target = (long)floor(c->volume_fraction * region_volume(c) / (v / 256.0) + 0.5);
    }
    placement_grid g;
    if (!grid_for_region(&g, p, c->region_min, c->region_max, r_max))
        return BDL_ERR_NOMEM;
    long placed = 0, attempts = 0, max_attempts = 2000 * target + 100000;
    double d = bdl_species_draw_diameter(s, rng);
    while (placed < target && attempts < max_attempts) {
        ++attempts;
        double r = 0.5 * d;
        bdl_vec3 x;
        if (!try_place(c, walls, &g, p, r, r_max, rng, &x))
            continue;
        if (add_checked(p, &g, x, draw_velocity(c, rng), r, ctx, c->species) < 0) {
            grid_free(&g);
            return BDL_ERR_NOMEM;
        }
        ++placed;
        d = bdl_species_draw_diameter(s, rng);
    }
    grid_free(&g);
    if (placed < target) {
        char what[512];
        snprintf(what, sizeof what,
                 "random fill placed only %ld of %ld particles; random sequential insertion jams "
                 "near a solids fraction of 0.38 — use a lower count or volume_fraction, a larger "
                 "region, type = lattice, or type = pour",
                 placed, target);
        return fail(why, why_len, what);
    }
    return BDL_OK;
}

static bdl_result create_lattice(const bdl_create_def *c, const bdl_create_context *ctx,
                                 bdl_particles *p, char *why, size_t why_len)
{
    const bdl_species_def *s = &ctx->species[c->species];
    const double r_max = largest_radius(ctx), d_species = bdl_species_max_diameter(s);
    double h = c->spacing > 0.0 ? c->spacing : 1.0001 * d_species;
    placement_grid g;
    if (!grid_for_region(&g, p, c->region_min, c->region_max, r_max))
        return BDL_ERR_NOMEM;
    long placed = 0;
    long limit = c->count > 0 ? c->count : -1;
    bdl_vec3 lo = c->region_min;
    int nx = (int)floor((c->region_max.x - lo.x - d_species) / h) + 1;
    int ny = (int)floor((c->region_max.y - lo.y - d_species) / h) + 1;
    int nz = (int)floor((c->region_max.z - lo.z - d_species) / h) + 1;
    for (int k = 0; k < nz && placed != limit; ++k)
        for (int j = 0; j < ny && placed != limit; ++j)
            for (int i = 0; i < nx && placed != limit; ++i) {
                double d = bdl_species_draw_diameter(s, ctx->rng);
                bdl_vec3 x = bdl_v3(lo.x + 0.5 * d_species + i * h, lo.y + 0.5 * d_species + j * h,
                                    lo.z + 0.5 * d_species + k * h);
                if (!inside_walls(ctx->walls, x, 0.5 * d) ||
                    grid_overlaps(&g, p, x, 0.5 * d, r_max))
                    continue;
                if (add_checked(p, &g, x, draw_velocity(c, ctx->rng), 0.5 * d, ctx, c->species) <
                    0) {
                    grid_free(&g);
                    return BDL_ERR_NOMEM;
                }
                ++placed;
            }
    grid_free(&g);
    if (limit > 0 && placed < limit) {
        char what[256];
        snprintf(what, sizeof what, "lattice holds only %ld of the %ld particles asked for", placed,
                 limit);
        return fail(why, why_len, what);
    }
    if (placed == 0)
        return fail(why, why_len,
                    "lattice region holds no particle (region smaller than a diameter?)");
    return BDL_OK;
}

/// Column names of a particle CSV file.
enum { COL_X, COL_Y, COL_Z, COL_D, COL_VX, COL_VY, COL_VZ, COL_COUNT };

static bdl_result create_file(const bdl_create_def *c, const bdl_create_context *ctx,
                              bdl_particles *p, char *why, size_t why_len)
{
    const bdl_species_def *species = &ctx->species[c->species];
    static const char *const names[COL_COUNT] = {"x", "y", "z", "diameter", "vx", "vy", "vz"};
    FILE *f = fopen(c->file, "r");
    char what[600];
    if (!f) {
        snprintf(what, sizeof what, "cannot open '%s': %s", c->file, strerror(errno));
        return fail(why, why_len, what);
    }
    char line[4096];
    int col[COL_COUNT];
    for (int k = 0; k < COL_COUNT; ++k)
        col[k] = -1;
    int ncols = 0;
    if (!fgets(line, sizeof line, f)) {
        fclose(f);
        return fail(why, why_len,
                    "particle file is empty (expected a header such as x,y,z,diameter)");
    }
    for (char *tok = strtok(line, ",\r\n"); tok; tok = strtok(NULL, ",\r\n"), ++ncols) {
        while (*tok == ' ')
            ++tok;
        for (int k = 0; k < COL_COUNT; ++k)
            if (strcmp(tok, names[k]) == 0)
                col[k] = ncols;
    }
    if (col[COL_X] < 0 || col[COL_Y] < 0 || col[COL_Z] < 0) {
        fclose(f);
        return fail(why, why_len, "particle file header must name columns x, y and z");
    }
    long row = 1;
    bdl_result result = BDL_OK;
    while (fgets(line, sizeof line, f)) {
        ++row;
        if (line[0] == '\n' || line[0] == '#')
            continue;
        double v[64];
        int n = 0;
        char *s = line, *end;
        while (n < 64) {
            v[n] = strtod(s, &end);
            if (end == s)
                break;
            ++n;
            s = end;
            while (*s == ' ')
                ++s;
            if (*s != ',')
                break;
            ++s;
        }
        if (n < ncols) {
            snprintf(what, sizeof what, "%s:%ld: expected %d numbers, found %d", c->file, row,
                     ncols, n);
            result = fail(why, why_len, what);
            break;
        }
        double d = col[COL_D] >= 0 ? v[col[COL_D]] : bdl_species_draw_diameter(species, ctx->rng);
        if (!(d > 0.0) || !isfinite(d)) {
            snprintf(what, sizeof what, "%s:%ld: diameter %g must be > 0", c->file, row, d);
            result = fail(why, why_len, what);
            break;
        }
        bdl_vec3 vel = c->velocity;
        if (col[COL_VX] >= 0 && col[COL_VY] >= 0 && col[COL_VZ] >= 0)
            vel = bdl_v3(v[col[COL_VX]], v[col[COL_VY]], v[col[COL_VZ]]);
        bdl_vec3 x = bdl_v3(v[col[COL_X]], v[col[COL_Y]], v[col[COL_Z]]);
        if (bdl_particles_add(p, x, vel, 0.5 * d, species->density, c->species) < 0) {
            result = BDL_ERR_NOMEM;
            break;
        }
    }
    fclose(f);
    return result;
}

bdl_result bdl_create_initial(const bdl_create_def *def, const bdl_create_context *ctx,
                              bdl_particles *p, char *why, size_t why_len)
{
    switch (def->kind) {
    case BDL_CREATE_RANDOM:
        return create_random(def, ctx, p, why, why_len);
    case BDL_CREATE_LATTICE:
        return create_lattice(def, ctx, p, why, why_len);
    case BDL_CREATE_FILE:
        return create_file(def, ctx, p, why, why_len);
    case BDL_CREATE_POUR:
        return BDL_OK;
    }
    return BDL_OK;
}

long bdl_create_pour(const bdl_create_def *def, const bdl_create_context *ctx, double t,
                     long *poured, bdl_particles *p)
{
    const bdl_walls *walls = ctx->walls;
    bdl_rng *rng = ctx->rng;
    if (t < def->start_time || *poured >= def->count)
        return 0;
    long due = (long)floor((t - def->start_time) * def->rate) + 1;
    if (due > def->count)
        due = def->count;
    if (due <= *poured)
        return 0;
    placement_grid g;
    double r_max = largest_radius(ctx);
    if (!grid_for_region(&g, p, def->region_min, def->region_max, r_max))
        return -1;
    long added = 0;
    const bdl_species_def *s = &ctx->species[def->species];
    while (*poured < due) {
        double r = 0.5 * bdl_species_draw_diameter(s, rng);
        int placed = 0;
        for (int attempt = 0; attempt < 50 && !placed; ++attempt) {
            bdl_vec3 x;
            if (!try_place(def, walls, &g, p, r, r_max, rng, &x))
                continue;
            if (add_checked(p, &g, x, draw_velocity(def, rng), r, ctx, def->species) < 0) {
                grid_free(&g);
                return -1;
            }
            placed = 1;
        }
        if (!placed)
            break; // the region is full for now; try again next step
        ++*poured;
        ++added;
    }
    grid_free(&g);
    return added;
}

/// Data rows of a particle file (lines after the header), 0 if it cannot be read.
static long count_rows(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return 0;
    long lines = 0;
    int c, last = '\n';
    while ((c = fgetc(f)) != EOF) {
        if (c == '\n')
            ++lines;
        last = c;
    }
    if (last != '\n')
        ++lines;
    fclose(f);
    return lines > 0 ? lines - 1 : 0;
}

long bdl_create_estimate_total(const bdl_create_def *creates, int count,
                               const bdl_species_def *species)
{
    long total = 0;
    for (int c = 0; c < count; ++c) {
        const bdl_create_def *def = &creates[c];
        if (def->count > 0) {
            total += def->count;
            continue;
        }
        const bdl_species_def *s = &species[def->species];
        double d = bdl_species_min_diameter(s);
        double vp = PI / 6.0 * d * d * d;
        if (def->kind == BDL_CREATE_RANDOM)
            total += (long)(def->volume_fraction * region_volume(def) / vp) + 1;
        else if (def->kind == BDL_CREATE_LATTICE)
            total += (long)(region_volume(def) / (d * d * d)) + 1;
        else
            total += count_rows(def->file);
    }
    return total;
}
