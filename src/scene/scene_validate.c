// bedlam — cross-checks of a parsed scene, and the values derived from it.
//
// Runs after the file and the --set overrides, so that every rule sees the final values. The
// per-key rules that the key table can express (required keys, keys that apply only to some
// wall or creator types, unit vectors) are checked generically; the rest are written out below.
// Checks that need the particles themselves (overlaps, particles outside the domain) belong to
// the solver.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/file.h"
#include "scene/scene_internal.h"

enum { TEXT_LEN = 128 };

static const double pi = 3.14159265358979323846;

static const char *axis_name(int axis) { return axis == 0 ? "x" : (axis == 1 ? "y" : "z"); }

static int given(const bdl_scene_section *s, const bdl_scene_key *key)
{
    return s->key_line[bdl_scene_key_index(key)] != 0;
}

static const bdl_scene_key *key_of(const bdl_scene_section *s, const char *name)
{
    return bdl_scene_key_find(s->kind, name); // only called with names of the table
}

static bdl_vec3 *vector_of(bdl_scene_parser *p, bdl_scene_section *s, const char *name)
{
    return bdl_scene_key_field(key_of(s, name), p->scene, s);
}

/// Fails at a given key's line, showing its current value; `with_allowed` adds the range.
static void fail_at_key(bdl_scene_parser *p, bdl_scene_section *s, const char *name,
                        int with_allowed, const char *what)
{
    const bdl_scene_key *key = key_of(s, name);
    char value[TEXT_LEN];
    bdl_scene_key_value_text(key, p->scene, s, value, sizeof value);
    int line = s->key_line[bdl_scene_key_index(key)];
    bdl_scene_fail(p,
                   &(bdl_scene_where){.line = line ? line : s->line,
                                      .title = s->title,
                                      .key = name,
                                      .value = line ? value : NULL,
                                      .allowed = with_allowed ? key : NULL},
                   "%s", what);
}

/// Fails at the section header for a key that is missing; `why` says why it is needed.
static void fail_missing(bdl_scene_parser *p, bdl_scene_section *s, const char *name,
                         const char *why)
{
    char what[TEXT_LEN * 2];
    snprintf(what, sizeof what, "missing required key%s%s", why,
             s->line == 0 ? " (the section is not in the file)" : "");
    bdl_scene_fail(p,
                   &(bdl_scene_where){
                       .line = s->line, .title = s->title, .key = name, .allowed = key_of(s, name)},
                   "%s", what);
}

/// Value names of the selector enum for the bits of `mask`: "plane, cylinder".
static void mask_text(const bdl_scene_key *selector, unsigned mask, char *buf, size_t size)
{
    buf[0] = '\0';
    for (int i = 0; selector->enum_names[i]; ++i)
        if (mask & (1u << i))
            snprintf(buf + strlen(buf), size - strlen(buf), "%s%s", buf[0] ? ", " : "",
                     selector->enum_names[i]);
}

/// Required keys, keys that do not apply to the chosen type, and unit vectors.
static void check_table_rules(bdl_scene_parser *p, bdl_scene_section *s)
{
    // Parcels have no contacts: a species of them needs no restitution.
    const int parcels =
        s->kind == BDL_SECTION_SPECIES && bdl_species_is_parcel(&p->scene->species[s->index]);
    for (int i = 0; i < bdl_scene_key_count && !p->failed; ++i) {
        const bdl_scene_key *key = &bdl_scene_keys[i];
        if (key->section != s->kind)
            continue;
        const bdl_scene_key *selector = key->selector ? key_of(s, key->selector) : NULL;
        int choice = selector ? *(int *)bdl_scene_key_field(selector, p->scene, s) : 0;
        unsigned bit = 1u << choice;
        char why[TEXT_LEN] = "";
        if (selector)
            snprintf(why, sizeof why, " for %s = %s", selector->name, selector->enum_names[choice]);
        int required = key->required == BDL_REQUIRED_ALWAYS || (selector && (key->required & bit));
        if (parcels && strcmp(key->name, "restitution") == 0) {
            if (!given(s, key))
                p->scene->species[s->index].material.restitution = 1.0;
            required = 0;
        }
        if (!given(s, key)) {
            if (required)
                fail_missing(p, s, key->name, key->required == BDL_REQUIRED_ALWAYS ? "" : why);
            continue;
        }
        if (selector && !(key->applies & bit)) {
            char only[TEXT_LEN], what[TEXT_LEN * 3];
            mask_text(selector, key->applies, only, sizeof only);
            snprintf(what, sizeof what, "does not apply%s; only for %s = %s", why, selector->name,
                     only);
            fail_at_key(p, s, key->name, 0, what);
            continue;
        }
        if (key->normalise) {
            bdl_vec3 *v = bdl_scene_key_field(key, p->scene, s);
            if (bdl_v3_len(*v) == 0.0)
                fail_at_key(p, s, key->name, 1, "zero vector has no direction");
            else
                *v = bdl_v3_normalize(*v);
        }
    }
}

/// min < max on every axis; fails at `max_name`.
static void check_box(bdl_scene_parser *p, bdl_scene_section *s, const char *min_name,
                      const char *max_name)
{
    bdl_vec3 lo = *vector_of(p, s, min_name), hi = *vector_of(p, s, max_name);
    for (int axis = 0; axis < 3 && !p->failed; ++axis) {
        if (!(bdl_v3_comp(hi, axis) > bdl_v3_comp(lo, axis))) {
            char what[TEXT_LEN];
            snprintf(what, sizeof what, "not larger than %s on the %s axis", min_name,
                     axis_name(axis));
            fail_at_key(p, s, max_name, 0, what);
        }
    }
}

/// Index of a species by name, or -1 with the "did you mean" and the list in `hint`.
static int find_species(const bdl_scene *scene, const char *name, char *hint, size_t size)
{
    bdl_suggestion suggestion;
    bdl_suggest_init(&suggestion, name);
    for (int i = 0; i < scene->species_count; ++i) {
        if (strcmp(scene->species[i].name, name) == 0)
            return i;
        bdl_suggest_consider(&suggestion, scene->species[i].name);
    }
    bdl_suggest_text(&suggestion, hint, size);
    snprintf(hint + strlen(hint), size - strlen(hint), "; allowed:");
    for (int i = 0; i < scene->species_count; ++i)
        snprintf(hint + strlen(hint), size - strlen(hint), "%s %s", i ? "," : "",
                 scene->species[i].name);
    return -1;
}

