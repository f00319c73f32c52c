// bedlam — the scene a checkpoint was written for, and how it compares with the scene it is
// resumed with.
//
// The state of a checkpoint means something only in a world of the same make: the same species
// (their particles' sizes and masses, their shapes, which decide the arrays saved), the same walls
// (whose primitives the wall contacts name), the same creators (whose pour counters are saved),
// the same contact law, sliding friction or none (the tangential history is saved only with it)
// and the same gas grid (its fields are saved cell by cell), and the same solids phases on the
// grid (their number, diameters and densities: their fractions are saved). A difference there
// refuses the checkpoint and names what differs. The contact parameters (stiffness, Young's
// modulus, restitution, friction ...) may change on a resume: they are listed, and the run reports
// them and steps with the time step of the scene (docs/checkpoints.md).
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include "output/checkpoint_parts.h"

/// The counts and choices at the head of the record.
enum {
    R_SPECIES,
    R_WALLS,
    R_CREATES,
    R_PAIRS,
    R_LAW,
    R_DAMPING,
    R_ROLLING,
    R_FRICTION,
    R_RODS,
    R_GAS,
    R_PHASES, ///< solids phases on the grid (0 without)
    R_HEAD
};

/// The material keys in the record's order, with the unit a message gives their values in.
static const struct {
    const char *key, *unit;
    size_t offset;
} material_keys[] = {
    {"youngs_modulus", " Pa", offsetof(bdl_material, youngs_modulus)},
    {"poisson_ratio", "", offsetof(bdl_material, poisson_ratio)},
    {"stiffness", " N/m", offsetof(bdl_material, stiffness)},
    {"tangential_stiffness", " N/m", offsetof(bdl_material, tangential_stiffness)},
    {"restitution", "", offsetof(bdl_material, restitution)},
    {"tangential_damping_ratio", "", offsetof(bdl_material, tangential_damping_ratio)},
    {"friction", "", offsetof(bdl_material, friction)},
    {"rolling_friction", "", offsetof(bdl_material, rolling_friction)},
};
#define MATERIAL_KEYS ((int)(sizeof material_keys / sizeof material_keys[0]))

/// A species as the record holds it.
typedef struct saved_species {
    int32_t shape, size_dist;
    double size[6]; ///< diameter, diameter_min, diameter_max, length, density, background_damping
    double material[MATERIAL_KEYS];
} saved_species;

static const char *const size_keys[6] = {"diameter", "diameter_min", "diameter_max",
                                         "length",   "density",      "background_damping"};
static const char *const size_units[6] = {" m", " m", " m", " m", " kg/m^3", " 1/s"};

/// A [pair A B] override as the record holds it.
typedef struct saved_pair {
    int32_t species[2], has[4];
    double value[4]; ///< restitution, friction, rolling_friction, stiffness
} saved_pair;

static const char *const pair_keys[4] = {"restitution", "friction", "rolling_friction",
                                         "stiffness"};

/// The whole record.
typedef struct record {
    int32_t head[R_HEAD];
    double cells[3];
    saved_species species[BDL_MAX_SPECIES];
    int32_t wall_kind[BDL_MAX_WALLS];
    double wall_material[BDL_MAX_WALLS][MATERIAL_KEYS];
    saved_pair pairs[BDL_MAX_PAIRS];
    int32_t create_kind[BDL_MAX_CREATES];
    double phases[BDL_SOLIDS_PHASES][3]; ///< each solids phase's diameter, density, restitution
} record;

static const char *const phase_keys[3] = {"diameter", "density", "restitution"};

/// "[phase NAME]" for phase m of a scene with [phase] sections, "[solids]" for one phase.
static const char *phase_name(const bdl_scene *sc, int m, char *buf, size_t len)
{
    if (sc->solids.phase_count == 0)
        return "[solids]";
    snprintf(buf, len, "[phase %s]", sc->solids.phases[m].name);
    return buf;
}
static const char *const phase_units[3] = {" m", " kg/m^3", ""};

