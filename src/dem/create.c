#include "dem/create.h"

#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/file.h"
#include "core/memory.h"
#include "dem/capsule.h"

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

enum { GRID_MAX_CELLS = 8000000 };

static int grid_init(placement_grid *g, bdl_vec3 lo, bdl_vec3 hi, double cell)
{
    memset(g, 0, sizeof *g);
    g->lo = lo;
    // Keep the cell count modest for very large regions or very small particles. The count is
    // taken in doubles: cells of a nanometre over a centimetre are 1e21, beyond int and long.
    double cells[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < 4096; ++k, cell *= 1.5) {
        double total = 1.0;
        for (int a = 0; a < 3; ++a) {
            cells[a] = floor((bdl_v3_comp(hi, a) - bdl_v3_comp(lo, a)) / cell) + 1.0;
            total *= cells[a];
        }
        if (total <= GRID_MAX_CELLS)
            break;
    }
    size_t total = 1;
    for (int a = 0; a < 3; ++a) {
        if (!(cells[a] >= 1.0 && cells[a] <= GRID_MAX_CELLS))
            return 0; // a region that is not finite
        g->dims[a] = (int)cells[a];
        total *= (size_t)g->dims[a];
    }
    g->cell = cell;
    size_t bytes;
    if (!bdl_size_mul(total, sizeof(long), &bytes) || !(g->head = malloc(bytes)))
        return 0;
    for (size_t c = 0; c < total; ++c)
        g->head[c] = -1;
    return 1;
}

static void grid_free(placement_grid *g)
{
    free(g->head);
    free(g->next);
}

/// The cell along axis a of coordinate x, clamped to [-1, dims[a]]: a position far outside the
/// grid (or not finite) gives a cell just beyond it rather than an int that overflows.
static int cell_along(const placement_grid *g, double x, int a)
{
    const double k = floor((x - bdl_v3_comp(g->lo, a)) / g->cell);
    if (!(k >= -1.0))
        return -1;
    return k > g->dims[a] ? g->dims[a] : (int)k;
}

static long grid_cell(const placement_grid *g, bdl_vec3 x, int c[3])
{
    for (int a = 0; a < 3; ++a) {
        int k = cell_along(g, bdl_v3_comp(x, a), a);
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

/// A particle to be placed: centre, half axis (zero for a sphere), radius; a rod's orientation.
typedef struct body {
    bdl_vec3 x, e;
    double r, half_length;
    bdl_quat q;
} body;

/// A sphere at x of radius r.
static body sphere_at(bdl_vec3 x, double r)
{
    return (body){x, bdl_v3_zero(), r, 0.0, bdl_q_identity()};
}

/// Whether body b overlaps particle j: the centres (spheres) or the shafts (rods) closer than the
/// sum of the radii.
static int overlaps(const bdl_particles *p, long j, const body *b)
{
    double cut = b->r + p->radius[j];
    if (!p->rods)
        return bdl_v3_len2(bdl_v3_sub(b->x, p->pos[j])) < cut * cut;
    double s, t;
    return bdl_segments_closest(bdl_v3_sub(b->x, p->pos[j]), b->e, bdl_particle_half_axis(p, j), &s,
                                &t) < cut * cut;
}

/// True when body b overlaps a particle in the grid. Particles whose bounding spheres (of radius
/// at most r_max) touch b's are at most `reach` apart, so the search covers ceil(reach / cell)
/// cells.
static int grid_overlaps(const placement_grid *g, const bdl_particles *p, const body *b,
                         double r_max)
{
    int c[3];
    for (int a = 0; a < 3; ++a) // clamped: the exact test below rejects what is not near
        c[a] = cell_along(g, bdl_v3_comp(b->x, a), a);
    int reach = (int)ceil((b->r + b->half_length + r_max) / g->cell);
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
                for (long j = g->head[cell]; j >= 0; j = g->next[j])
                    if (overlaps(p, j, b))
                        return 1;
            }
        }
    }
    return 0;
}

/// Whether body b is clear of every wall (a rod: both tips; walls are touched at the tips).
static int inside_walls(const bdl_walls *walls, const body *b)
{
    const int tips = b->half_length > 0.0 ? 2 : 1;
    for (int k = 0; k < tips; ++k) {
        bdl_vec3 n;
        bdl_vec3 x = tips == 1 ? b->x : bdl_v3_madd(b->x, b->e, k ? 1.0 : -1.0);
        for (int w = 0; w < walls->prim_count; ++w)
            if (bdl_wall_gap(walls, w, x, b->r, &n) < 0.0)
                return 0;
        for (int w = 0; w < walls->wall_count; ++w) {
            const int32_t *near = NULL;
            int m = bdl_walls_near(walls, w, x, &near);
            for (int t = 0; t < m; ++t)
                if (bdl_wall_tri_gap(walls, near[t], x, b->r, &n) < 0.0)
                    return 0;
        }
    }
    return 1;
}