static void check_species(bdl_scene_parser *p, bdl_scene_section *s)
{
    bdl_species_def *sp = &p->scene->species[s->index];
    const int parcel = bdl_species_is_parcel(sp); // parcels have no contacts: no stiffness
    if (parcel && sp->parcel_particles > 0.0 && sp->parcel_volume > 0.0)
        fail_at_key(p, s, "parcel_volume", 0, "parcel_particles and parcel_volume are exclusive");
    if (parcel && sp->shape != BDL_SHAPE_SPHERE)
        fail_at_key(p, s, "shape", 0, "parcels are of spheres");
    if (!parcel && p->scene->law == BDL_LAW_HERTZ && !given(s, key_of(s, "youngs_modulus")))
        fail_missing(p, s, "youngs_modulus", " for [contact] law = hertz");
    if (!parcel && p->scene->law == BDL_LAW_LINEAR && !given(s, key_of(s, "stiffness")))
        fail_missing(p, s, "stiffness", " for [contact] law = linear");
    if (p->failed)
        return;
    if (sp->shape == BDL_SHAPE_ROD && !(sp->length > sp->diameter)) {
        fail_at_key(p, s, "length", 0, "must be longer than the diameter");
        return;
    }
    if (sp->shape == BDL_SHAPE_ROD && sp->size_dist != BDL_SIZE_SINGLE) {
        fail_at_key(p, s, "distribution", 0, "rods have one diameter and length: use single");
        return;
    }
    if (sp->size_dist == BDL_SIZE_SINGLE) {
        sp->diameter_min = sp->diameter_max = sp->diameter;
        return;
    }
    if (sp->size_dist == BDL_SIZE_NORMAL) {
        if (!given(s, key_of(s, "diameter_min")))
            sp->diameter_min = sp->diameter - 3.0 * sp->diameter_std;
        if (!given(s, key_of(s, "diameter_max")))
            sp->diameter_max = sp->diameter + 3.0 * sp->diameter_std;
        if (!(sp->diameter_min > 0.0)) {
            fail_at_key(p, s, "diameter_std", 0,
                        "diameter - 3 diameter_std is not > 0; give diameter_min explicitly");
            return;
        }
    }
    if (sp->diameter_min > sp->diameter)
        fail_at_key(p, s, "diameter_min", 0, "larger than diameter");
    else if (sp->diameter_max < sp->diameter)
        fail_at_key(p, s, "diameter_max", 0, "smaller than diameter");
}

static void check_pair(bdl_scene_parser *p, bdl_scene_section *s)
{
    bdl_pair_def *pair = &p->scene->pairs[s->index];
    int *indices[2] = {&pair->species_a, &pair->species_b};
    for (int i = 0; i < 2 && !p->failed; ++i) {
        char hint[512] = "";
        *indices[i] = find_species(p->scene, s->names[i], hint, sizeof hint);
        if (*indices[i] < 0)
            bdl_scene_fail(p, &(bdl_scene_where){.line = s->line, .title = s->title},
                           "unknown species '%s'%s", s->names[i], hint);
    }
}

/// A mesh wall's file is read and checked now, so that a bad mesh is named with its key.
static void check_mesh(bdl_scene_parser *p, bdl_scene_section *s, const bdl_wall_def *wall)
{
    for (int k = 0; k < p->scene->species_count; ++k)
        if (p->scene->species[k].shape == BDL_SHAPE_ROD) {
            fail_at_key(p, s, "type", 0,
                        "mesh, disk and cone walls hold spheres only (rods: plane, box or "
                        "cylinder walls)");
            return;
        }
    bdl_mesh m;
    char why[400], what[BDL_PATH_LEN + 420];
    if (bdl_wall_mesh_of(wall, &m, why, sizeof why) != BDL_OK) {
        if (wall->kind == BDL_WALL_MESH)
            snprintf(what, sizeof what, "'%s' %s", wall->file, why);
        else
            snprintf(what, sizeof what, "its triangles: %s", why);
        fail_at_key(p, s, wall->kind == BDL_WALL_MESH ? "file" : "type", 0, what);
        return;
    }
    bdl_mesh_free(&m);
}

/// A turning wall: triangles (mesh, disk, cone) turn about any axis; a cylinder must keep its
/// shape, turning about its own axis, and a plane about its normal; a box cannot turn.
static void check_rotation(bdl_scene_parser *p, bdl_scene_section *s, const bdl_wall_def *wall)
{
    const bdl_vec3 a = bdl_v3_normalize(wall->rotation_axis);
    const double tol = 1e-9;
    const char *why = NULL;
    if (wall->kind == BDL_WALL_MESH || wall->kind == BDL_WALL_DISK || wall->kind == BDL_WALL_CONE)
        return;
    if (wall->kind == BDL_WALL_CYLINDER) {
        const bdl_vec3 q = bdl_v3_sub(wall->rotation_center, wall->point);
        const double off = bdl_v3_len(bdl_v3_madd(q, wall->normal, -bdl_v3_dot(q, wall->normal)));
        if (fabs(fabs(bdl_v3_dot(a, wall->normal)) - 1.0) > tol)
            why = "an infinite cylinder turns only about its own axis: rotation_axis must be "
                  "parallel to axis (a cone wall with equal radii is a finite tube that turns "
                  "about any axis)";
        else if (off > tol * wall->radius)
            why = "an infinite cylinder turns only about its own axis: rotation_center must lie "
                  "on it";
    } else if (wall->kind == BDL_WALL_PLANE) {
        if (fabs(fabs(bdl_v3_dot(a, wall->normal)) - 1.0) > tol)
            why = "an infinite plane turns only about its normal: rotation_axis must be parallel "
                  "to normal (a disk or mesh turns about any axis)";
    } else {
        why = "a box cannot turn (make it of a mesh, which turns about any axis)";
    }
    if (why)
        fail_at_key(p, s, wall->kind == BDL_WALL_BOX ? "motion" : "rotation_axis", 0, why);
}