static void material_values(const bdl_material *m, double *v)
{
    for (int k = 0; k < MATERIAL_KEYS; ++k)
        memcpy(&v[k], (const char *)m + material_keys[k].offset, sizeof(double));
}

static saved_species species_of(const bdl_species_def *s)
{
    saved_species r = {.shape = (int32_t)s->shape,
                       .size_dist = (int32_t)s->size_dist,
                       .size = {s->diameter, s->diameter_min, s->diameter_max, s->length,
                                s->density, s->background_damping}};
    material_values(&s->material, r.material);
    return r;
}

static saved_pair pair_of(const bdl_pair_def *p)
{
    return (saved_pair){
        {p->species_a, p->species_b},
        {p->has_restitution, p->has_friction, p->has_rolling_friction, p->has_stiffness},
        {p->restitution, p->friction, p->rolling_friction, p->stiffness}};
}

/// The record of the world's scene (the gas grid's cells are zero without a gas).
static void record_of(const bdl_world *w, record *r)
{
    const bdl_scene *s = &w->scene;
    memset(r, 0, sizeof *r);
    const int32_t head[R_HEAD] = {s->species_count,
                                  s->wall_count,
                                  s->create_count,
                                  s->pair_count,
                                  (int32_t)s->law,
                                  (int32_t)s->damping,
                                  (int32_t)s->rolling,
                                  w->friction,
                                  w->particles.rods,
                                  w->gas != NULL,
                                  w->solids ? w->solids->count : 0};
    memcpy(r->head, head, sizeof head);
    if (w->gas)
        r->cells[0] = s->gas.cells.x, r->cells[1] = s->gas.cells.y, r->cells[2] = s->gas.cells.z;
    for (int k = 0; k < s->species_count; ++k)
        r->species[k] = species_of(&s->species[k]);
    for (int k = 0; k < s->wall_count; ++k) {
        r->wall_kind[k] = (int32_t)s->walls[k].kind;
        material_values(&s->walls[k].material, r->wall_material[k]);
    }
    for (int k = 0; k < s->pair_count; ++k)
        r->pairs[k] = pair_of(&s->pairs[k]);
    for (int k = 0; k < s->create_count; ++k)
        r->create_kind[k] = (int32_t)s->creates[k].kind;
    for (int m = 0; w->solids && m < w->solids->count; ++m) {
        const bdl_solids_def *d = &w->solids->phase[m].def;
        r->phases[m][0] = d->diameter, r->phases[m][1] = d->density;
        r->phases[m][2] = d->restitution;
    }
}

/// The record's fields in file order, for `r`'s counts; the writer and the reader walk the same
/// list. Each entry is one run of bytes without padding.
static int record_fields(record *r, void **data, size_t *bytes)
{
    int k = 0;
#define FIELD(p, n) (data[k] = (p), bytes[k] = (n), ++k)
    FIELD(r->head, sizeof r->head);
    FIELD(r->cells, sizeof r->cells);
    for (int s = 0; s < r->head[R_SPECIES]; ++s) {
        FIELD(&r->species[s].shape, 2 * sizeof(int32_t));
        FIELD(r->species[s].size, sizeof r->species[s].size);
        FIELD(r->species[s].material, sizeof r->species[s].material);
    }
    for (int s = 0; s < r->head[R_WALLS]; ++s) {
        FIELD(&r->wall_kind[s], sizeof(int32_t));
        FIELD(r->wall_material[s], sizeof r->wall_material[s]);
    }
    for (int s = 0; s < r->head[R_PAIRS]; ++s) {
        FIELD(r->pairs[s].species, sizeof r->pairs[s].species + sizeof r->pairs[s].has);
        FIELD(r->pairs[s].value, sizeof r->pairs[s].value);
    }
    FIELD(r->create_kind, (size_t)r->head[R_CREATES] * sizeof(int32_t));
    FIELD(r->phases, (size_t)r->head[R_PHASES] * sizeof r->phases[0]);
#undef FIELD
    return k;
}

#define MAX_RECORD_FIELDS (2 + 3 * BDL_MAX_SPECIES + 2 * BDL_MAX_WALLS + 2 * BDL_MAX_PAIRS + 2)

