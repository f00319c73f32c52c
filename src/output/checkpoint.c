#include "output/checkpoint.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cfd/gas.h"
#include "core/file.h"

// Version 2: the gas state and the inlet scale among the live parameters. 3: particles that left
// through an outlet. 4: force and torque side by side in one record per particle.
static const char magic[8] = {'B', 'D', 'L', 'C', 'K', 'P', 'T', '5'};

/// Fingerprint of the scene quantities a checkpoint depends on (species, walls, law, counts).
static uint64_t scene_fingerprint(const bdl_scene *s)
{
    uint64_t h = BDL_HASH_INIT;
    int counts[4] = {s->species_count, s->wall_count, s->create_count, (int)s->law};
    h = bdl_hash_bytes(h, counts, sizeof counts);
    for (int k = 0; k < s->species_count; ++k) {
        double v[4] = {s->species[k].diameter, s->species[k].density, s->species[k].diameter_min,
                       s->species[k].diameter_max};
        h = bdl_hash_bytes(h, v, sizeof v);
    }
    for (int k = 0; k < s->wall_count; ++k) {
        int kind = (int)s->walls[k].kind;
        h = bdl_hash_bytes(h, &kind, sizeof kind);
    }
    if (s->gas.enabled)
        h = bdl_hash_bytes(h, &s->gas.cells, sizeof s->gas.cells);
    for (int k = 0; k < s->species_count; ++k)
        if (s->species[k].shape == BDL_SHAPE_ROD) { // spheres' fingerprints stay as they were
            double rod[2] = {(double)k, s->species[k].length};
            h = bdl_hash_bytes(h, rod, sizeof rod);
        }
    return h;
}

typedef struct writer {
    FILE *f;
    int ok;
} writer;

static void put(writer *w, const void *data, size_t size)
{
    if (w->ok && size > 0 && fwrite(data, 1, size, w->f) != size)
        w->ok = 0;
}

typedef struct reader {
    FILE *f;
    int ok;
} reader;

static void get(reader *r, void *data, size_t size)
{
    if (r->ok && size > 0 && fread(data, 1, size, r->f) != size)
        r->ok = 0;
}

/// The scalar fields saved and restored, in file order.
// clang-format off
#define SCALARS(X) \
    X(time) X(step) X(dt) X(rng) X(poured) X(live) X(wall_work) X(inserted_energy) \
    X(damping_work) X(energy0) X(contact_time) X(contact_time_dt_ratio) X(removed) \
    X(removed_mass) X(removed_energy)
// clang-format on

/// One array of the saved state.
typedef struct field {
    void *data;
    size_t bytes;
} field;

#define MAX_FIELDS 64

/// The arrays of the state in file order, for the counts the world holds now. Save and load walk
/// the same table, so the two cannot drift apart.
static int state_fields(bdl_world *w, field *f)
{
    bdl_particles *p = &w->particles;
    bdl_neighbor *nb = &w->neighbor;
    size_t n = (size_t)p->count, np = (size_t)nb->pair_count, nw = (size_t)nb->wall_pair_count;
    size_t v = sizeof(bdl_vec3), i32 = sizeof(int32_t);
    int k = 0;
    bdl_particle_array arrays[BDL_PARTICLE_ARRAYS];
    int count = bdl_particles_arrays(p, BDL_ARRAYS_ALWAYS, arrays);
    for (int a = 0; a < count; ++a)
        f[k++] = (field){arrays[a].data, n * arrays[a].element};
    f[k++] = (field){w->coordination, n};
    f[k++] = (field){nb->wall_offset_at_build, sizeof nb->wall_offset_at_build};
    f[k++] = (field){nb->start, (n + 1) * i32};
    f[k++] = (field){nb->partner, np * i32};
    f[k++] = (field){nb->touching, np};
    if (nb->history)
        f[k++] = (field){nb->history, np * v};
    f[k++] = (field){nb->wall_start, (n + 1) * i32};
    f[k++] = (field){nb->wall_prim, nw * i32};
    f[k++] = (field){nb->wall_history, nw * v};
    f[k++] = (field){nb->wall_force, nw * v};
    f[k++] = (field){nb->wall_touching, nw};
    // The gas's forces on the particles, held between gas steps; the rods' orientations.
    count = bdl_particles_arrays(p, BDL_ARRAYS_WITH_GAS | BDL_ARRAYS_WITH_RODS, arrays);
    for (int a = 0; a < count; ++a)
        f[k++] = (field){arrays[a].data, n * arrays[a].element};
    bdl_gas *g = w->gas;
    if (g) {
        const size_t cells = (size_t)g->grid.size * sizeof(double);
        f[k++] = (field){&w->gas_every, sizeof w->gas_every};
        f[k++] = (field){&w->gas_next, sizeof w->gas_next};
        f[k++] = (field){&w->gas_steps, sizeof w->gas_steps};
        f[k++] = (field){&w->gas_stable, sizeof w->gas_stable};
        f[k++] = (field){&w->gas_work, sizeof w->gas_work};
        f[k++] = (field){w->particle_drag, sizeof w->particle_drag};
        f[k++] = (field){w->gas_drag, sizeof w->gas_drag};
        f[k++] = (field){&g->time, sizeof g->time};
        f[k++] = (field){&g->steps, sizeof g->steps};
        f[k++] = (field){&g->last_solve, sizeof g->last_solve};
        f[k++] = (field){&g->mass_imbalance, sizeof g->mass_imbalance};
        for (int a = 0; a < 3; ++a)
            f[k++] = (field){g->u[a], cells};
        f[k++] = (field){g->p, cells};
        f[k++] = (field){g->eps, cells};
        f[k++] = (field){g->eps_old, cells};
    }
    return k;
}