static void check_wall(bdl_scene_parser *p, bdl_scene_section *s)
{
    bdl_wall_def *wall = &p->scene->walls[s->index];
    if (wall->kind == BDL_WALL_BOX)
        check_box(p, s, "min", "max");
    if (wall->kind == BDL_WALL_DISK && !p->failed && !(wall->hole_radius < wall->radius))
        fail_at_key(p, s, "hole_radius", 0, "must be smaller than radius");
    if ((wall->kind == BDL_WALL_MESH || wall->kind == BDL_WALL_DISK ||
         wall->kind == BDL_WALL_CONE) &&
        !p->failed)
        check_mesh(p, s, wall);
    if (wall->motion == BDL_MOTION_ROTATE && !p->failed)
        check_rotation(p, s, wall);
    if (wall->motion == BDL_MOTION_MOVE && !p->failed && !(wall->stop > wall->start))
        fail_at_key(p, s, "stop", 0, "must be later than start");
    for (int a = 0; a < 3 && !p->failed; ++a) {
        if (wall->periodic[a] && !p->scene->periodic[a])
            fail_at_key(p, s, "periodic", 0, "names an axis that is not periodic in [domain]");
        else if (wall->periodic[a] && wall->motion == BDL_MOTION_ROTATE)
            fail_at_key(p, s, "periodic", 0, "a repeating wall cannot turn (motion = rotate)");
    }
    if (p->failed || wall->motion != BDL_MOTION_VIBRATE)
        return;
    if (wall->frame == BDL_FRAME_CONTAINER)
        for (int k = 0; k < p->scene->wall_count; ++k)
            if (k != s->index && p->scene->walls[k].motion != BDL_MOTION_NONE) {
                char what[160];
                snprintf(what, sizeof what,
                         "the container carries every wall: [wall %s] must have motion = none",
                         p->scene->walls[k].name);
                fail_at_key(p, s, "frame", 0, what);
                return;
            }
    int has_amplitude = given(s, key_of(s, "amplitude")), has_gamma = given(s, key_of(s, "gamma"));
    if (has_amplitude && has_gamma) {
        fail_at_key(p, s, "gamma", 0, "amplitude and gamma are exclusive; give one of them");
    } else if (!has_amplitude && !has_gamma) {
        fail_missing(p, s, "amplitude", " (or gamma) for motion = vibrate");
    } else if (has_gamma) {
        // Gamma = A w^2 / g  ->  A = Gamma g / w^2 with w = 2 pi f.
        double g = bdl_v3_len(p->scene->gravity);
        double omega = 2.0 * pi * wall->frequency;
        if (g == 0.0)
            fail_at_key(p, s, "gamma", 0, "needs a nonzero [run] gravity; give amplitude instead");
        else
            wall->amplitude = s->gamma * g / (omega * omega);
    }
}

/// Largest extent of a particle of a species: its diameter, or a rod's length [m]
/// (diameter_max is set for every distribution by now).
static double largest_diameter(const bdl_scene *scene, int species)
{
    return bdl_species_max_extent(&scene->species[species]);
}

static void check_region(bdl_scene_parser *p, bdl_scene_section *s, double diameter)
{
    const bdl_scene *scene = p->scene;
    check_box(p, s, "region_min", "region_max");
    bdl_vec3 lo = *vector_of(p, s, "region_min"), hi = *vector_of(p, s, "region_max");
    for (int axis = 0; axis < 3 && !p->failed; ++axis) {
        double dlo = bdl_v3_comp(scene->domain_min, axis);
        double dhi = bdl_v3_comp(scene->domain_max, axis);
        double tolerance = 1e-12 * fmax(fabs(dlo), fmax(fabs(dhi), dhi - dlo));
        char what[TEXT_LEN * 2];
        if (bdl_v3_comp(lo, axis) < dlo - tolerance) {
            snprintf(what, sizeof what, "outside the domain on the %s axis ([domain] min = %g)",
                     axis_name(axis), dlo);
            fail_at_key(p, s, "region_min", 0, what);
        } else if (bdl_v3_comp(hi, axis) > dhi + tolerance) {
            snprintf(what, sizeof what, "outside the domain on the %s axis ([domain] max = %g)",
                     axis_name(axis), dhi);
            fail_at_key(p, s, "region_max", 0, what);
        } else if (bdl_v3_comp(hi, axis) - bdl_v3_comp(lo, axis) < diameter) {
            snprintf(what, sizeof what,
                     "region narrower than the largest particle diameter (%g m) on the %s axis",
                     diameter, axis_name(axis));
            fail_at_key(p, s, "region_max", 0, what);
        }
    }
}

/// A mesh region: its file read and placed, closed, within the region's box; its volume kept.
static void check_region_mesh(bdl_scene_parser *p, bdl_scene_section *s, bdl_create_def *c)
{
    bdl_mesh m;
    char what[BDL_PATH_LEN + 480];
    if (bdl_create_region_mesh(c, &m, what, sizeof what) != BDL_OK) {
        fail_at_key(p, s, "region_file", 0, what);
        return;
    }
    int border_only = 0;
    const long border = bdl_mesh_unclosed_edge(&m, &border_only);
    bdl_vec3 lo = m.vertex[0], hi = m.vertex[0];
    for (long k = 1; k < m.vertex_count; ++k) {
        lo =
            bdl_v3(fmin(lo.x, m.vertex[k].x), fmin(lo.y, m.vertex[k].y), fmin(lo.z, m.vertex[k].z));
        hi =
            bdl_v3(fmax(hi.x, m.vertex[k].x), fmax(hi.y, m.vertex[k].y), fmax(hi.z, m.vertex[k].z));
    }
    const bdl_vec3 blo = c->region_min, bhi = c->region_max;
    if (border == -2) {
        fail_at_key(p, s, "region_file", 0, "needs more memory than there is");
    } else if (border >= 0) {
        const bdl_vec3 a = m.vertex[m.edge[border][0]], b = m.vertex[m.edge[border][1]];
        snprintf(what, sizeof what,
                 "'%s' is not a closed, consistently turned surface: the edge from (%g, %g, %g) "
                 "to (%g, %g, %g) %s (a region needs an inside)",
                 c->region_file, a.x, a.y, a.z, b.x, b.y, b.z,
                 border_only
                     ? "borders one triangle only"
                     : "is run the same way by its two triangles (they face opposite ways)");
        fail_at_key(p, s, "region_file", 0, what);
    } else if (lo.x < blo.x || lo.y < blo.y || lo.z < blo.z || hi.x > bhi.x || hi.y > bhi.y ||
               hi.z > bhi.z) {
        snprintf(what, sizeof what,
                 "the mesh, placed, spans (%g, %g, %g) to (%g, %g, %g): region_min and "
                 "region_max must enclose it",
                 lo.x, lo.y, lo.z, hi.x, hi.y, hi.z);
        fail_at_key(p, s, "region_file", 0, what);
    } else {
        c->region_volume = fabs(bdl_mesh_volume(&m));
    }
    bdl_mesh_free(&m);
}

/// Exactly one of two keys; `first` is named when both are missing.
static void check_one_of(bdl_scene_parser *p, bdl_scene_section *s, const char *first,
                         const char *second, const char *why)
{
    int has_first = given(s, key_of(s, first)), has_second = given(s, key_of(s, second));
    char what[TEXT_LEN];
    if (has_first && has_second) {
        snprintf(what, sizeof what, "%s and %s are exclusive; give one of them", first, second);
        fail_at_key(p, s, second, 0, what);
    } else if (!has_first && !has_second) {
        snprintf(what, sizeof what, " (or %s)%s", second, why);
        fail_missing(p, s, first, what);
    }
}