void bdl_ckpt_put_scene(bdl_ckpt_writer *out, const bdl_world *w)
{
    record r;
    record_of(w, &r);
    void *data[MAX_RECORD_FIELDS];
    size_t bytes[MAX_RECORD_FIELDS];
    const int n = record_fields(&r, data, bytes);
    for (int k = 0; k < n; ++k)
        bdl_ckpt_put(out, data[k], bytes[k]);
}

/// Reads a record; 0 when it is short or its counts are out of range.
static int read_record(bdl_ckpt_reader *in, record *r)
{
    memset(r, 0, sizeof *r);
    bdl_ckpt_get(in, r->head, sizeof r->head);
    const int32_t *h = r->head;
    if (!in->ok || h[R_SPECIES] < 0 || h[R_SPECIES] > BDL_MAX_SPECIES || h[R_WALLS] < 0 ||
        h[R_WALLS] > BDL_MAX_WALLS || h[R_CREATES] < 0 || h[R_CREATES] > BDL_MAX_CREATES ||
        h[R_PAIRS] < 0 || h[R_PAIRS] > BDL_MAX_PAIRS || h[R_PHASES] < 0 ||
        h[R_PHASES] > BDL_SOLIDS_PHASES)
        return 0;
    void *data[MAX_RECORD_FIELDS];
    size_t bytes[MAX_RECORD_FIELDS];
    const int n = record_fields(r, data, bytes);
    for (int k = 1; k < n; ++k) // the head is in already
        bdl_ckpt_get(in, data[k], bytes[k]);
    return in->ok;
}

/// snprintf appended to what `buf` holds, after "; " when it holds something.
static void append(char *buf, size_t len, const char *format, ...)
{
    size_t used = strlen(buf);
    if (used + 3 >= len)
        return;
    if (used > 0) {
        memcpy(buf + used, "; ", 3);
        used += 2;
    }
    va_list args;
    va_start(args, format);
    vsnprintf(buf + used, len - used, format, args);
    va_end(args);
}

/// The word of a choice from its NULL-terminated list, or "value N" for a number outside it.
static const char *word(const char *const *names, int32_t value, char *buf, size_t len)
{
    for (int32_t k = 0; names[k]; ++k)
        if (k == value)
            return names[k];
    snprintf(buf, len, "value %d", (int)value);
    return buf;
}

/// The numbers of things and the choices the state's layout depends on; 0 with the reason.
static int check_layout(const record *r, const record *now, char *why, size_t len)
{
    const record *s = now;
    static const char *const what[R_PAIRS + 1] = {"species", "walls", "creators",
                                                  "[pair] sections"};
    for (int k = R_SPECIES; k <= R_PAIRS; ++k)
        if (r->head[k] != s->head[k]) {
            snprintf(why, len, "%d %s in the checkpoint, %d in the scene", (int)r->head[k], what[k],
                     (int)s->head[k]);
            return 0;
        }
    char a[32], b[32];
    if (r->head[R_LAW] != s->head[R_LAW]) {
        snprintf(why, len, "[contact] law = %s in the checkpoint, %s in the scene",
                 word(bdl_normal_law_names, r->head[R_LAW], a, sizeof a),
                 word(bdl_normal_law_names, s->head[R_LAW], b, sizeof b));
        return 0;
    }
    static const char *const off_on[3] = {"none", "some", NULL};
    if (r->head[R_FRICTION] != s->head[R_FRICTION] || r->head[R_RODS] != s->head[R_RODS] ||
        r->head[R_GAS] != s->head[R_GAS]) {
        const int k = r->head[R_FRICTION] != s->head[R_FRICTION] ? R_FRICTION
                      : r->head[R_RODS] != s->head[R_RODS]       ? R_RODS
                                                                 : R_GAS;
        const char *name = k == R_FRICTION ? "sliding friction (tangential history)"
                           : k == R_RODS   ? "rods"
                                           : "a gas";
        snprintf(why, len, "%s: %s in the checkpoint, %s in the scene", name,
                 word(off_on, r->head[k], a, sizeof a), off_on[s->head[k] != 0]);
        return 0;
    }
    if (r->head[R_PHASES] != s->head[R_PHASES]) {
        snprintf(why, len, "%d solids phases in the checkpoint, %d in the scene",
                 (int)r->head[R_PHASES], (int)s->head[R_PHASES]);
        return 0;
    }
    if (memcmp(r->cells, s->cells, sizeof s->cells) != 0) {
        snprintf(why, len,
                 "gas grid %g x %g x %g cells in the checkpoint, %g x %g x %g in the scene",
                 r->cells[0], r->cells[1], r->cells[2], s->cells[0], s->cells[1], s->cells[2]);
        return 0;
    }
    return 1;
}