bdl_result bdl_checkpoint_save(const bdl_world *w, const char *path)
{
    bdl_atomic_file af;
    bdl_result res = bdl_atomic_open(&af, path);
    if (res != BDL_OK)
        return res;
    writer out = {af.file, 1};
    const bdl_particles *p = &w->particles;
    const bdl_neighbor *nb = &w->neighbor;
    uint64_t fp = scene_fingerprint(&w->scene);
    put(&out, magic, sizeof magic);
    put(&out, &fp, sizeof fp);
#define PUT_SCALAR(name) put(&out, &w->name, sizeof w->name);
    SCALARS(PUT_SCALAR)
#undef PUT_SCALAR
    long counts[7] = {p->count,   (long)p->next_id, nb->pair_count, nb->wall_pair_count,
                      nb->builds, nb->count,        nb->version};
    put(&out, counts, sizeof counts);
    field f[MAX_FIELDS];
    // The table takes a mutable world; saving only reads through it.
    int count = state_fields((bdl_world *)w, f);
    for (int k = 0; k < count; ++k)
        put(&out, f[k].data, f[k].bytes);
    put(&out, magic, sizeof magic);
    if (!out.ok) {
        bdl_atomic_abort(&af);
        return BDL_ERR_IO;
    }
    return bdl_atomic_commit(&af);
}

static bdl_result fail(char *why, size_t len, const char *path, const char *what)
{
    snprintf(why, len, "checkpoint '%s': %s", path, what);
    return BDL_ERR_CHECKPOINT;
}

bdl_result bdl_checkpoint_load(bdl_world *w, const char *path, char *why, size_t why_len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return fail(why, why_len, path, "cannot be opened");
    reader in = {f, 1};
    char m[8];
    uint64_t fp = 0;
    get(&in, m, sizeof m);
    get(&in, &fp, sizeof fp);
    if (in.ok && memcmp(m, magic, sizeof magic - 1) == 0 && m[7] != magic[7]) {
        fclose(f);
        return fail(why, why_len, path,
                    "was written by another version of bedlam (checkpoint format differs)");
    }
    if (!in.ok || memcmp(m, magic, sizeof magic) != 0) {
        fclose(f);
        return fail(why, why_len, path, "is not a bedlam checkpoint (bad magic)");
    }
    if (fp != scene_fingerprint(&w->scene)) {
        fclose(f);
        return fail(why, why_len, path,
                    "was written for a different scene (species, walls or law differ)");
    }
#define GET_SCALAR(name) get(&in, &w->name, sizeof w->name);
    SCALARS(GET_SCALAR)
#undef GET_SCALAR
    long counts[7];
    get(&in, counts, sizeof counts);
    if (!in.ok || counts[0] < 0 || counts[2] < 0 || counts[3] < 0 || counts[0] > (1L << 31)) {
        fclose(f);
        return fail(why, why_len, path, "is truncated or damaged");
    }
    bdl_particles *p = &w->particles;
    bdl_neighbor *nb = &w->neighbor;
    if (bdl_particles_reserve(p, counts[0] + 1) != BDL_OK ||
        bdl_neighbor_reserve(nb, counts[0], counts[2], counts[3]) != BDL_OK) {
        fclose(f);
        return BDL_ERR_NOMEM;
    }
    uint8_t *coord = realloc(w->coordination, (size_t)p->capacity);
    if (!coord) {
        fclose(f);
        return BDL_ERR_NOMEM;
    }
    w->coordination = coord;
    w->coordination_capacity = p->capacity;
    p->count = counts[0];
    p->next_id = (uint32_t)counts[1];
    nb->pair_count = counts[2];
    nb->wall_pair_count = counts[3];
    nb->builds = counts[4];
    nb->count = counts[5];
    nb->version = counts[6];
    w->force_work.version = -1; // derived from the lists: rebuilt on the next step
    field fields[MAX_FIELDS];
    int count = state_fields(w, fields);
    for (int k = 0; k < count; ++k)
        get(&in, fields[k].data, fields[k].bytes);
    get(&in, m, sizeof m);
    fclose(f);
    if (!in.ok || memcmp(m, magic, sizeof magic) != 0)
        return fail(why, why_len, path, "is truncated or damaged");
    for (long i = 0; i < p->count; ++i)
        if (p->species[i] < 0 || p->species[i] >= w->scene.species_count)
            return fail(why, why_len, path, "holds a particle of an unknown species");
    bdl_world_apply_live(w);
    return BDL_OK;
}