static void resolve_create_species(bdl_scene_parser *p, bdl_scene_section *s)
{
    bdl_create_def *create = &p->scene->creates[s->index];
    char hint[512] = "";
    if (given(s, key_of(s, "species"))) {
        create->species = find_species(p->scene, s->species_ref, hint, sizeof hint);
        if (create->species < 0) {
            char what[600];
            snprintf(what, sizeof what, "unknown species%s", hint);
            fail_at_key(p, s, "species", 0, what);
        }
    } else if (p->scene->species_count == 1) {
        create->species = 0;
    } else {
        find_species(p->scene, "", hint, sizeof hint);
        bdl_scene_fail(p, &(bdl_scene_where){.line = s->line, .title = s->title, .key = "species"},
                       "missing required key: the scene has %d species%s", p->scene->species_count,
                       hint);
    }
}

static void check_create(bdl_scene_parser *p, bdl_scene_section *s)
{
    bdl_create_def *create = &p->scene->creates[s->index];
    resolve_create_species(p, s);
    if (p->failed)
        return;
    double diameter = largest_diameter(p->scene, create->species);
    if (create->kind == BDL_CREATE_FILE) {
        // A FIFO, a device or a folder is refused before anything opens it (a FIFO would block).
        char why[TEXT_LEN * 2];
        FILE *file = bdl_open_regular(create->file, why, sizeof why);
        if (!file) {
            char what[TEXT_LEN * 3 + BDL_PATH_LEN];
            snprintf(what, sizeof what, "'%s' %s", create->file, why);
            fail_at_key(p, s, "file", 1, what);
        } else {
            fclose(file);
        }
        return;
    }
    if (create->kind == BDL_CREATE_RANDOM)
        check_one_of(p, s, "count", "volume_fraction", " for type = random");
    if (create->kind == BDL_CREATE_POUR && !(create->stop_time > create->start_time))
        fail_at_key(p, s, "stop_time", 0, "must be later than start_time");
    if (create->kind == BDL_CREATE_LATTICE && given(s, key_of(s, "spacing")) &&
        create->spacing < diameter)
        fail_at_key(p, s, "spacing", 0,
                    "smaller than the largest diameter: particles would overlap");
    if (!p->failed)
        check_region(p, s, diameter);
    if (!p->failed && create->region_shape == BDL_REGION_MESH)
        check_region_mesh(p, s, create);
}

/// True when the section is in the file or one of its keys was set.
static int section_used(const bdl_scene_section *s)
{
    if (s->line > 0)
        return 1;
    for (int k = 0; k < BDL_SCENE_KEY_CAPACITY; ++k)
        if (s->key_line[k] != 0)
            return 1;
    return 0;
}

/// The jet rectangle on every inlet side: jet_max above jet_min, and inside the face, on the two
/// axes along the face (the coordinate normal to the side is not read).
static void check_jet(bdl_scene_parser *p, bdl_scene_section *gas)
{
    const bdl_scene *sc = p->scene;
    const bdl_gas_scene *g = &sc->gas;
    for (int side = 0; side < 6 && !p->failed; ++side) {
        if (sc->periodic[side / 2] || g->side[side] != BDL_SIDE_INLET)
            continue;
        for (int b = 0; b < 3 && !p->failed; ++b) {
            if (b == side / 2)
                continue;
            const double lo = bdl_v3_comp(g->jet_min, b), hi = bdl_v3_comp(g->jet_max, b);
            const double dlo = bdl_v3_comp(sc->domain_min, b), dhi = bdl_v3_comp(sc->domain_max, b);
            const double tol = 1e-9 * (dhi - dlo);
            char what[TEXT_LEN];
            if (!(hi > lo))
                snprintf(what, sizeof what, "not larger than jet_min on the %s axis (%g <= %g)",
                         axis_name(b), hi, lo);
            else if (lo < dlo - tol || hi > dhi + tol)
                snprintf(what, sizeof what,
                         "the jet %g..%g m on the %s axis reaches outside the inlet face, which "
                         "spans [domain] %g..%g m",
                         lo, hi, axis_name(b), dlo, dhi);
            else
                continue;
            fail_at_key(p, gas, !(hi > lo) || hi > dhi + tol ? "jet_max" : "jet_min", 0, what);
        }
    }
}

/// `pressure_solver = direct` on a grid it can band (bdl_poisson_direct_band); says why not.
static int direct_solver_fits(bdl_scene_parser *p, bdl_scene_section *gas)
{
    const bdl_gas_scene *g = &p->scene->gas;
    if (g->pressure_solver != BDL_PRESSURE_DIRECT)
        return 1;
    const int n[3] = {(int)g->cells.x, (int)g->cells.y, (int)g->cells.z};
    const int band = bdl_poisson_direct_band(n, p->scene->periodic);
    const double cost = bdl_poisson_direct_cost(n, p->scene->periodic);
    if (band >= 0 && band <= BDL_POISSON_DIRECT_BAND_MAX && cost <= BDL_POISSON_DIRECT_COST_MAX)
        return 1;
    char why[200];
    if (band < 0)
        snprintf(why, sizeof why, "direct needs no periodic axis of more than one cell; use mgpcg");
    else if (band > BDL_POISSON_DIRECT_BAND_MAX)
        snprintf(why, sizeof why,
                 "direct factors a band of %d cells (an x row, or an x-y layer); at most %d: use "
                 "mgpcg",
                 band, BDL_POISSON_DIRECT_BAND_MAX);
    else
        snprintf(why, sizeof why,
                 "direct factors a band of %d cells over %.0f cells each step, %.2g "
                 "multiply-adds; at most %.0e: use mgpcg",
                 band, cost / ((double)band * band), cost, BDL_POISSON_DIRECT_COST_MAX);
    fail_at_key(p, gas, "pressure_solver", 0, why);
    return 0;
}