/// Species' shapes, sizes and densities, walls' and creators' kinds; 0 with the reason.
static int check_things(const record *r, const record *now, const bdl_world *w, char *why,
                        size_t len)
{
    const bdl_scene *sc = &w->scene;
    char a[32], b[32];
    for (int k = 0; k < sc->species_count; ++k) {
        const saved_species *x = &r->species[k], y = species_of(&sc->species[k]);
        const char *name = sc->species[k].name;
        if (x->shape != y.shape || x->size_dist != y.size_dist) {
            const int shape = x->shape != y.shape;
            const char *const *names = shape ? bdl_shape_names : bdl_size_dist_names;
            snprintf(why, len, "species '%s': %s %s in the checkpoint, %s in the scene", name,
                     shape ? "shape" : "distribution",
                     word(names, shape ? x->shape : x->size_dist, a, sizeof a),
                     names[shape ? y.shape : y.size_dist]);
            return 0;
        }
        for (int q = 0; q < 5; ++q) // sizes and density: the particles' in the state
            if (!(x->size[q] == y.size[q])) {
                snprintf(why, len, "species '%s': %s %g%s in the checkpoint, %g%s in the scene",
                         name, size_keys[q], x->size[q], size_units[q], y.size[q], size_units[q]);
                return 0;
            }
    }
    for (int k = 0; k < sc->wall_count; ++k)
        if (r->wall_kind[k] != (int32_t)sc->walls[k].kind) {
            snprintf(why, len, "wall '%s': a %s in the checkpoint, a %s in the scene",
                     sc->walls[k].name, word(bdl_wall_kind_names, r->wall_kind[k], a, sizeof a),
                     bdl_wall_kind_names[sc->walls[k].kind]);
            return 0;
        }
    for (int m = 0; m < now->head[R_PHASES]; ++m)
        for (int q = 0; q < 2; ++q) // sizes and densities: the state's fractions are of them
            if (!(r->phases[m][q] == now->phases[m][q])) {
                char label[BDL_NAME_LEN + 16];
                snprintf(why, len, "%s: %s %g%s in the checkpoint, %g%s in the scene",
                         phase_name(sc, m, label, sizeof label), phase_keys[q], r->phases[m][q],
                         phase_units[q], now->phases[m][q], phase_units[q]);
                return 0;
            }
    for (int k = 0; k < sc->create_count; ++k)
        if (r->create_kind[k] != (int32_t)sc->creates[k].kind) {
            snprintf(why, len, "[create %s]: type %s in the checkpoint, %s in the scene",
                     sc->creates[k].name,
                     word(bdl_create_kind_names, r->create_kind[k], b, sizeof b),
                     bdl_create_kind_names[sc->creates[k].kind]);
            return 0;
        }
    return 1;
}

/// A material value for a message: the number and its unit, or "not given".
static const char *material_text(double v, const char *unit, char *buf, size_t len)
{
    if (v < 0.0)
        snprintf(buf, len, "not given");
    else
        snprintf(buf, len, "%g%s", v, unit);
    return buf;
}

/// Appends to `changes` every material key of `who` whose value differs.
static void note_material(const char *who, const double *saved, const double *now, char *changes,
                          size_t len)
{
    for (int q = 0; q < MATERIAL_KEYS; ++q) {
        if (saved[q] == now[q])
            continue;
        char a[48], b[48];
        append(changes, len, "%s: %s %s in the checkpoint, %s in the scene", who,
               material_keys[q].key, material_text(saved[q], material_keys[q].unit, a, sizeof a),
               material_text(now[q], material_keys[q].unit, b, sizeof b));
    }
}