/// The largest bounding radius of any species (half a diameter, or half a rod's length):
/// particles of all species share the placement grid.
static double largest_radius(const bdl_create_context *ctx)
{
    double r = 0.0;
    for (int s = 0; s < ctx->species_count; ++s) {
        double d = bdl_species_max_extent(&ctx->species[s]);
        if (0.5 * d > r)
            r = 0.5 * d;
    }
    return r;
}

/// A random orientation for a rod of species s (uniform over directions); spheres draw nothing.
static void orient(body *b, const bdl_species_def *s, bdl_rng *rng)
{
    if (s->shape != BDL_SHAPE_ROD)
        return;
    const bdl_vec3 u = bdl_rng_direction(rng);
    b->half_length = 0.5 * s->length - b->r;
    b->q = bdl_q_from_z(u);
    b->e = bdl_v3_scale(u, b->half_length);
}

/// Whether a rod's tips, with its radius around them, lie in the creator's region (a sphere's
/// centre was drawn inside it already).
static int inside_region(const bdl_create_def *c, const body *b)
{
    for (int a = 0; a < 3; ++a) {
        const double x = bdl_v3_comp(b->x, a), e = fabs(bdl_v3_comp(b->e, a));
        if (x - e - b->r < bdl_v3_comp(c->region_min, a) ||
            x + e + b->r > bdl_v3_comp(c->region_max, a))
            return 0;
    }
    return 1;
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

/// The cylinder of a region: its axis, the centre of its cross-section, its radius [m].
static void region_cylinder(const bdl_create_def *c, int *u, int *v, double *cu, double *cv,
                            double *radius)
{
    *u = (c->region_axis + 1) % 3;
    *v = (c->region_axis + 2) % 3;
    const double lu = bdl_v3_comp(c->region_min, *u), hu = bdl_v3_comp(c->region_max, *u);
    const double lv = bdl_v3_comp(c->region_min, *v), hv = bdl_v3_comp(c->region_max, *v);
    *cu = 0.5 * (lu + hu);
    *cv = 0.5 * (lv + hv);
    *radius = 0.5 * fmin(hu - lu, hv - lv);
}

/// A point drawn uniformly in the region, at least `r` inside its boundary.
static bdl_vec3 draw_in_region(const bdl_create_def *c, bdl_rng *rng, double r)
{
    bdl_vec3 x;
    if (c->region_shape != BDL_REGION_CYLINDER) { // a box, or the box around a mesh
        // One draw per statement: argument evaluation order is unspecified in C.
        x.x = bdl_rng_range(rng, c->region_min.x + r, c->region_max.x - r);
        x.y = bdl_rng_range(rng, c->region_min.y + r, c->region_max.y - r);
        x.z = bdl_rng_range(rng, c->region_min.z + r, c->region_max.z - r);
        return x;
    }
    int u, v;
    double cu, cv, radius;
    region_cylinder(c, &u, &v, &cu, &cv, &radius);
    const double a = c->region_axis;
    const double along = bdl_rng_range(rng, bdl_v3_comp(c->region_min, (int)a) + r,
                                       bdl_v3_comp(c->region_max, (int)a) - r);
    const double rho = fmax(0.0, radius - r) * sqrt(bdl_rng_uniform(rng));
    const double phi = 2.0 * BDL_PI * bdl_rng_uniform(rng);
    bdl_v3_set_comp(&x, c->region_axis, along);
    bdl_v3_set_comp(&x, u, cu + rho * cos(phi));
    bdl_v3_set_comp(&x, v, cv + rho * sin(phi));
    return x;
}

/// Whether a body lies wholly inside the creator's mesh (any body, when its region is no mesh):
/// a sphere's centre (a rod's two tips) inside, and at least its radius from the surface.
static int inside_mesh(const bdl_create_def *c, const bdl_create_context *ctx, const body *b)
{
    if (c->region_shape != BDL_REGION_MESH)
        return 1;
    for (int tip = 0; tip < (b->half_length > 0.0 ? 2 : 1); ++tip) {
        const bdl_vec3 x = bdl_v3_madd(b->x, b->e, tip ? -1.0 : 1.0);
        if (!(fabs(bdl_mesh_winding(ctx->region, x)) > 0.5) ||
            bdl_mesh_distance(ctx->region, x) < b->r)
            return 0;
    }
    return 1;
}

/// Draws a centre uniformly in the creator's region (a whole sphere inside it) and a rod's
/// orientation; true when the particle lies in the region and overlaps no wall and no particle.
static int try_place(const bdl_create_def *c, const bdl_create_context *ctx,
                     const placement_grid *g, const bdl_particles *p, double r, double r_max,
                     body *b)
{
    bdl_rng *rng = ctx->rng;
    const bdl_vec3 x = draw_in_region(c, rng, r);
    *b = sphere_at(x, r);
    orient(b, &ctx->species[c->species], rng);
    return (b->half_length == 0.0 || inside_region(c, b)) && inside_walls(ctx->walls, b) &&
           !grid_overlaps(g, p, b, r_max) && inside_mesh(c, ctx, b);
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

bdl_result bdl_create_region_mesh(const bdl_create_def *c, bdl_mesh *m, char *why, size_t why_len)
{
    char reason[400];
    bdl_result r = bdl_mesh_read(c->region_file, m, reason, sizeof reason);
    if (r == BDL_OK)
        bdl_mesh_transform(m, c->region_scale, c->region_rotate, c->region_translate);
    else
        snprintf(why, why_len, "'%s' %s", c->region_file, reason);
    return r;
}

double bdl_create_region_volume(const bdl_create_def *c)
{
    if (c->region_shape == BDL_REGION_MESH)
        return c->region_volume;
    bdl_vec3 l = bdl_v3_sub(c->region_max, c->region_min);
    if (c->region_shape == BDL_REGION_CYLINDER) {
        int u, v;
        double cu, cv, radius;
        region_cylinder(c, &u, &v, &cu, &cv, &radius);
        return BDL_PI * radius * radius * bdl_v3_comp(l, c->region_axis);
    }
    return l.x * l.y * l.z;
}

/// Sites of a creator's lattice along axis a (as create_lattice lays them), as a number.
static double lattice_sites(const bdl_create_def *c, double extent, double spacing, int a)
{
    const double n =
        floor((bdl_v3_comp(c->region_max, a) - bdl_v3_comp(c->region_min, a) - extent) / spacing) +
        1.0;
    return n > 0.0 ? n : 0.0;
}

static long add_checked(bdl_particles *p, placement_grid *g, const body *b, bdl_vec3 v,
                        const bdl_create_context *ctx, int species)
{
    const double density = ctx->species[species].density;
    long i = b->half_length > 0.0
                 ? bdl_particles_add_rod(p, b->x, v, b->r, b->half_length, b->q, density, species)
                 : bdl_particles_add(p, b->x, v, b->r, density, species);
    if (i >= 0 && p->parcels)
        bdl_particle_set_parcel(p, i, bdl_species_parcel_count(&ctx->species[species], 2.0 * b->r));
    if (i >= 0 && g && !grid_insert(g, p, i))
        return -1;
    return i;
}

/// A lattice's spacing: as given, else just over the largest extent of a particle of the
/// species (of a parcel: the diameter of the sphere of its solids volume).
static double lattice_spacing(const bdl_create_def *c, const bdl_species_def *s)
{
    if (c->spacing > 0.0)
        return c->spacing;
    if (bdl_species_is_parcel(s))
        return 1.0001 * cbrt(6.0 / BDL_PI * bdl_species_parcel_volume(s));
    return 1.0001 * bdl_species_max_extent(s);
}

/// Mean solids volume of what a random fill of species s places: a particle's, or a parcel's
/// (from a sample of the distribution, drawn from a copy of the generator).
static double mean_placed_volume(const bdl_species_def *s, const bdl_rng *rng)
{
    bdl_rng probe = *rng;
    double v = 0.0;
    for (int k = 0; k < 256; ++k) {
        const double d = bdl_species_draw_diameter(s, &probe);
        v += bdl_species_volume(s, d) * bdl_species_parcel_count(s, d);
    }
    return v / 256.0;
}

/// A random fill of parcels: parcels stand for a solids fraction, not for bodies that exclude
/// each other, so they are placed uniformly in the region (clear of the walls) and may overlap.
static bdl_result create_random_parcels(const bdl_create_def *c, const bdl_create_context *ctx,
                                        long target, bdl_particles *p)
{
    const bdl_species_def *s = &ctx->species[c->species];
    for (long placed = 0; placed < target;) {
        body b;
        const double d = bdl_species_draw_diameter(s, ctx->rng);
        b = sphere_at(draw_in_region(c, ctx->rng, 0.0), 0.5 * d);
        if (!inside_walls(ctx->walls, &b) || !inside_mesh(c, ctx, &b))
            continue;
        if (add_checked(p, NULL, &b, draw_velocity(c, ctx->rng), ctx, c->species) < 0)
            return BDL_ERR_NOMEM;
        ++placed;
    }
    return BDL_OK;
}

/// A creator that cannot do what it is asked: the reason into `why`.
static bdl_result fail(char *why, size_t why_len, const char *what)
{
    snprintf(why, why_len, "%s", what);
    return BDL_ERR_SCENE;
}

/// Placements over which a random fill measures its success rate.
#define JAM_WINDOW 64

/// Whether a random fill cannot reach its target: random sequential insertion approaches its
/// jamming limit as phi_J - phi(t) ~ t^(-1/f) (Feder 1980, Swendsen 1981; f the degrees of
/// freedom of a placement: 3 for a sphere, 5 for a rod), so the particles still placeable are
/// about f times the current success rate times the attempts so far. A fill is refused now,
/// instead of spending its whole budget of tries, when its remaining count exceeds 10 times the
/// rate times the attempts (twice the largest f); the repository's tightest fill
/// (scenes/brazil_nut.ini) reaches 3.4 times. The rate is taken over the last JAM_WINDOW
/// placements with the longest one left out (one hard draw, a large particle of a wide size
/// distribution, does not decide), and judged once it has fallen below 1/20. The attempts are
/// this fill's: a region already partly filled by an earlier creator makes the test stricter.
static int fill_jammed(long *recent, long placed, long attempts, long target)
{
    const long slot = placed % JAM_WINDOW, before = recent[slot];
    recent[slot] = attempts; // recent[slot] now the newest, recent[slot + 1] the oldest
    if (placed <= JAM_WINDOW || (double)(attempts - before) < 20.0 * JAM_WINDOW)
        return 0;
    long previous = before, longest = 0;
    for (int k = 1; k <= JAM_WINDOW; ++k) {
        const long at = recent[(slot + k) % JAM_WINDOW];
        longest = at - previous > longest ? at - previous : longest;
        previous = at;
    }
    const double rate = (JAM_WINDOW - 1) / (double)(attempts - before - longest);
    return rate < 0.05 && (double)(target - placed) > 10.0 * rate * (double)attempts;
}

static bdl_result create_random(const bdl_create_def *c, const bdl_create_context *ctx,
                                bdl_particles *p, char *why, size_t why_len)
{
    const bdl_species_def *s = &ctx->species[c->species];
    bdl_rng *rng = ctx->rng;
    double r_max = largest_radius(ctx);
    long target = c->count;
    if (target < 0)
        target = (long)floor(
            c->volume_fraction * bdl_create_region_volume(c) / mean_placed_volume(s, rng) + 0.5);
    if (p->parcels)
        return create_random_parcels(c, ctx, target, p);
    placement_grid g;
    if (!grid_for_region(&g, p, c->region_min, c->region_max, r_max))
        return BDL_ERR_NOMEM;
    long placed = 0, attempts = 0, max_attempts = 2000 * target + 100000;
    long recent[JAM_WINDOW] = {0}; // attempt count at each of the last placements
    int jammed = 0;
    double d = bdl_species_draw_diameter(s, rng);
    while (placed < target && attempts < max_attempts && !jammed) {
        ++attempts;
        body b;
        if (!try_place(c, ctx, &g, p, 0.5 * d, r_max, &b))
            continue;
        if (add_checked(p, &g, &b, draw_velocity(c, rng), ctx, c->species) < 0) {
            grid_free(&g);
            return BDL_ERR_NOMEM;
        }
        ++placed;
        jammed = fill_jammed(recent, placed, attempts, target);
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
    const double r_max = largest_radius(ctx), d_species = bdl_species_max_extent(s);
    const double h = lattice_spacing(c, s);
    placement_grid g;
    if (!grid_for_region(&g, p, c->region_min, c->region_max, r_max))
        return BDL_ERR_NOMEM;
    long placed = 0;
    long limit = c->count > 0 ? c->count : -1;
    bdl_vec3 lo = c->region_min;
    // Taken as numbers first: sites along an axis beyond an int are refused long before this
    // (the scene's memory estimate), but the cast must not overflow all the same.
    const int nx = (int)fmin(lattice_sites(c, d_species, h, 0), INT_MAX);
    const int ny = (int)fmin(lattice_sites(c, d_species, h, 1), INT_MAX);
    const int nz = (int)fmin(lattice_sites(c, d_species, h, 2), INT_MAX);
    for (int k = 0; k < nz && placed != limit; ++k)
        for (int j = 0; j < ny && placed != limit; ++j)
            for (int i = 0; i < nx && placed != limit; ++i) {
                double d = bdl_species_draw_diameter(s, ctx->rng);
                body b =
                    sphere_at(bdl_v3(lo.x + 0.5 * d_species + i * h, lo.y + 0.5 * d_species + j * h,
                                     lo.z + 0.5 * d_species + k * h),
                              0.5 * d);
                orient(&b, s, ctx->rng);
                if (!inside_walls(ctx->walls, &b) ||
                    (!p->parcels && grid_overlaps(&g, p, &b, r_max)))
                    continue;
                if (add_checked(p, &g, &b, draw_velocity(c, ctx->rng), ctx, c->species) < 0) {
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

/// Columns of a particle CSV file.
enum { COL_X, COL_Y, COL_Z, COL_D, COL_VX, COL_VY, COL_VZ, COL_UX, COL_UY, COL_UZ, COL_COUNT };

/// Reads the header line of a particle file into col (column index of each name, or -1) and
/// returns the number of columns, or a negative value with the reason in what.
static int file_header(FILE *f, const bdl_species_def *species, int col[COL_COUNT], char *what,
                       size_t what_len)
{
    static const char *const names[COL_COUNT] = {"x",  "y",  "z",  "diameter", "vx",
                                                 "vy", "vz", "ux", "uy",       "uz"};
    char line[4096];
    for (int k = 0; k < COL_COUNT; ++k)
        col[k] = -1;
    if (!fgets(line, sizeof line, f)) {
        snprintf(what, what_len,
                 "particle file is empty (expected a header such as x,y,z,diameter)");
        return -1;
    }
    int ncols = 0;
    for (char *tok = strtok(line, ",\r\n"); tok; tok = strtok(NULL, ",\r\n"), ++ncols) {
        while (*tok == ' ')
            ++tok;
        for (int k = 0; k < COL_COUNT; ++k)
            if (strcmp(tok, names[k]) == 0)
                col[k] = ncols;
    }
    const int axis = (col[COL_UX] >= 0) + (col[COL_UY] >= 0) + (col[COL_UZ] >= 0);
    const int rod = species->shape == BDL_SHAPE_ROD;
    if (col[COL_X] < 0 || col[COL_Y] < 0 || col[COL_Z] < 0)
        snprintf(what, what_len, "particle file header must name columns x, y and z");
    else if (axis != 0 && axis != 3)
        snprintf(what, what_len,
                 "particle file header names only some of ux, uy, uz "
                 "(a rod's axis needs all three)");
    else if (axis && !rod)
        snprintf(what, what_len,
                 "particle file has axis columns ux, uy, uz but species '%s' "
                 "is a sphere",
                 species->name);
    else if (rod && col[COL_D] >= 0)
        snprintf(what, what_len,
                 "particle file has a diameter column but species '%s' is a rod "
                 "(its diameter and length come from the species)",
                 species->name);
    else
        return ncols;
    return -1;
}

/// Parses up to 64 comma-separated numbers of a line into v; returns how many.
static int parse_numbers(char *s, double v[64])
{
    int n = 0;
    char *end;
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
    return n;
}

/// The particle of one row of a particle file (numbers v, columns col): a sphere of the row's
/// or the species' diameter, or a rod along the row's axis or a random one. Returns 0 with the
/// reason in what for a row that describes no particle.
static int file_body(const double *v, const int col[COL_COUNT], const bdl_species_def *species,
                     bdl_rng *rng, body *b, char *what, size_t what_len)
{
    const double d = col[COL_D] >= 0 ? v[col[COL_D]] : bdl_species_draw_diameter(species, rng);
    if (!(d > 0.0) || !isfinite(d)) {
        snprintf(what, what_len, "diameter %g must be > 0", d);
        return 0;
    }
    // The neighbour lists' cutoff and the time step come from the species' sizes: a particle
    // larger would miss contacts, a smaller one have contacts shorter than the step resolves.
    if (d < species->diameter_min * (1.0 - 1e-9) || d > species->diameter_max * (1.0 + 1e-9)) {
        snprintf(what, what_len,
                 "diameter %g m is outside the sizes of [species %s], [%g, %g] m (the neighbour "
                 "lists and the time step are sized from them: give the species a distribution "
                 "that covers the file)",
                 d, species->name, species->diameter_min, species->diameter_max);
        return 0;
    }
    *b = sphere_at(bdl_v3(v[col[COL_X]], v[col[COL_Y]], v[col[COL_Z]]), 0.5 * d);
    if (species->shape != BDL_SHAPE_ROD)
        return 1;
    if (col[COL_UX] < 0) {
        orient(b, species, rng);
        return 1;
    }
    const bdl_vec3 u = bdl_v3(v[col[COL_UX]], v[col[COL_UY]], v[col[COL_UZ]]);
    const double len = bdl_v3_len(u);
    if (!(len > 0.0) || !isfinite(len)) {
        snprintf(what, what_len, "axis (%g, %g, %g) must be a nonzero direction", u.x, u.y, u.z);
        return 0;
    }
    b->half_length = 0.5 * species->length - b->r;
    b->q = bdl_q_from_z(bdl_v3_scale(u, 1.0 / len));
    b->e = bdl_v3_scale(u, b->half_length / len);
    return 1;
}

/// A row's numbers, all finite; else 0 with the column (1-based, and its name when the header
/// gives one of ours) in what.
static int finite_row(const double *v, int n, const int col[COL_COUNT], char *what, size_t what_len)
{
    static const char *const names[COL_COUNT] = {"x",  "y",  "z",  "diameter", "vx",
                                                 "vy", "vz", "ux", "uy",       "uz"};
    for (int c = 0; c < n; ++c) {
        if (isfinite(v[c]))
            continue;
        const char *name = "";
        for (int k = 0; k < COL_COUNT; ++k)
            if (col[k] == c)
                name = names[k];
        snprintf(what, what_len, "column %d%s%s%s is %g: not a finite number", c + 1,
                 *name ? " (" : "", name, *name ? ")" : "", v[c]);
        return 0;
    }
    return 1;
}

/// Particles of a file closer than this fraction of the smaller diameter are the same particle
/// written twice: refused with both lines rather than reported later as an overlap.
#define COINCIDENT 1e-6

/// Particles of a file in cells of `cell` metres, hashed: a chain per bucket through `next`.
/// Any file gives a few particles per cell, however far apart its particles lie.
typedef struct cell_hash {
    double cell;
    size_t mask; ///< buckets - 1 (a power of two)
    long *head;  ///< first particle (index from the file's first) of each bucket, -1 if none
    long *next;
} cell_hash;

static size_t hash_bucket(const cell_hash *h, const double k[3])
{
    const double key[3] = {k[0] + 0.0, k[1] + 0.0, k[2] + 0.0}; // -0 and +0: the same cell
    uint64_t bits[3], x = 0x9e3779b97f4a7c15u;
    memcpy(bits, key, sizeof bits);
    for (int a = 0; a < 3; ++a) {
        x = (x ^ bits[a]) * 0xff51afd7ed558ccdu;
        x ^= x >> 33;
    }
    return (size_t)x & h->mask;
}

static int hash_init(cell_hash *h, long n, double cell)
{
    size_t buckets = 64, bytes;
    while (buckets < 2 * (size_t)n)
        buckets *= 2;
    *h = (cell_hash){.cell = cell, .mask = buckets - 1};
    if (!bdl_size_mul(buckets, sizeof(long), &bytes) || !(h->head = malloc(bytes)) ||
        !bdl_size_mul((size_t)n, sizeof(long), &bytes) || !(h->next = malloc(bytes)))
        return 0;
    memset(h->head, 0xff, buckets * sizeof(long)); // every bucket -1
    return 1;
}

/// The first particle of [first, p->count) whose centre coincides with an earlier one of the
/// range, with the file line of each (`rows`, per particle from `first`); BDL_OK when none.
/// Cells as large as the largest distance that counts keep the search to 27 cells a particle.
static bdl_result find_coincident(const bdl_particles *p, long first, const long *rows, char *what,
                                  size_t what_len)
{
    double r_max = 0.0;
    for (long i = first; i < p->count; ++i)
        r_max = fmax(r_max, p->radius[i]);
    cell_hash h;
    if (!hash_init(&h, p->count - first, 2.0 * COINCIDENT * r_max)) {
        free(h.head);
        return BDL_ERR_NOMEM;
    }
    bdl_result r = BDL_OK;
    for (long i = first; i < p->count && r == BDL_OK; ++i) {
        const double k[3] = {floor(p->pos[i].x / h.cell), floor(p->pos[i].y / h.cell),
                             floor(p->pos[i].z / h.cell)};
        for (int m = 0; m < 27 && r == BDL_OK; ++m) {
            const double near[3] = {k[0] + m % 3 - 1, k[1] + m / 3 % 3 - 1, k[2] + m / 9 - 1};
            for (long j = h.head[hash_bucket(&h, near)]; j >= 0; j = h.next[j]) {
                const double cut = COINCIDENT * 2.0 * fmin(p->radius[i], p->radius[first + j]);
                if (bdl_v3_len2(bdl_v3_sub(p->pos[i], p->pos[first + j])) < cut * cut) {
                    snprintf(what, what_len,
                             "lines %ld and %ld: two particles at (%g, %g, %g) m, closer than "
                             "%g of the smaller diameter",
                             rows[j], rows[i - first], p->pos[i].x, p->pos[i].y, p->pos[i].z,
                             COINCIDENT);
                    r = BDL_ERR_SCENE;
                    break;
                }
            }
        }
        const size_t b = hash_bucket(&h, k);
        h.next[i - first] = h.head[b];
        h.head[b] = i - first;
    }
    free(h.head);
    free(h.next);
    return r;
}

/// Adds the particle of one data row (numbers v, n of them) of a particle file; 0 with the
/// reason in `reason` for a row that describes no particle, -1 when out of memory.
static int file_row(const bdl_create_def *c, const bdl_create_context *ctx, const double *v, int n,
                    int ncols, const int col[COL_COUNT], bdl_particles *p, char *reason,
                    size_t reason_len)
{
    const bdl_species_def *species = &ctx->species[c->species];
    body b;
    if (n < ncols) {
        snprintf(reason, reason_len, "expected %d numbers, found %d", ncols, n);
        return 0;
    }
    if (!finite_row(v, n, col, reason, reason_len) ||
        !file_body(v, col, species, ctx->rng, &b, reason, reason_len))
        return 0;
    bdl_vec3 vel = c->velocity;
    if (col[COL_VX] >= 0 && col[COL_VY] >= 0 && col[COL_VZ] >= 0)
        vel = bdl_v3(v[col[COL_VX]], v[col[COL_VY]], v[col[COL_VZ]]);
    const double density = species->density;
    const long i = b.half_length > 0.0 ? bdl_particles_add_rod(p, b.x, vel, b.r, b.half_length, b.q,
                                                               density, c->species)
                                       : bdl_particles_add(p, b.x, vel, b.r, density, c->species);
    if (i >= 0 && p->parcels)
        bdl_particle_set_parcel(p, i, bdl_species_parcel_count(species, 2.0 * b.r));
    return i < 0 ? -1 : 1;
}

/// Particles from a CSV file: a header naming x, y, z and optionally diameter (spheres), vx, vy,
/// vz, and ux, uy, uz (a rod's axis; rods without them get random axes). Every number must be
/// finite, and no two centres may coincide.
static bdl_result create_file(const bdl_create_def *c, const bdl_create_context *ctx,
                              bdl_particles *p, char *why, size_t why_len)
{
    char what[600], reason[300];
    FILE *f = bdl_open_regular(c->file, reason, sizeof reason);
    if (!f) {
        snprintf(what, sizeof what, "'%s' %s", c->file, reason);
        return fail(why, why_len, what);
    }
    int col[COL_COUNT];
    const int ncols = file_header(f, &ctx->species[c->species], col, reason, sizeof reason);
    if (ncols < 0) {
        fclose(f);
        snprintf(what, sizeof what, "%s: %s", c->file, reason);
        return fail(why, why_len, what);
    }
    const long first = p->count;
    long *rows = NULL, capacity = 0, row = 1; // the file line of each particle, for messages
    char line[4096];
    bdl_result result = BDL_OK;
    what[0] = '\0';
    while (fgets(line, sizeof line, f)) {
        ++row;
        if (line[0] == '\n' || line[0] == '#')
            continue;
        double v[64];
        const int n = parse_numbers(line, v);
        const int added = file_row(c, ctx, v, n, ncols, col, p, reason, sizeof reason);
        const long k = p->count - 1 - first;
        if (added == 0) {
            snprintf(what, sizeof what, "%s:%ld: %s", c->file, row, reason);
            result = BDL_ERR_SCENE;
            break;
        }
        if (added < 0 || (k >= capacity && !bdl_grow((void **)&rows, 2 * k + 64, sizeof(long)))) {
            result = BDL_ERR_NOMEM;
            break;
        }
        capacity = k >= capacity ? 2 * k + 64 : capacity;
        rows[k] = row;
    }
    fclose(f);
    if (result == BDL_OK && p->count > first &&
        (result = find_coincident(p, first, rows, reason, sizeof reason)) == BDL_ERR_SCENE)
        snprintf(what, sizeof what, "%s: %s", c->file, reason);
    free(rows);
    return result == BDL_ERR_SCENE ? fail(why, why_len, what) : result;
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
    bdl_rng *rng = ctx->rng;
    if (t < def->start_time || t >= def->stop_time || *poured >= def->count)
        return 0;
    const double due_now = floor((t - def->start_time) * def->rate) + 1.0;
    const long due = due_now < (double)def->count ? (long)due_now : def->count;
    if (due <= *poured)
        return 0;
    placement_grid g;
    double r_max = largest_radius(ctx);
    if (!grid_for_region(&g, p, def->region_min, def->region_max, r_max))
        return -1;
    long added = 0;
    const bdl_species_def *s = &ctx->species[def->species];
    // 50 tries per particle in the region; more where the region fills less of its box.
    const bdl_vec3 box = bdl_v3_sub(def->region_max, def->region_min);
    const double tries = 50.0 * box.x * box.y * box.z / bdl_create_region_volume(def);
    const int attempts = tries < 5000.0 ? (int)ceil(tries) : 5000;
    while (*poured < due) {
        double r = 0.5 * bdl_species_draw_diameter(s, rng);
        int placed = 0;
        for (int attempt = 0; attempt < attempts && !placed; ++attempt) {
            body b;
            if (!try_place(def, ctx, &g, p, r, r_max, &b))
                continue;
            if (add_checked(p, &g, &b, draw_velocity(def, rng), ctx, def->species) < 0) {
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

/// Data rows of a particle file (lines after the header), 0 if it cannot be read or is not a
/// regular file (a FIFO would block here).
static long count_rows(const char *path)
{
    char why[256], block[1 << 14];
    FILE *f = bdl_open_regular(path, why, sizeof why);
    if (!f)
        return 0;
    long lines = 0;
    char last = '\n';
    size_t got;
    while ((got = fread(block, 1, sizeof block, f)) > 0) {
        for (const char *c = block; (c = memchr(c, '\n', got - (size_t)(c - block))); ++c)
            ++lines;
        last = block[got - 1];
    }
    if (last != '\n')
        ++lines;
    fclose(f);
    return lines > 0 ? lines - 1 : 0;
}

double bdl_create_expected(const bdl_create_def *c, const bdl_species_def *s)
{
    if (c->kind == BDL_CREATE_FILE)
        return (double)count_rows(c->file);
    const double count = c->count > 0 ? (double)c->count : INFINITY;
    if (c->kind == BDL_CREATE_LATTICE) {
        const double extent = bdl_species_max_extent(s);
        const double h = lattice_spacing(c, s);
        const double sites = lattice_sites(c, extent, h, 0) * lattice_sites(c, extent, h, 1) *
                             lattice_sites(c, extent, h, 2);
        return fmin(count, sites);
    }
    if (c->kind == BDL_CREATE_RANDOM && c->count <= 0)
        return floor(
            c->volume_fraction * bdl_create_region_volume(c) /
                (bdl_species_volume(s, s->diameter) * bdl_species_parcel_count(s, s->diameter)) +
            0.5);
    return c->count > 0 ? (double)c->count : 0.0;
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
        double vp = bdl_species_volume(s, d) * bdl_species_parcel_count(s, d);
        double h = bdl_species_is_parcel(s) ? lattice_spacing(def, s) : d;
        if (def->kind == BDL_CREATE_RANDOM)
            total += (long)(def->volume_fraction * bdl_create_region_volume(def) / vp) + 1;
        else if (def->kind == BDL_CREATE_LATTICE)
            total += (long)(bdl_create_region_volume(def) / (h * h * h)) + 1;
        else
            total += count_rows(def->file);
    }
    return total;
}