/// [gas] and [coupling]: present or not; whole cell counts; inlets with a velocity.
static void check_gas(bdl_scene_parser *p, bdl_scene_section *gas, bdl_scene_section *coupling)
{
    bdl_gas_scene *g = &p->scene->gas;
    g->enabled = gas && section_used(gas);
    if (!g->enabled) {
        if (coupling && section_used(coupling))
            bdl_scene_fail(p, &(bdl_scene_where){.line = coupling->line, .title = "coupling"},
                           "[coupling] needs a [gas] section");
        return;
    }
    if (!given(gas, key_of(gas, "cells"))) {
        fail_missing(p, gas, "cells", " (the gas grid: cells along x, y, z)");
        return;
    }
    for (int a = 0; a < 3; ++a) {
        double n = bdl_v3_comp(g->cells, a);
        if (n != floor(n) || n < 1.0 || n > 4096.0) {
            fail_at_key(p, gas, "cells", 0, "cell counts must be whole numbers from 1 to 4096");
            return;
        }
    }
    if (!bdl_pressure_solver_available(g->pressure_solver)) {
        fail_at_key(p, gas, "pressure_solver", 0,
                    "this build has no hypre: configure with -DBDL_WITH_MPI=ON (OpenMPI and "
                    "libhypre-dev), or use mgpcg");
        return;
    }
    if (!direct_solver_fits(p, gas))
        return;
    int inlets = 0;
    for (int side = 0; side < 6; ++side)
        inlets += !p->scene->periodic[side / 2] && g->side[side] == BDL_SIDE_INLET;
    if (inlets > 0 && !(g->inlet_velocity > 0.0 || g->jet_velocity > 0.0)) {
        fail_at_key(p, gas, "inlet_velocity", 0,
                    "an inlet side needs inlet_velocity (or jet_velocity) > 0");
        return;
    }
    if (g->jet_velocity > 0.0 && !(g->has_jet_min && g->has_jet_max)) {
        fail_at_key(p, gas, "jet_velocity", 0, "a jet needs jet_min and jet_max");
        return;
    }
    if (g->distributor_resistance > 0.0 && (inlets == 0 || g->jet_velocity > 0.0)) {
        fail_at_key(p, gas, "distributor_resistance", 0,
                    inlets == 0 ? "a distributor needs an inlet side"
                                : "a distributor plate has no jet: leave out jet_velocity");
        return;
    }
    if (g->has_jet_min && g->has_jet_max)
        check_jet(p, gas);
    if (p->failed)
        return;
    if (g->has_probe_low != g->has_probe_high) {
        fail_at_key(p, gas, g->has_probe_low ? "probe_low" : "probe_high", 0,
                    "the pressure probes come in pairs: give probe_low and probe_high");
        return;
    }
    if (g->has_probe_low && !(g->probe_high > g->probe_low)) {
        fail_at_key(p, gas, "probe_high", 0, "must be above probe_low");
        return;
    }
    if (g->has_probe_high) {
        // Heights are measured along gravity (z without it) from the domain's floor.
        const bdl_scene *sc = p->scene;
        const int axis = bdl_v3_major_axis(sc->gravity);
        double height = bdl_v3_comp(sc->domain_max, axis) - bdl_v3_comp(sc->domain_min, axis);
        if (g->probe_high > height) {
            char what[128];
            snprintf(what, sizeof what, "must lie inside the domain (height %.6g m)", height);
            fail_at_key(p, gas, "probe_high", 0, what);
            return;
        }
    }
}

/// A scene with parcels: every species of parcels, a gas to carry them, no [wall] (the domain's
/// sides bound them) and the step in [run] dt (it is the gas's step too).
static void check_parcels(bdl_scene_parser *p)
{
    bdl_scene *scene = p->scene;
    int parcels = 0, first_parcel = -1, first_other = -1;
    for (int k = 0; k < scene->species_count; ++k) {
        const int is = bdl_species_is_parcel(&scene->species[k]);
        parcels += is;
        if (is && first_parcel < 0)
            first_parcel = k;
        if (!is && first_other < 0)
            first_other = k;
    }
    scene->parcels.enabled = parcels > 0;
    bdl_scene_section *section = NULL, *gas = NULL, *camera = NULL;
    for (int i = 0; i < p->section_count; ++i) {
        if (p->sections[i].kind == BDL_SECTION_PARCELS)
            section = &p->sections[i];
        if (p->sections[i].kind == BDL_SECTION_GAS)
            gas = &p->sections[i];
        if (p->sections[i].kind == BDL_SECTION_CAMERA)
            camera = &p->sections[i];
    }
    const bdl_scene_where at_parcels = {.line = section ? section->line : 0, .title = "parcels"};
    if (!parcels) {
        if (section && section_used(section))
            bdl_scene_fail(p, &at_parcels,
                           "[parcels] needs a species made of parcels (parcel_particles or "
                           "parcel_volume)");
        return;
    }
    char title[BDL_NAME_LEN + 16];
    snprintf(title, sizeof title, "species %s", scene->species[first_parcel].name);
    const bdl_scene_where at_species = {.line = scene->line.species[first_parcel], .title = title};
    if (first_other >= 0)
        bdl_scene_fail(p, &at_species,
                       "species '%s' is made of parcels and '%s' is not: a scene holds parcels or "
                       "particles, not both (yet)",
                       scene->species[first_parcel].name, scene->species[first_other].name);
    else if (!scene->gas.enabled)
        bdl_scene_fail(p, &at_species,
                       "parcels move with a gas (or liquid): the scene needs a [gas] section");
    else if (scene->wall_count > 0)
        bdl_scene_fail(p, &(bdl_scene_where){.line = scene->line.walls[0], .title = "wall"},
                       "[wall] sections bound particles; parcels are bounded by the domain's "
                       "sides (the [gas] side types): remove the wall");
    else if (scene->gas.dt > 0.0 && gas)
        fail_at_key(p, gas, "dt", 0,
                    "with parcels the gas steps with the parcels: give the step as [run] dt");
    else if (scene->camera.color == BDL_COLOR_COORDINATION && camera)
        fail_at_key(p, camera, "color", 0,
                    "parcels have no contacts, so no coordination number; colour them by solids "
                    "(the solids fraction), speed, vx, vy, vz, voidage or species");
    else if (scene->coupling.drag_velocity != 0)
        for (int i = 0; i < p->section_count; ++i)
            if (p->sections[i].kind == BDL_SECTION_COUPLING)
                fail_at_key(p, &p->sections[i], "drag_velocity", 0,
                            "a parcel's drag is implicit in its own velocity: parcels take "
                            "drag_velocity = particle");
}

/// The [solids] section, if the scene uses it.
static bdl_scene_section *solids_section(bdl_scene_parser *p)
{
    for (int i = 0; i < p->section_count; ++i)
        if (p->sections[i].kind == BDL_SECTION_SOLIDS && section_used(&p->sections[i]))
            return &p->sections[i];
    return NULL;
}

/// A scene with a solids phase on the grid: a gas, no particles or walls (the domain's sides
/// bound the phase), gravity along -z, a bed height inside the domain, and the step in [run] dt.
/// The first wall that is not the container's vibration (with a solids phase only that one may
/// be given: its motion is the container's), or -1.
static int bounding_wall(const bdl_scene *scene)
{
    for (int k = 0; k < scene->wall_count; ++k)
        if (scene->walls[k].motion != BDL_MOTION_VIBRATE ||
            scene->walls[k].frame != BDL_FRAME_CONTAINER)
            return k;
    return -1;
}

/// Whether [solids] bed_height is needed: without phases, or when a phase has no bed_top.
static int needs_bed_height(const bdl_solids_scene *so)
{
    for (int i = 0; i < so->phase_count; ++i)
        if (!(so->phases[i].bed_top > 0.0))
            return 1;
    return so->phase_count == 0;
}