/// Lists the contact parameters that differ: species' and walls' materials, background damping,
/// [pair] overrides, the damping and rolling models.
static void note_changes(const record *r, const record *now, const bdl_world *w, char *changes,
                         size_t len)
{
    const bdl_scene *sc = &w->scene;
    char who[2 * BDL_NAME_LEN + 16], a[32];
    for (int k = 0; k < sc->species_count; ++k) {
        const saved_species y = species_of(&sc->species[k]);
        snprintf(who, sizeof who, "species '%s'", sc->species[k].name);
        note_material(who, r->species[k].material, y.material, changes, len);
        if (!(r->species[k].size[5] == y.size[5]))
            append(changes, len,
                   "%s: background_damping %g 1/s in the checkpoint, %g 1/s in the "
                   "scene",
                   who, r->species[k].size[5], y.size[5]);
    }
    for (int k = 0; k < sc->wall_count; ++k) {
        double values[MATERIAL_KEYS];
        material_values(&sc->walls[k].material, values);
        snprintf(who, sizeof who, "wall '%s'", sc->walls[k].name);
        note_material(who, r->wall_material[k], values, changes, len);
    }
    for (int k = 0; k < sc->pair_count; ++k) {
        const saved_pair x = r->pairs[k], y = pair_of(&sc->pairs[k]);
        snprintf(who, sizeof who, "[pair %s %s]", sc->species[y.species[0]].name,
                 sc->species[y.species[1]].name);
        if (x.species[0] != y.species[0] || x.species[1] != y.species[1]) {
            append(changes, len, "%s: another pair of species in the checkpoint", who);
            continue;
        }
        for (int q = 0; q < 4; ++q) {
            if (x.has[q] == y.has[q] && (!y.has[q] || x.value[q] == y.value[q]))
                continue;
            char b[48];
            append(changes, len, "%s %s: %s in the checkpoint, %s in the scene", who, pair_keys[q],
                   material_text(x.has[q] ? x.value[q] : -1.0, "", a, sizeof a),
                   material_text(y.has[q] ? y.value[q] : -1.0, "", b, sizeof b));
        }
    }
    for (int m = 0; m < now->head[R_PHASES]; ++m)
        if (!(r->phases[m][2] == now->phases[m][2]))
            append(changes, len,
                   "%s: %s %g in the checkpoint, %g in the scene (the effective one, with "
                   "friction)",
                   phase_name(sc, m, who, sizeof who), phase_keys[2], r->phases[m][2],
                   now->phases[m][2]);
    if (r->head[R_DAMPING] != (int32_t)sc->damping)
        append(changes, len, "[contact] damping = %s in the checkpoint, %s in the scene",
               word(bdl_damping_mode_names, r->head[R_DAMPING], a, sizeof a),
               bdl_damping_mode_names[sc->damping]);
    if (r->head[R_ROLLING] != (int32_t)sc->rolling)
        append(changes, len, "[contact] rolling = %s in the checkpoint, %s in the scene",
               word(bdl_rolling_model_names, r->head[R_ROLLING], a, sizeof a),
               bdl_rolling_model_names[sc->rolling]);
}

int bdl_ckpt_check_scene(bdl_ckpt_reader *in, const bdl_world *w, char *why, size_t why_len,
                         char *changes, size_t changes_len)
{
    record r;
    changes[0] = '\0';
    if (!read_record(in, &r)) {
        snprintf(why, why_len, "its record of the scene is damaged");
        return 0;
    }
    char what[512];
    record now; // the scene's own record, to compare with
    record_of(w, &now);
    if (!check_layout(&r, &now, what, sizeof what) ||
        !check_things(&r, &now, w, what, sizeof what)) {
        snprintf(why, why_len, "does not match the scene: %s", what);
        return 0;
    }
    note_changes(&r, &now, w, changes, changes_len);
    return 1;
}