/// The i-th [phase NAME] section.
static bdl_scene_section *phase_section(bdl_scene_parser *p, int i)
{
    for (int k = 0; k < p->section_count; ++k)
        if (p->sections[k].kind == BDL_SECTION_PHASE && p->sections[k].index == i)
            return &p->sections[k];
    return NULL;
}

static void check_phase_layers(bdl_scene_parser *p, const bdl_solids_scene *so);

/// A mixture's [phase NAME] sections: two or more, their particles not also in [solids], their
/// layers' fractions at most 0.6 where they overlap.
static void check_phases(bdl_scene_parser *p, bdl_scene_section *s)
{
    const bdl_solids_scene *so = &p->scene->solids;
    static const char *const mixture_keys[] = {"hindrance", "phase_friction"};
    for (int k = 0; k < 2 && so->phase_count == 0; ++k)
        if (given(s, key_of(s, mixture_keys[k]))) {
            fail_at_key(p, s, mixture_keys[k], 0,
                        "acts between solids phases, and the scene has one: give [phase NAME] "
                        "sections or remove the key");
            return;
        }
    if (so->phase_count == 0)
        return;
    if (so->phase_count == 1) {
        bdl_scene_fail(p, &(bdl_scene_where){.line = phase_section(p, 0)->line, .title = "phase"},
                       "one [phase NAME] section: a mixture has 2 to %d phases (one phase is "
                       "[solids] alone)",
                       BDL_SOLIDS_PHASES);
        return;
    }
    if (so->def.kinetic_pressure == BDL_KINETIC_PRESSURE_IMPLICIT) {
        fail_at_key(p, s, "kinetic_pressure", 0,
                    "implicit is built for one phase; a mixture's phases have a pressure each: "
                    "use explicit");
        return;
    }
    static const char *const own[] = {
        "diameter", "density", "restitution", "friction", "tangential_restitution", "fraction"};
    for (int k = 0; k < 6; ++k)
        if (given(s, key_of(s, own[k]))) {
            fail_at_key(p, s, own[k], 0,
                        "the scene has [phase NAME] sections, and each phase gives its own: "
                        "remove the key here");
            return;
        }
    check_phase_layers(p, so);
}

/// Each phase's layer [bed_bottom, bed_top) inside the domain and not empty; where layers
/// overlap, their fractions' sum at most 0.6 (checked between every two of their ends).
static void check_phase_layers(bdl_scene_parser *p, const bdl_solids_scene *so)
{
    const double height = p->scene->domain_max.z - p->scene->domain_min.z;
    double ends[2 * BDL_SOLIDS_PHASES];
    int n = 0;
    char what[200];
    const double h = height / fmax(p->scene->gas.cells.z, 1.0); // the cells' height
    for (int i = 0; i < so->phase_count; ++i) {
        const bdl_phase_scene *ph = &so->phases[i];
        const double top = ph->bed_top > 0.0 ? ph->bed_top : so->bed_height;
        if (!(ph->bed_top > 0.0) && !(so->bed_height > 0.0 && so->bed_height <= height))
            continue; // [solids] bed_height missing or out of range: its own check names it
        const double centre = (ceil(ph->bed_bottom / h - 0.5) + 0.5) * h; // the lowest at or above
        if (!(top > ph->bed_bottom) || top > height || !(centre < top)) {
            snprintf(what, sizeof what,
                     "out of range: the phase's layer runs from %g to %g m; allowed: above "
                     "bed_bottom, <= the domain's height, %g (m), and holding a cell's centre "
                     "(cells %g m high)",
                     ph->bed_bottom, top, height, h);
            fail_at_key(p, phase_section(p, i), ph->bed_top > 0.0 ? "bed_top" : "bed_bottom", 0,
                        what);
            return;
        }
        ends[n++] = ph->bed_bottom, ends[n++] = top;
    }
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            const double mid = 0.5 * (ends[a] + ends[b]);
            double sum = 0.0;
            int last = -1;
            for (int i = 0; i < so->phase_count; ++i) {
                const bdl_phase_scene *ph = &so->phases[i];
                const double top = ph->bed_top > 0.0 ? ph->bed_top : so->bed_height;
                if (mid >= ph->bed_bottom && mid < top)
                    sum += ph->fraction, last = i;
            }
            if (sum > 0.6 + 1e-12) {
                snprintf(what, sizeof what,
                         "out of range: the phases' fractions add up to %g at %g m; allowed: a "
                         "sum <= 0.6",
                         sum, mid);
                fail_at_key(p, phase_section(p, last), "fraction", 0, what);
                return;
            }
        }
}

static void check_solids(bdl_scene_parser *p)
{
    bdl_scene *scene = p->scene;
    bdl_scene_section *s = solids_section(p);
    scene->solids.enabled = s != NULL;
    if (!s && scene->gas.enabled && scene->gas.convection_step == BDL_CONVECTION_POINT_IMPLICIT) {
        for (int i = 0; i < p->section_count; ++i)
            if (p->sections[i].kind == BDL_SECTION_GAS)
                fail_at_key(p, &p->sections[i], "convection_step", 0,
                            "point_implicit is for a solids phase on the grid ([solids]); with "
                            "particles or parcels the gas steps within its Courant limit");
        return;
    }
    if (!s && scene->solids.phase_count > 0)
        bdl_scene_fail(p, &(bdl_scene_where){.line = phase_section(p, 0)->line, .title = "phase"},
                       "a [phase NAME] section is a phase of a [solids] mixture: the scene needs "
                       "a [solids] section");
    if (!s)
        return;
    const bdl_scene_where at = {.line = s->line, .title = "solids"};
    const double height = scene->domain_max.z - scene->domain_min.z;
    char what[160];
    if (!scene->gas.enabled)
        bdl_scene_fail(p, &at,
                       "a solids phase lives on the gas's grid: the scene needs a [gas] "
                       "section");
    else if (scene->species_count > 0)
        bdl_scene_fail(p, &(bdl_scene_where){.line = scene->line.species[0], .title = "species"},
                       "a scene with [solids] holds no particles (the hybrid of a solids phase "
                       "and particles is not built yet): remove the [species] sections");
    else if (bounding_wall(scene) >= 0)
        bdl_scene_fail(
            p, &(bdl_scene_where){.line = scene->line.walls[bounding_wall(scene)], .title = "wall"},
            "[wall] sections bound particles; a solids phase is bounded by the domain's sides: "
            "remove the wall (a wall with motion = vibrate and frame = container may stay: it "
            "shakes the container)");
    else if ((needs_bed_height(&scene->solids) || given(s, key_of(s, "bed_height"))) &&
             (!(scene->solids.bed_height > 0.0) || scene->solids.bed_height > height)) {
        snprintf(what, sizeof what, "%s; allowed: > 0 and <= the domain's height, %g (m)",
                 given(s, key_of(s, "bed_height")) ? "out of range" : "missing required key",
                 height);
        fail_at_key(p, s, "bed_height", 0, what);
    } else if (scene->gravity.x != 0.0 || scene->gravity.y != 0.0 || !(scene->gravity.z < 0.0))
        bdl_scene_fail(p, &at,
                       "a solids phase's bed is filled along z: [run] gravity must point "
                       "along -z");
    else if (!(scene->dt > 0.0))
        bdl_scene_fail(p, &at,
                       "with [solids] the gas and the solids share one step: give it as "
                       "[run] dt (1e-4 s suits 1 cm cells)");
    else if (scene->output.fields_interval > 0.0) {
        for (int i = 0; i < p->section_count; ++i)
            if (p->sections[i].kind == BDL_SECTION_OUTPUT)
                fail_at_key(p, &p->sections[i], "fields_interval", 0,
                            "the field files average particles, and a solids phase has none (its "
                            "voidage is in the pictures' slice): remove the key");
    } else if (scene->solids.def.wave_weight > 0.0 &&
               scene->solids.def.kinetic_pressure != BDL_KINETIC_PRESSURE_IMPLICIT)
        fail_at_key(p, s, "wave_weight", 0,
                    "weighs the pressure waves in the step of kinetic_pressure = implicit (the "
                    "explicit pressure counts them whole): set kinetic_pressure = implicit, or "
                    "remove the key");
    else
        check_phases(p, s);
}

/// [output] fields_cell against the domain: no larger than its largest side, and no grid of
/// more than BDL_MAX_FIELD_CELLS cells. The count is bounded from above by the domain's extent
/// in cells along each axis (at least one), which the grid of analysis/fields.h never exceeds;
/// the default, from the particles, is checked when the run starts.
static void check_fields_cell(bdl_scene_parser *p, bdl_scene_section *output)
{
    const double cell = p->scene->output.fields_cell;
    const bdl_vec3 span = bdl_v3_sub(p->scene->domain_max, p->scene->domain_min);
    double largest = 0.0, cells = 1.0;
    for (int a = 0; a < 3; ++a) {
        largest = fmax(largest, bdl_v3_comp(span, a));
        cells *= fmax(1.0, bdl_v3_comp(span, a) / cell + 1e-9);
    }
    char what[TEXT_LEN * 2];
    if (cell > largest) {
        snprintf(what, sizeof what,
                 "larger than the domain (its largest side is %g m); allowed: > 0 and <= %g (m)",
                 largest, largest);
        fail_at_key(p, output, "fields_cell", 0, what);
    } else if (cells > BDL_MAX_FIELD_CELLS) {
        snprintf(what, sizeof what,
                 "makes about %.3g cells over the domain, more than %g; allowed: a cell of about "
                 "%.3g m or more (m)",
                 cells, BDL_MAX_FIELD_CELLS, cell * cbrt(cells / BDL_MAX_FIELD_CELLS));
        fail_at_key(p, output, "fields_cell", 0, what);
    }
}

static void check_singletons(bdl_scene_parser *p)
{
    bdl_scene_section *domain = NULL, *guards = NULL, *gas = NULL, *coupling = NULL, *camera = NULL,
                      *output = NULL;
    for (int i = 0; i < p->section_count && !p->failed; ++i) {
        bdl_scene_section *s = &p->sections[i];
        if (bdl_section_infos[s->kind].name_count != 0)
            continue;
        check_table_rules(p, s);
        if (s->kind == BDL_SECTION_DOMAIN)
            domain = s;
        if (s->kind == BDL_SECTION_GUARDS)
            guards = s;
        if (s->kind == BDL_SECTION_GAS)
            gas = s;
        if (s->kind == BDL_SECTION_COUPLING)
            coupling = s;
        if (s->kind == BDL_SECTION_CAMERA)
            camera = s;
        if (s->kind == BDL_SECTION_OUTPUT)
            output = s;
    }
    if (!p->failed && output && given(output, key_of(output, "mixing_cells")))
        for (int a = 0; a < 3; ++a) {
            double n = bdl_v3_comp(p->scene->output.mixing_cells, a);
            if (n != floor(n) || n < 1.0 || n > 4096.0) {
                fail_at_key(p, output, "mixing_cells", 0,
                            "cell counts must be whole numbers from 1 to 4096");
                break;
            }
        }
    if (!p->failed)
        check_gas(p, gas, coupling);
    if (!p->failed && camera && p->scene->camera.gas_field != BDL_GAS_FIELD_NONE &&
        !p->scene->gas.enabled)
        fail_at_key(p, camera, "gas_field", 0, "needs a [gas] section (this scene has no gas)");
    if (!p->failed)
        check_box(p, domain, "min", "max");
    if (!p->failed && output && given(output, key_of(output, "fields_cell")))
        check_fields_cell(p, output);
    // A pseudo-2D bed (y thinner than a fifth of x and of z) is seen from the front unless the
    // scene says otherwise: from the iso corner it would be a sliver.
    const bdl_vec3 span = bdl_v3_sub(p->scene->domain_max, p->scene->domain_min);
    if (!p->failed && !(camera && given(camera, key_of(camera, "view"))) && 5.0 * span.y < span.x &&
        5.0 * span.y < span.z)
        p->scene->camera.view = BDL_VIEW_FRONT;
    if (!p->failed && p->scene->guards.dt_warn > p->scene->guards.dt_refuse) {
        int warn_given = given(guards, key_of(guards, "dt_warn"));
        fail_at_key(p, guards, warn_given ? "dt_warn" : "dt_refuse", 0,
                    warn_given ? "larger than dt_refuse" : "smaller than dt_warn");
    }
}

static void check_dia(bdl_scene_parser *p, bdl_scene_section *s)
{
    const bdl_dia_scene_def *d = &p->scene->dias[s->index];
    bdl_vec3 view = bdl_v3_sub(d->target, d->position);
    if (d->bits != 8 && d->bits != 16)
        fail_at_key(p, s, "bits", 0, "must be 8 or 16");
    else if (!(bdl_v3_len(view) > 0.0))
        fail_at_key(p, s, "target", 0, "must differ from position: the camera looks along it");
    else if (bdl_v3_len(bdl_v3_cross(view, d->up)) < 1e-6 * bdl_v3_len(view))
        fail_at_key(p, s, "up", 0, "must not be parallel to the view (target - position)");
    else if (d->pair_dt >= d->interval)
        fail_at_key(p, s, "pair_dt", 0, "must be shorter than interval");
    else if (d->dark >= d->bright)
        fail_at_key(p, s, "dark", 0, "must be below bright");
    else if (d->stop > 0.0 && d->stop < d->start)
        fail_at_key(p, s, "stop", 0, "must be at or after start (0: no stop)");
}

/// An output interval that would ask for more than BDL_MAX_OUTPUTS outputs up to end_time.
typedef struct output_excess {
    int dia;         ///< the [camera NAME] index, or -1 for [output]
    const char *key; ///< the interval's key
    double interval; ///< [s]
    double count;    ///< outputs it asks for
} output_excess;

/// The first output interval of the scene that asks for too many outputs up to end_time; 0 when
/// none does. Zero intervals write nothing (or only at the end) and pass.
static int find_output_excess(const bdl_scene *scene, double end_time, output_excess *e)
{
    const bdl_output_def *o = &scene->output;
    static const char *const keys[] = {
        "diagnostics_interval", "vtk_interval",         "checkpoint_interval", "frame_interval",
        "contacts_interval",    "orientation_interval", "fields_interval",     "rheology_interval"};
    const double intervals[] = {o->diagnostics_interval, o->vtk_interval,
                                o->checkpoint_interval,  o->frame_interval,
                                o->contacts_interval,    o->orientation_interval,
                                o->fields_interval,      o->rheology_interval};
    enum { OWN = sizeof intervals / sizeof intervals[0] };
    for (int k = 0; k < OWN + scene->dia_count; ++k) {
        const double interval = k < OWN ? intervals[k] : scene->dias[k - OWN].interval;
        if (interval > 0.0 && end_time / interval > BDL_MAX_OUTPUTS) {
            *e = (output_excess){k < OWN ? -1 : k - OWN, k < OWN ? keys[k] : "interval", interval,
                                 end_time / interval};
            return 1;
        }
    }
    return 0;
}

static void excess_text(const output_excess *e, double end_time, char *buf, size_t size)
{
    snprintf(buf, size,
             "%.3g outputs up to end_time = %g s; at most %g per run: the interval must be >= "
             "end_time / %g = %g s",
             e->count, end_time, BDL_MAX_OUTPUTS, BDL_MAX_OUTPUTS, end_time / BDL_MAX_OUTPUTS);
}

/// Every output interval against the end time, at the interval's line.
static void check_output_counts(bdl_scene_parser *p)
{
    output_excess e;
    if (!find_output_excess(p->scene, p->scene->end_time, &e))
        return;
    for (int i = 0; i < p->section_count; ++i) {
        bdl_scene_section *s = &p->sections[i];
        if ((e.dia < 0 && s->kind == BDL_SECTION_OUTPUT) ||
            (e.dia >= 0 && s->kind == BDL_SECTION_DIA && s->index == e.dia)) {
            char what[TEXT_LEN * 2];
            excess_text(&e, p->scene->end_time, what, sizeof what);
            fail_at_key(p, s, e.key, 0, what);
            return;
        }
    }
}

bdl_result bdl_scene_set_end_time(bdl_scene *scene, double end_time, bdl_scene_error *err)
{
    const bdl_scene_key *key = bdl_scene_key_find(BDL_SECTION_RUN, "end_time");
    char text[TEXT_LEN * 2];
    output_excess e;
    if (!(end_time > key->lo && end_time <= key->hi)) {
        bdl_scene_key_range_text(key, text, sizeof text);
        snprintf(err->message, sizeof err->message, "--until %g: out of range; allowed: %s (%s)",
                 end_time, text, key->unit);
        return BDL_ERR_SCENE;
    }
    if (find_output_excess(scene, end_time, &e)) {
        excess_text(&e, end_time, text, sizeof text);
        snprintf(err->message, sizeof err->message, "--until %g: [%s%s] %s = %g: %s", end_time,
                 e.dia < 0 ? "output" : "camera ", e.dia < 0 ? "" : scene->dias[e.dia].name, e.key,
                 e.interval, text);
        return BDL_ERR_SCENE;
    }
    scene->end_time = end_time;
    return BDL_OK;
}

static bdl_scene_section *singleton(bdl_scene_parser *p, bdl_section_kind kind)
{
    for (int i = 0; i < p->section_count; ++i)
        if (p->sections[i].kind == kind)
            return &p->sections[i];
    return NULL;
}

/// Lees–Edwards boundaries need a box periodic in x and z of particles alone; the bulk region of
/// rheology.csv must be left by its margins.
static void check_shear(bdl_scene_parser *p)
{
    const bdl_scene *sc = p->scene;
    bdl_scene_section *domain = singleton(p, BDL_SECTION_DOMAIN);
    if (domain && sc->shear_rate != 0.0) {
        if (!sc->periodic[0] || !sc->periodic[2])
            fail_at_key(
                p, domain, "shear_rate", 0,
                "Lees-Edwards boundaries need periodic = x z (or x y z): the shear is along "
                "x, its gradient along z");
        else if (sc->gas.enabled || sc->parcels.enabled)
            fail_at_key(p, domain, "shear_rate", 0,
                        "Lees-Edwards boundaries hold particles alone: remove the [gas] section");
    }
    bdl_scene_section *output = singleton(p, BDL_SECTION_OUTPUT);
    const double height = sc->domain_max.z - sc->domain_min.z;
    if (!p->failed && output && !(2.0 * sc->output.rheology_margin < height))
        fail_at_key(p, output, "rheology_margin", 0,
                    "twice the margin must be less than the domain's height along z");
}

int bdl_scene_validate(bdl_scene_parser *p)
{
    check_singletons(p);
    if (!p->failed && p->scene->species_count == 0 && !solids_section(p))
        bdl_scene_fail(p, &(bdl_scene_where){.line = 0},
                       "no [species NAME] section: at least one species is required");
    // Species first: pairs and creators refer to them and to their diameters.
    static const bdl_section_kind order[] = {
        BDL_SECTION_SPECIES, BDL_SECTION_PAIR, BDL_SECTION_WALL, BDL_SECTION_CREATE,
        BDL_SECTION_DIA,     BDL_SECTION_SINK, BDL_SECTION_PHASE};
    for (int k = 0; k < 7; ++k) {
        for (int i = 0; i < p->section_count && !p->failed; ++i) {
            bdl_scene_section *s = &p->sections[i];
            if (s->kind != order[k])
                continue;
            check_table_rules(p, s);
            if (p->failed)
                break;
            if (s->kind == BDL_SECTION_SPECIES)
                check_species(p, s);
            else if (s->kind == BDL_SECTION_PAIR)
                check_pair(p, s);
            else if (s->kind == BDL_SECTION_WALL)
                check_wall(p, s);
            else if (s->kind == BDL_SECTION_DIA)
                check_dia(p, s);
            else if (s->kind == BDL_SECTION_SINK)
                check_box(p, s, "min", "max");
            else if (s->kind == BDL_SECTION_CREATE)
                check_create(p, s);
        }
    }
    if (!p->failed)
        check_parcels(p);
    if (!p->failed)
        check_solids(p);
    if (!p->failed)
        check_shear(p);
    if (!p->failed)
        check_output_counts(p);
    return !p->failed;
}
