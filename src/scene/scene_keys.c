// bedlam — the table of every scene key, and the helpers that read it.
//
// This table is the single source of truth for the scene format: the parser looks keys up here,
// writes values through the offsets, checks ranges and requirements from it, builds "did you
// mean" hints from it, and tests/test_scene.c checks docs/scene-format.md against it.
#include <ctype.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "scene/scene_internal.h"

// The enum keys are written through an int pointer: the C enums must have int's size.
_Static_assert(sizeof(bdl_normal_law) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_damping_mode) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_rolling_model) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_size_dist) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_wall_kind) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_outside) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_region_shape) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_motion_kind) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_wall_frame) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_create_kind) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_view_preset) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_projection) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_color_mode) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_gas_side_type) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_convection) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_drag_law) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_shape) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_dia_projection) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_dia_lighting) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_sweep) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_gas_field) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_parcel_model) == sizeof(int), "enum size");
_Static_assert(sizeof(bdl_parcel_display) == sizeof(int), "enum size");

const bdl_section_info bdl_section_infos[BDL_SECTION_KIND_COUNT] = {
    [BDL_SECTION_RUN] = {"run", "run", 0, 1},
    [BDL_SECTION_DOMAIN] = {"domain", "domain", 0, 1},
    [BDL_SECTION_CONTACT] = {"contact", "contact", 0, 1},
    [BDL_SECTION_OUTPUT] = {"output", "output", 0, 1},
    [BDL_SECTION_GUARDS] = {"guards", "guards", 0, 1},
    [BDL_SECTION_CAMERA] = {"camera", "camera", 0, 1},
    [BDL_SECTION_GAS] = {"gas", "gas", 0, 1},
    [BDL_SECTION_COUPLING] = {"coupling", "coupling", 0, 1},
    [BDL_SECTION_PARCELS] = {"parcels", "parcels", 0, 1},
    [BDL_SECTION_SOLIDS] = {"solids", "solids", 0, 1},
    [BDL_SECTION_SPECIES] = {"species", "species NAME", 1, BDL_MAX_SPECIES},
    [BDL_SECTION_PAIR] = {"pair", "pair A B", 2, BDL_MAX_PAIRS},
    [BDL_SECTION_WALL] = {"wall", "wall NAME", 1, BDL_MAX_WALLS},
    [BDL_SECTION_CREATE] = {"create", "create NAME", 1, BDL_MAX_CREATES},
    [BDL_SECTION_DIA] = {"camera", "camera NAME", 1, BDL_MAX_DIA},
    [BDL_SECTION_SINK] = {"sink", "sink NAME", 1, BDL_MAX_SINKS},
    [BDL_SECTION_PHASE] = {"phase", "phase NAME", 1, BDL_SOLIDS_PHASES},
    [BDL_SECTION_PARALLEL] = {"parallel", "parallel", 0, 1},
};

// Words of the choices that are the scene's own (the solver modules define theirs beside their
// enums); the parser stores the index.
#define BDL_X_WORD(name, word, label, unit)  word,
#define BDL_X_LABEL(name, word, label, unit) label,
#define BDL_X_UNIT(name, word, label, unit)  unit,
BDL_CHOICE_WORDS(bdl_view_preset, BDL_VIEW_PRESETS);
BDL_CHOICE_WORDS(bdl_projection, BDL_PROJECTIONS);
const char *const bdl_color_mode_names[] = {BDL_COLOR_MODES(BDL_X_WORD) NULL};
const char *const bdl_color_mode_labels[] = {BDL_COLOR_MODES(BDL_X_LABEL) NULL};
const char *const bdl_color_mode_units[] = {BDL_COLOR_MODES(BDL_X_UNIT) NULL};
const char *const bdl_gas_field_names[] = {BDL_GAS_FIELDS(BDL_X_WORD) NULL};
const char *const bdl_gas_field_labels[] = {BDL_GAS_FIELDS(BDL_X_LABEL) NULL};
const char *const bdl_gas_field_units[] = {BDL_GAS_FIELDS(BDL_X_UNIT) NULL};
static const char *const axis_names[] = {"x", "y", "z", NULL};
static const char *const drag_velocity_names[] = {"particle", "mean", NULL};
static const char *const dia_kind_names[] = {"dia", NULL};
BDL_CHOICE_WORDS(bdl_dia_projection, BDL_DIA_PROJECTIONS);
BDL_CHOICE_WORDS(bdl_dia_lighting, BDL_DIA_LIGHTINGS);
const char *const bdl_dia_lighting_labels[] = {BDL_DIA_LIGHTINGS(BDL_ENUM_LABEL) NULL};
BDL_CHOICE_WORDS(bdl_sweep, BDL_SWEEPS);
BDL_CHOICE_WORDS(bdl_outside, BDL_OUTSIDES);
BDL_CHOICE_WORDS(bdl_region_shape, BDL_REGION_SHAPES);
BDL_CHOICE_WORDS(bdl_parcel_display, BDL_PARCEL_DISPLAYS);

#define IN_SCENE(field)   .target = BDL_TARGET_STRUCT, .offset = offsetof(bdl_scene, field)
#define IN_SPECIES(field) .target = BDL_TARGET_STRUCT, .offset = offsetof(bdl_species_def, field)
#define IN_PAIR(field)                                                                             \
    .target = BDL_TARGET_STRUCT, .offset = offsetof(bdl_pair_def, field), .has_flag = 1,           \
    .flag_offset = offsetof(bdl_pair_def, has_##field)
#define IN_WALL(field)   .target = BDL_TARGET_STRUCT, .offset = offsetof(bdl_wall_def, field)
#define IN_CREATE(field) .target = BDL_TARGET_STRUCT, .offset = offsetof(bdl_create_def, field)
#define IN_SINK(field)   .target = BDL_TARGET_STRUCT, .offset = offsetof(bdl_sink_def, field)
#define IN_PHASE(field)  .target = BDL_TARGET_STRUCT, .offset = offsetof(bdl_phase_scene, field)
#define IN_DIA(field)    .target = BDL_TARGET_STRUCT, .offset = offsetof(bdl_dia_scene_def, field)
#define IN_CAMERA(field) .target = BDL_TARGET_STRUCT, .offset = offsetof(bdl_scene, camera.field)
#define IN_CAMERA_FLAGGED(field)                                                                   \
    IN_CAMERA(field), .has_flag = 1, .flag_offset = offsetof(bdl_scene, camera.has_##field)
#define IN_GAS(field) .target = BDL_TARGET_STRUCT, .offset = offsetof(bdl_scene, gas.field)
#define IN_COUPLING(field)                                                                         \
    .target = BDL_TARGET_STRUCT, .offset = offsetof(bdl_scene, coupling.field)
#define IN_PARCELS(field)                                                                          \
    .target = BDL_TARGET_STRUCT, .offset = offsetof(bdl_scene, parcels.def.field)
#define IN_SOLIDS(field) .target = BDL_TARGET_STRUCT, .offset = offsetof(bdl_scene, solids.field)
#define GAS_SIDE(name, index)                                                                      \
    {                                                                                              \
        S(GAS), name, .type = BDL_KEY_ENUM, "-", IN_GAS(side[index]), .def = {BDL_SIDE_WALL},      \
                      .enum_names = bdl_gas_side_names,                                            \
                      .doc = "gas boundary on the " name                                           \
                             " side of the domain: wall (no-slip), slip, inlet or "                \
                             "outlet (particles that cross an outlet side leave the run and are "  \
                             "counted: particles_out); ignored on a periodic axis"                 \
    }
#define IN_RECORD(field) .target = BDL_TARGET_RECORD, .offset = offsetof(bdl_scene_section, field)
#define GT(x)            .lo_kind = BDL_BOUND_OPEN, .lo = (x)
#define GE(x)            .lo_kind = BDL_BOUND_CLOSED, .lo = (x)
#define LT(x)            .hi_kind = BDL_BOUND_OPEN, .hi = (x)
#define LE(x)            .hi_kind = BDL_BOUND_CLOSED, .hi = (x)
#define BIT(v)           (1u << (v))
#define REQUIRED         .required = BDL_REQUIRED_ALWAYS
#define WHEN(key, mask)  .selector = key, .applies = (mask)

#define S(kind) .section = BDL_SECTION_##kind
#define NUM     .type = BDL_KEY_NUMBER
#define VEC     .type = BDL_KEY_VECTOR

const bdl_scene_key bdl_scene_keys[] = {
    // [run]
    {S(RUN), "dt", NUM, "s", IN_SCENE(dt), .default_text = "0 (auto)", GE(0),
     .doc = "time step; 0 = dt_fraction times the smallest contact time, chosen by the solver"},
    {S(RUN), "dt_fraction", NUM, "-", IN_SCENE(dt_fraction), .def = {0.02}, GT(0), LE(0.2),
     .doc = "fraction of the smallest contact time used as the step when dt is 0"},
    {S(RUN), "end_time", NUM, "s", IN_SCENE(end_time), REQUIRED, GT(0), LE(1e9),
     .doc = "simulated time at which the run stops"},
    {S(RUN), "gravity", VEC, "m/s^2", IN_SCENE(gravity), .def = {0, 0, -9.81},
     .max_length = BDL_MAX_GRAVITY, .doc = "gravitational acceleration vector"},
    {S(RUN), "seed", .type = BDL_KEY_U64, "-", IN_SCENE(seed), .def = {1}, GE(0),
     .doc = "seed of the random number generator (creation, velocity jitter)"},
    {S(RUN), "threads", .type = BDL_KEY_INT, "-", IN_SCENE(threads), .def = {0},
     .default_text = "0 (all cores)", GE(0), LE(256), .doc = "worker threads; 0 = all cores"},

    // [domain]
    {S(DOMAIN), "min", VEC, "m", IN_SCENE(domain_min), REQUIRED, GE(-BDL_MAX_COORDINATE),
     LE(BDL_MAX_COORDINATE), .doc = "lower corner of the simulation box"},
    {S(DOMAIN), "max", VEC, "m", IN_SCENE(domain_max), REQUIRED, GE(-BDL_MAX_COORDINATE),
     LE(BDL_MAX_COORDINATE),
     .doc = "upper corner of the simulation box; larger than min on every axis"},
    {S(DOMAIN), "periodic", .type = BDL_KEY_AXES, "-", IN_SCENE(periodic),
     .doc = "periodic axes: none, or letters among x y z (e.g. \"x y\")"},
    {S(DOMAIN), "outside", .type = BDL_KEY_ENUM, "-", IN_SCENE(outside),
     .def = {BDL_OUTSIDE_REMOVE}, .enum_names = bdl_outside_names,
     .doc = "a particle whose centre crosses a face that is not periodic: remove (removed and "
            "counted as particles_out and mass_out) or stop (the run stops and names it)"},
    {S(DOMAIN), "shear_rate", NUM, "1/s", IN_SCENE(shear_rate), .def = {0},
     .default_text = "0 (none)", GE(-1e6), LE(1e6),
     .doc = "Lees-Edwards boundaries: simple shear u_x = shear_rate (z - middle) of a box periodic "
            "in x and z, whose images above and below slide along x at +/- shear_rate x height; "
            "the particles start on that profile; 0 = none"},

    // [contact]
    {S(CONTACT), "law", .type = BDL_KEY_ENUM, "-", IN_SCENE(law), .def = {BDL_LAW_HERTZ},
     .enum_names = bdl_normal_law_names,
     .doc = "normal contact law: linear spring-dashpot or Hertz-Mindlin"},
    {S(CONTACT), "damping", .type = BDL_KEY_ENUM, "-", IN_SCENE(damping),
     .def = {BDL_DAMPING_EXACT}, .enum_names = bdl_damping_mode_names,
     .doc = "damping from restitution: exact (solved with the no-pull clamp) or closed_form "
            "(textbook formula)"},
    {S(CONTACT), "rolling", .type = BDL_KEY_ENUM, "-", IN_SCENE(rolling), .def = {BDL_ROLLING_NONE},
     .enum_names = bdl_rolling_model_names,
     .doc = "rolling resistance: none, or a constant torque mu_r R* F_n against rolling"},
    {S(CONTACT), "skin", NUM, "-", IN_SCENE(skin), .def = {0.1}, GT(0), LE(1),
     .doc = "Verlet neighbour-list skin as a fraction of the largest diameter"},

    // [species NAME]
    {S(SPECIES), "shape", .type = BDL_KEY_ENUM, "-", IN_SPECIES(shape), .def = {BDL_SHAPE_SPHERE},
     .enum_names = bdl_shape_names,
     .doc = "particle shape: sphere, or rod (a spherocylinder: a cylinder of the diameter with "
            "hemispherical caps)"},
    {S(SPECIES), "length", NUM, "m", IN_SPECIES(length), WHEN("shape", BIT(BDL_SHAPE_ROD)),
     .required = BIT(BDL_SHAPE_ROD), GT(0), .default_text = "required for rods",
     .doc = "tip-to-tip length of a rod (longer than its diameter; aspect ratio = length / "
            "diameter)"},
    {S(SPECIES), "diameter", NUM, "m", IN_SPECIES(diameter), REQUIRED, GT(0),
     .doc = "particle diameter (the mean for uniform and normal distributions)"},
    {S(SPECIES), "distribution", .type = BDL_KEY_ENUM, "-", IN_SPECIES(size_dist),
     .def = {BDL_SIZE_SINGLE}, .enum_names = bdl_size_dist_names, .doc = "diameter distribution"},
    {S(SPECIES), "diameter_min", NUM, "m", IN_SPECIES(diameter_min),
     WHEN("distribution", BIT(BDL_SIZE_UNIFORM) | BIT(BDL_SIZE_NORMAL)),
     .required = BIT(BDL_SIZE_UNIFORM), GT(0),
     .default_text = "required for uniform; diameter - 3 diameter_std for normal",
     .doc = "smallest diameter (uniform, normal)"},
    {S(SPECIES), "diameter_max", NUM, "m", IN_SPECIES(diameter_max),
     WHEN("distribution", BIT(BDL_SIZE_UNIFORM) | BIT(BDL_SIZE_NORMAL)),
     .required = BIT(BDL_SIZE_UNIFORM), GT(0),
     .default_text = "required for uniform; diameter + 3 diameter_std for normal",
     .doc = "largest diameter (uniform, normal)"},
    {S(SPECIES), "diameter_std", NUM, "m", IN_SPECIES(diameter_std),
     WHEN("distribution", BIT(BDL_SIZE_NORMAL)), .required = BIT(BDL_SIZE_NORMAL), GT(0),
     .default_text = "required for normal", .doc = "standard deviation of the diameter (normal)"},
    {S(SPECIES), "density", NUM, "kg/m^3", IN_SPECIES(density), REQUIRED, GT(0),
     .doc = "solid density"},
    {S(SPECIES), "youngs_modulus", NUM, "Pa", IN_SPECIES(material.youngs_modulus), .def = {-1},
     .default_text = "required if law = hertz", GT(0), .doc = "Young's modulus E (Hertz law)"},
    {S(SPECIES), "poisson_ratio", NUM, "-", IN_SPECIES(material.poisson_ratio), .def = {0.25},
     GT(-1), LT(0.5), .doc = "Poisson's ratio (Hertz law)"},
    {S(SPECIES), "stiffness", NUM, "N/m", IN_SPECIES(material.stiffness), .def = {-1},
     .default_text = "required if law = linear", GT(0),
     .doc = "normal spring stiffness k_n (linear law)"},
    {S(SPECIES), "tangential_stiffness", NUM, "N/m", IN_SPECIES(material.tangential_stiffness),
     .def = {-1}, .default_text = "2/7 * stiffness", GT(0),
     .doc = "tangential spring stiffness k_t (linear law)"},
    {S(SPECIES), "restitution", NUM, "-", IN_SPECIES(material.restitution), REQUIRED, GT(0), LE(1),
     .doc = "normal coefficient of restitution (not for parcels: theirs is [parcels] "
            "collision_restitution)"},
    {S(SPECIES), "tangential_damping_ratio", NUM, "-",
     IN_SPECIES(material.tangential_damping_ratio), .def = {0}, GE(0), LE(1),
     .doc = "tangential to normal damping ratio (0: no tangential dashpot)"},
    {S(SPECIES), "friction", NUM, "-", IN_SPECIES(material.friction), .def = {0}, GE(0),
     .doc = "sliding friction coefficient mu"},
    {S(SPECIES), "rolling_friction", NUM, "-", IN_SPECIES(material.rolling_friction), .def = {0},
     GE(0), .doc = "rolling friction coefficient mu_r (used when rolling = constant)"},
    {S(SPECIES), "background_damping", NUM, "1/s", IN_SPECIES(background_damping), .def = {0},
     GE(0),
     .doc = "force -b m v on every particle of the species (in a Lees-Edwards box v is taken "
            "relative to the shear profile: a medium that moves with the shear)"},
    {S(SPECIES), "parcel_particles", NUM, "-", IN_SPECIES(parcel_particles), .def = {0},
     .default_text = "0 (not parcels)", GE(0), LE(1e15),
     .doc = "makes the species parcels (MP-PIC, docs/parcels.md), each standing for this many "
            "real particles of the species' diameter and density; needs [gas]"},
    {S(SPECIES), "parcel_volume", NUM, "m^3", IN_SPECIES(parcel_volume), .def = {0},
     .default_text = "0 (not parcels)", GE(0), LE(1e3),
     .doc = "makes the species parcels of this solids volume each (parcels of equal volume: the "
            "particle count follows each parcel's drawn diameter); instead of parcel_particles"},

    // [pair A B]: each given key replaces the value mixed from the two species.
    {S(PAIR), "restitution", NUM, "-", IN_PAIR(restitution), .default_text = "from the species",
     GT(0), LE(1), .doc = "normal coefficient of restitution of the pair"},
    {S(PAIR), "friction", NUM, "-", IN_PAIR(friction), .default_text = "from the species", GE(0),
     .doc = "sliding friction coefficient of the pair"},
    {S(PAIR), "rolling_friction", NUM, "-", IN_PAIR(rolling_friction),
     .default_text = "from the species", GE(0), .doc = "rolling friction coefficient of the pair"},
    {S(PAIR), "stiffness", NUM, "N/m", IN_PAIR(stiffness), .default_text = "from the species",
     GT(0), .doc = "normal stiffness of the pair (linear law)"},

    // [wall NAME]
    {S(WALL), "type", .type = BDL_KEY_ENUM, "-", IN_WALL(kind), REQUIRED,
     .enum_names = bdl_wall_kind_names, .doc = "wall geometry"},
    {S(WALL), "point", VEC, "m", IN_WALL(point),
     WHEN("type",
          BIT(BDL_WALL_PLANE) | BIT(BDL_WALL_CYLINDER) | BIT(BDL_WALL_DISK) | BIT(BDL_WALL_CONE)),
     .required =
         BIT(BDL_WALL_PLANE) | BIT(BDL_WALL_CYLINDER) | BIT(BDL_WALL_DISK) | BIT(BDL_WALL_CONE),
     .default_text = "required for plane, cylinder, disk, cone",
     .doc = "plane: a point on the plane; cylinder: a point on the axis; disk: the centre; cone: "
            "the centre of the base circle"},
    {S(WALL), "normal", VEC, "-", .normalise = 1, IN_WALL(normal),
     WHEN("type", BIT(BDL_WALL_PLANE) | BIT(BDL_WALL_DISK)),
     .required = BIT(BDL_WALL_PLANE) | BIT(BDL_WALL_DISK),
     .default_text = "required for plane, disk",
     .doc = "plane normal pointing to the particle side (normalised); disk: its normal"},
    {S(WALL), "min", VEC, "m", IN_WALL(box_min), WHEN("type", BIT(BDL_WALL_BOX)),
     .required = BIT(BDL_WALL_BOX), .default_text = "required for box",
     .doc = "box: lower corner (particles stay inside)"},
    {S(WALL), "max", VEC, "m", IN_WALL(box_max), WHEN("type", BIT(BDL_WALL_BOX)),
     .required = BIT(BDL_WALL_BOX), .default_text = "required for box",
     .doc = "box: upper corner, larger than min on every axis"},
    {S(WALL), "axis", VEC, "-", .normalise = 1, IN_WALL(normal),
     WHEN("type", BIT(BDL_WALL_CYLINDER) | BIT(BDL_WALL_CONE)),
     .required = BIT(BDL_WALL_CYLINDER) | BIT(BDL_WALL_CONE),
     .default_text = "required for cylinder, cone",
     .doc = "cylinder: axis direction; cone: from the base circle to the top one (normalised)"},
    {S(WALL), "radius", NUM, "m", IN_WALL(radius),
     WHEN("type", BIT(BDL_WALL_CYLINDER) | BIT(BDL_WALL_DISK) | BIT(BDL_WALL_CONE)),
     .required = BIT(BDL_WALL_CYLINDER) | BIT(BDL_WALL_DISK) | BIT(BDL_WALL_CONE),
     .default_text = "required for cylinder, disk, cone", GT(0),
     .doc = "cylinder: radius (particles stay inside); disk: outer radius; cone: radius of the "
            "base circle"},
    {S(WALL), "hole_radius", NUM, "m", IN_WALL(hole_radius), WHEN("type", BIT(BDL_WALL_DISK)),
     .def = {0}, GE(0), .doc = "disk: radius of a central hole, smaller than radius (0: none)"},
    {S(WALL), "radius_top", NUM, "m", IN_WALL(radius_top), WHEN("type", BIT(BDL_WALL_CONE)),
     .required = BIT(BDL_WALL_CONE), .default_text = "required for cone", GE(0),
     .doc = "cone: radius of the top circle (0: a pointed cone; equal to radius: a tube)"},
    {S(WALL), "height", NUM, "m", IN_WALL(height), WHEN("type", BIT(BDL_WALL_CONE)),
     .required = BIT(BDL_WALL_CONE), .default_text = "required for cone", GT(0),
     .doc = "cone: distance from the base circle to the top one"},
    {S(WALL), "segments", .type = BDL_KEY_INT, "-", IN_WALL(segments),
     WHEN("type", BIT(BDL_WALL_DISK) | BIT(BDL_WALL_CONE)), .def = {96}, GE(3), LE(4096),
     .doc = "disk, cone: sides of the polygons that stand for the circles (two triangles each)"},
    {S(WALL), "file", .type = BDL_KEY_PATH, "-", IN_WALL(file), WHEN("type", BIT(BDL_WALL_MESH)),
     .required = BIT(BDL_WALL_MESH), .default_text = "required for mesh",
     .doc = "mesh: STL (ASCII or binary) or OBJ file of triangles, relative to the scene folder"},
    {S(WALL), "scale", NUM, "-", IN_WALL(scale), WHEN("type", BIT(BDL_WALL_MESH)), .def = {1},
     GT(0), .doc = "mesh: factor on the file's coordinates (0.001 for a file in millimetres)"},
    {S(WALL), "rotate", VEC, "deg", IN_WALL(rotate), WHEN("type", BIT(BDL_WALL_MESH)),
     .def = {0, 0, 0},
     .doc = "mesh: rotation after scaling, about x, then y, then z (right hand, degrees)"},
    {S(WALL), "translate", VEC, "m", IN_WALL(translate), WHEN("type", BIT(BDL_WALL_MESH)),
     .def = {0, 0, 0}, .doc = "mesh: shift after scaling and rotating"},
    {S(WALL), "periodic", .type = BDL_KEY_AXES, "-", IN_WALL(periodic),
     WHEN("type", BIT(BDL_WALL_MESH) | BIT(BDL_WALL_DISK) | BIT(BDL_WALL_CONE)),
     .doc = "the wall repeats along these periodic axes of the domain: a particle meets it at its "
            "position modulo the domain's length, so it may move along them for ever (a "
            "corrugated floor driving a shear cell); its triangles must repeat with that period "
            "and reach a particle diameter beyond the domain's faces on those axes"},
    {S(WALL), "open_time", NUM, "s", IN_WALL(open_time), .def = {INFINITY}, .default_text = "never",
     GE(0), .doc = "simulated time the wall is taken away (a gate, or the plug of an orifice)"},
    {S(WALL), "motion", .type = BDL_KEY_ENUM, "-", IN_WALL(motion), .def = {BDL_MOTION_NONE},
     .enum_names = bdl_motion_kind_names, .doc = "wall motion"},
    {S(WALL), "direction", VEC, "-", .normalise = 1, IN_WALL(direction), .def = {0, 0, 1},
     WHEN("motion", BIT(BDL_MOTION_VIBRATE)),
     .doc = "vibrate: direction of the displacement (normalised)"},
    {S(WALL), "frequency", NUM, "Hz", IN_WALL(frequency), WHEN("motion", BIT(BDL_MOTION_VIBRATE)),
     .required = BIT(BDL_MOTION_VIBRATE), .default_text = "required for vibrate", GT(0),
     .doc = "vibrate: frequency f"},
    {S(WALL), "amplitude", NUM, "m", IN_WALL(amplitude), WHEN("motion", BIT(BDL_MOTION_VIBRATE)),
     .default_text = "give amplitude or gamma", GT(0),
     .doc = "vibrate: displacement amplitude A (exclusive with gamma)"},
    {S(WALL), "gamma", NUM, "-", IN_RECORD(gamma), WHEN("motion", BIT(BDL_MOTION_VIBRATE)),
     .default_text = "give amplitude or gamma", GT(0),
     .doc = "vibrate: peak acceleration A (2 pi f)^2 / g in units of g = length of gravity "
            "(exclusive with amplitude)"},
    {S(WALL), "phase", NUM, "rad", IN_WALL(phase), WHEN("motion", BIT(BDL_MOTION_VIBRATE)),
     .def = {0}, .doc = "vibrate: phase of A sin(2 pi f t + phase)"},
    {S(WALL), "start", NUM, "s", IN_WALL(start),
     WHEN("motion", BIT(BDL_MOTION_VIBRATE) | BIT(BDL_MOTION_ROTATE) | BIT(BDL_MOTION_MOVE)),
     .def = {0}, GE(0),
     .doc = "vibrate, rotate, move: simulated time the motion starts (the wall stands still "
            "before; t is counted from here)"},
    {S(WALL), "velocity", VEC, "m/s", IN_WALL(velocity), WHEN("motion", BIT(BDL_MOTION_MOVE)),
     .required = BIT(BDL_MOTION_MOVE), .default_text = "required for move",
     .doc = "move: velocity of the wall"},
    {S(WALL), "stop", NUM, "s", IN_WALL(stop), WHEN("motion", BIT(BDL_MOTION_MOVE)),
     .def = {INFINITY}, .default_text = "never", GE(0),
     .doc = "move: simulated time the wall stops (it stays where it got to)"},
    {S(WALL), "rotation_axis", VEC, "-", .normalise = 1, IN_WALL(rotation_axis),
     WHEN("motion", BIT(BDL_MOTION_ROTATE)), .required = BIT(BDL_MOTION_ROTATE),
     .default_text = "required for rotate",
     .doc = "rotate: axis of the turn (normalised; the turn is right-handed about it)"},
    {S(WALL), "rotation_center", VEC, "m", IN_WALL(rotation_center),
     WHEN("motion", BIT(BDL_MOTION_ROTATE)), .required = BIT(BDL_MOTION_ROTATE),
     .default_text = "required for rotate", .doc = "rotate: a point on the axis of the turn"},
    {S(WALL), "angular_velocity", NUM, "rad/s", IN_WALL(angular_velocity),
     WHEN("motion", BIT(BDL_MOTION_ROTATE)), .required = BIT(BDL_MOTION_ROTATE),
     .default_text = "required for rotate", GE(-1e4), LE(1e4),
     .doc = "rotate: rate of the turn (negative: the other way); 1 rpm = 0.10472 rad/s"},
    {S(WALL), "frame", .type = BDL_KEY_ENUM, "-", IN_WALL(frame), .def = {BDL_FRAME_LAB},
     .enum_names = bdl_wall_frame_names, WHEN("motion", BIT(BDL_MOTION_VIBRATE)),
     .doc = "vibrate: lab (the wall moves through the domain) or container (the whole container, "
            "every wall and the gas grid, moves with this wall; particles and gas feel the "
            "inertial acceleration instead)"},
    {S(WALL), "youngs_modulus", NUM, "Pa", IN_WALL(material.youngs_modulus), .def = {-1},
     .default_text = "species value", GT(0), .doc = "wall Young's modulus (Hertz law)"},
    // >= 0 rather than > -1: a negative value would read as "not given" (-1) to the solver.
    {S(WALL), "poisson_ratio", NUM, "-", IN_WALL(material.poisson_ratio), .def = {-1},
     .default_text = "species value", GE(0), LT(0.5), .doc = "wall Poisson's ratio"},
    {S(WALL), "stiffness", NUM, "N/m", IN_WALL(material.stiffness), .def = {-1},
     .default_text = "species value", GT(0), .doc = "wall-particle normal stiffness (linear law)"},
    {S(WALL), "tangential_stiffness", NUM, "N/m", IN_WALL(material.tangential_stiffness),
     .def = {-1}, .default_text = "species value", GT(0),
     .doc = "wall-particle tangential stiffness (linear law)"},
    {S(WALL), "restitution", NUM, "-", IN_WALL(material.restitution), .def = {-1},
     .default_text = "species value", GT(0), LE(1),
     .doc = "wall-particle coefficient of restitution"},
    {S(WALL), "friction", NUM, "-", IN_WALL(material.friction), .def = {-1},
     .default_text = "species value", GE(0), .doc = "wall-particle sliding friction coefficient"},
    {S(WALL), "rolling_friction", NUM, "-", IN_WALL(material.rolling_friction), .def = {-1},
     .default_text = "species value", GE(0), .doc = "wall-particle rolling friction coefficient"},
    {S(WALL), "tangential_damping_ratio", NUM, "-", IN_WALL(material.tangential_damping_ratio),
     .def = {-1}, .default_text = "species value", GE(0), LE(1),
     .doc = "wall-particle tangential to normal damping ratio"},

    // [create NAME]
    {S(CREATE), "type", .type = BDL_KEY_ENUM, "-", IN_CREATE(kind), REQUIRED,
     .enum_names = bdl_create_kind_names, .doc = "how particles are created"},
    {S(CREATE), "species", .type = BDL_KEY_NAME, "-", IN_RECORD(species_ref),
     .default_text = "the only species (required if there are several)",
     .doc = "name of the [species NAME] section of the created particles"},
    {S(CREATE), "region_min", VEC, "m", IN_CREATE(region_min),
     WHEN("type", BIT(BDL_CREATE_RANDOM) | BIT(BDL_CREATE_LATTICE) | BIT(BDL_CREATE_POUR)),
     .required = BIT(BDL_CREATE_RANDOM) | BIT(BDL_CREATE_LATTICE) | BIT(BDL_CREATE_POUR),
     .default_text = "required for random, lattice, pour",
     .doc = "lower corner of the region (inside the domain)"},
    {S(CREATE), "region_max", VEC, "m", IN_CREATE(region_max),
     WHEN("type", BIT(BDL_CREATE_RANDOM) | BIT(BDL_CREATE_LATTICE) | BIT(BDL_CREATE_POUR)),
     .required = BIT(BDL_CREATE_RANDOM) | BIT(BDL_CREATE_LATTICE) | BIT(BDL_CREATE_POUR),
     .default_text = "required for random, lattice, pour",
     .doc = "upper corner of the region (inside the domain)"},
    {S(CREATE), "region_shape", .type = BDL_KEY_ENUM, "-", IN_CREATE(region_shape),
     WHEN("type", BIT(BDL_CREATE_RANDOM) | BIT(BDL_CREATE_POUR)), .def = {BDL_REGION_BOX},
     .enum_names = bdl_region_shape_names,
     .doc = "random, pour: the box, or the cylinder inscribed in it along region_axis"},
    {S(CREATE), "region_axis", .type = BDL_KEY_ENUM, "-", IN_CREATE(region_axis),
     WHEN("type", BIT(BDL_CREATE_RANDOM) | BIT(BDL_CREATE_POUR)), .def = {2},
     .enum_names = axis_names, .doc = "random, pour: the axis of a cylindrical region"},
    {S(CREATE), "region_file", .type = BDL_KEY_PATH, "-", IN_CREATE(region_file),
     WHEN("region_shape", BIT(BDL_REGION_MESH)), .required = BIT(BDL_REGION_MESH),
     .default_text = "required for region_shape = mesh",
     .doc = "mesh region: STL or OBJ file of a closed surface, relative to the scene folder"},
    {S(CREATE), "region_scale", NUM, "-", IN_CREATE(region_scale),
     WHEN("region_shape", BIT(BDL_REGION_MESH)), .def = {1}, GT(0),
     .doc = "mesh region: factor on the file's coordinates (0.001 for millimetres)"},
    {S(CREATE), "region_rotate", VEC, "deg", IN_CREATE(region_rotate),
     WHEN("region_shape", BIT(BDL_REGION_MESH)), .def = {0, 0, 0},
     .doc = "mesh region: rotation after scaling, about x, then y, then z (degrees)"},
    {S(CREATE), "region_translate", VEC, "m", IN_CREATE(region_translate),
     WHEN("region_shape", BIT(BDL_REGION_MESH)), .def = {0, 0, 0},
     .doc = "mesh region: shift after scaling and rotating"},
    {S(CREATE), "count", .type = BDL_KEY_LONG, "-", IN_CREATE(count),
     WHEN("type", BIT(BDL_CREATE_RANDOM) | BIT(BDL_CREATE_LATTICE) | BIT(BDL_CREATE_POUR)),
     .required = BIT(BDL_CREATE_POUR), .def = {-1},
     .default_text = "required for pour; random: count or volume_fraction; lattice: fill", GT(0),
     LE(1e15), .doc = "number of particles"},
    {S(CREATE), "volume_fraction", NUM, "-", IN_CREATE(volume_fraction),
     WHEN("type", BIT(BDL_CREATE_RANDOM)), .def = {-1},
     .default_text = "random: count or volume_fraction", GT(0), LE(0.64),
     .doc = "random: solids fraction of the region to fill"},
    {S(CREATE), "spacing", NUM, "m", IN_CREATE(spacing), WHEN("type", BIT(BDL_CREATE_LATTICE)),
     .def = {-1}, .default_text = "1.0001 * largest diameter", GT(0),
     .doc = "lattice: distance between neighbouring lattice sites"},
    {S(CREATE), "rate", NUM, "particles/s", IN_CREATE(rate), WHEN("type", BIT(BDL_CREATE_POUR)),
     .required = BIT(BDL_CREATE_POUR), .default_text = "required for pour", GT(0),
     .doc = "pour: insertion rate"},
    {S(CREATE), "start_time", NUM, "s", IN_CREATE(start_time), WHEN("type", BIT(BDL_CREATE_POUR)),
     .def = {0}, GE(0), .doc = "pour: simulated time of the first insertion"},
    {S(CREATE), "stop_time", NUM, "s", IN_CREATE(stop_time), WHEN("type", BIT(BDL_CREATE_POUR)),
     .def = {INFINITY}, .default_text = "never", GE(0),
     .doc = "pour: no insertion from this time on, whether count is reached or not"},
    {S(CREATE), "velocity", VEC, "m/s", IN_CREATE(velocity), .def = {0, 0, 0},
     .doc = "initial velocity of the created particles"},
    {S(CREATE), "velocity_jitter", NUM, "m/s", IN_CREATE(velocity_jitter), .def = {0}, GE(0),
     .doc = "magnitude of a random velocity added to each particle"},
    {S(CREATE), "file", .type = BDL_KEY_PATH, "-", IN_CREATE(file),
     WHEN("type", BIT(BDL_CREATE_FILE)), .required = BIT(BDL_CREATE_FILE),
     .default_text = "required for file",
     .doc = "file: CSV file of positions (optionally diameters, velocities, rod axes), relative "
            "to the scene folder"},

    // [sink NAME]
    {S(SINK), "min", VEC, "m", IN_SINK(min), REQUIRED,
     .doc = "lower corner of the box whose particles are removed"},
    {S(SINK), "max", VEC, "m", IN_SINK(max), REQUIRED,
     .doc = "upper corner of the box, larger than min on every axis"},
    {S(SINK), "start_time", NUM, "s", IN_SINK(start_time), .def = {0}, GE(0),
     .doc = "simulated time the sink starts removing particles"},

    // [output]
    {S(OUTPUT), "diagnostics_interval", NUM, "s", IN_SCENE(output.diagnostics_interval),
     .def = {1e-3}, GT(0), .doc = "simulated time between rows of diagnostics.csv"},
    {S(OUTPUT), "vtk_interval", NUM, "s", IN_SCENE(output.vtk_interval), .def = {0},
     .default_text = "0 (none)", GE(0),
     .doc = "simulated time between particle VTK files; 0 = none"},
    {S(OUTPUT), "checkpoint_interval", NUM, "s", IN_SCENE(output.checkpoint_interval), .def = {0},
     .default_text = "0 (start and end only)", GE(0),
     .doc = "simulated time between checkpoints (checkpoint/state.bdlckpt; the time series reach "
            "the disk at each); 0 = only at the start, at the end and on Ctrl-C"},
    {S(OUTPUT), "progress_interval", NUM, "s", IN_SCENE(output.progress_interval), .def = {1},
     GT(0), .doc = "wall-clock time between progress lines"},
    {S(OUTPUT), "frame_interval", NUM, "s", IN_SCENE(output.frame_interval), .def = {0},
     .default_text = "0 (none)", GE(0),
     .doc = "simulated time between PNG frames in frames/ (drawn as [camera] says); 0 = none"},
    {S(OUTPUT), "frame_width", .type = BDL_KEY_INT, "px", IN_SCENE(output.frame_width),
     .def = {1280}, GE(16), LE(8192), .doc = "width of the PNG frames"},
    {S(OUTPUT), "frame_height", .type = BDL_KEY_INT, "px", IN_SCENE(output.frame_height),
     .def = {720}, GE(16), LE(8192), .doc = "height of the PNG frames"},
    {S(OUTPUT), "frame_samples", .type = BDL_KEY_INT, "-", IN_SCENE(output.frame_samples),
     .def = {4}, GE(0), LE(16), .doc = "multisample anti-aliasing samples per pixel; 0 = none"},
    {S(OUTPUT), "contacts_interval", NUM, "s", IN_SCENE(output.contacts_interval), .def = {0},
     .default_text = "0 (none)", GE(0),
     .doc = "simulated time between contact files in contacts/ (every contact: particles, "
            "positions, normal force; for force networks); 0 = none"},
    {S(OUTPUT), "mixing_cells", VEC, "-", IN_SCENE(output.mixing_cells), .def = {0, 0, 0},
     .default_text = "the gas grid's cells, else 10 10 10",
     .doc = "cells along x y z of the grid on which species.csv's Lacey indices are taken "
            "(scenes of two species; whole numbers >= 1)"},
    {S(OUTPUT), "orientation_interval", NUM, "s", IN_SCENE(output.orientation_interval), .def = {0},
     .default_text = "0 (none)", GE(0),
     .doc =
         "simulated time between rows of orientation.csv (scenes with rods: histograms of the "
         "rods' angle in the x-z plane near the front and back walls and in the bulk); 0 = none"},
    {S(OUTPUT), "fields_interval", NUM, "s", IN_SCENE(output.fields_interval), .def = {0},
     .default_text = "0 (none)", GE(0),
     .doc = "simulated time between samples of the particles for fields.vti (the solids fraction "
            "and solids velocity averaged over the samples on a grid of cubic cells; written at "
            "every checkpoint and at the end); 0 = none"},
    {S(OUTPUT), "fields_start", NUM, "s", IN_SCENE(output.fields_start), .def = {0}, GE(0),
     .doc = "simulated time of the first sample counted in fields.vti (earlier ones are not)"},
    {S(OUTPUT), "fields_cell", NUM, "m", IN_SCENE(output.fields_cell), .def = {-1},
     .default_text = "three mean diameters of the particles at the start", GT(0),
     .doc = "side of the cells of fields.vti (each axis divided into whole cells, at least one); "
            "at most the domain's largest side, and at most 5e7 cells over the domain"},
    {S(OUTPUT), "rheology_interval", NUM, "s", IN_SCENE(output.rheology_interval), .def = {0},
     .default_text = "0 (none)", GE(0),
     .doc = "simulated time between rows of rheology.csv: the stress tensor of the bulk "
            "(streaming and contact parts), granular temperature, shear rate, solids fraction, "
            "mu = tau/p, inertial number, normal-stress differences (shear along x, gradient "
            "along z); 0 = none"},
    {S(OUTPUT), "rheology_margin", NUM, "m", IN_SCENE(output.rheology_margin), .def = {0}, GE(0),
     .doc = "rheology.csv: the bulk region leaves out this much at the domain's lower and upper "
            "z faces (the layers next to driving walls)"},
    {S(OUTPUT), "rheology_bins", .type = BDL_KEY_INT, "-", IN_SCENE(output.rheology_bins),
     .def = {16}, GE(2), LE(4096),
     .doc = "rheology.csv: slabs across z over which the mean velocity is taken (the velocity "
            "fluctuation is the velocity less its slab's mean)"},

    // [camera]
    {S(CAMERA), "view", .type = BDL_KEY_ENUM, "-", IN_CAMERA(view), .def = {BDL_VIEW_ISO},
     .default_text = "iso; front for a pseudo-2D domain", .enum_names = bdl_view_preset_names,
     .doc = "preset direction: iso (front-right, above), front (along +y, the x-z plane), side "
            "(along -x), top (down -z); a domain whose y is thinner than a fifth of x and of z "
            "is seen from the front unless view is given"},
    {S(CAMERA), "projection", .type = BDL_KEY_ENUM, "-", IN_CAMERA(projection),
     .def = {BDL_PROJ_PERSPECTIVE}, .enum_names = bdl_projection_names,
     .doc = "perspective or orthographic (no foreshortening: pseudo-2D beds, DIA)"},
    {S(CAMERA), "color", .type = BDL_KEY_ENUM, "-", IN_CAMERA(color), .def = {BDL_COLOR_SPEED},
     .enum_names = bdl_color_mode_names,
     .doc = "particle colour: species, coordination (contacts; not for parcels), speed, vx, vy, "
            "vz (velocity component), voidage (void fraction around the particle), solids (the "
            "gas's solids fraction 1 - eps at the particle, kernel-interpolated); with rods tilt "
            "(angle of the axis to z, 0 vertical to 90 horizontal) and azimuth (angle of the axis "
            "in the x-y plane, modulo 180)"},
    {S(CAMERA), "color_min", NUM, "unit of the field", IN_CAMERA_FLAGGED(color_min),
     .default_text = "automatic", .doc = "value at the low end of the colour map"},
    {S(CAMERA), "color_max", NUM, "unit of the field", IN_CAMERA_FLAGGED(color_max),
     .default_text = "automatic", .doc = "value at the high end of the colour map"},
    {S(CAMERA), "target", VEC, "m", IN_CAMERA_FLAGGED(target), .default_text = "domain centre",
     .doc = "point the camera looks at"},
    {S(CAMERA), "distance", NUM, "m", IN_CAMERA(distance), .def = {0}, .default_text = "0 (fit)",
     GE(0), .doc = "eye to target; 0 = far enough to see the whole domain"},
    {S(CAMERA), "yaw", NUM, "deg", IN_CAMERA_FLAGGED(yaw), .default_text = "from view", GE(-360),
     LE(360), .doc = "turn about +z; 0 looks along +y, 90 along -x"},
    {S(CAMERA), "pitch", NUM, "deg", IN_CAMERA_FLAGGED(pitch), .default_text = "from view", GE(-90),
     LE(90), .doc = "elevation of the eye above the target's horizontal plane"},
    {S(CAMERA), "fov", NUM, "deg", IN_CAMERA(fov), .def = {35}, GT(1), LT(170),
     .doc = "vertical field of view (perspective)"},
    {S(CAMERA), "clip", .type = BDL_KEY_BOOL, "-", IN_CAMERA(clip), .def = {0},
     .doc = "cut the bed open: hide the particles whose centres lie on the clip_normal side of "
            "the clipping plane"},
    {S(CAMERA), "clip_point", VEC, "m", IN_CAMERA_FLAGGED(clip_point), .default_text = "the target",
     .doc = "a point on the clipping plane"},
    {S(CAMERA), "clip_normal", VEC, "-", IN_CAMERA(clip_normal), .def = {0, -1, 0}, .normalise = 1,
     .doc = "normal of the clipping plane, pointing to the hidden side"},
    {S(CAMERA), "lighting", .type = BDL_KEY_BOOL, "-", IN_CAMERA(lighting), .def = {1},
     .doc = "shade the spheres; false draws flat colours"},
    {S(CAMERA), "overlay", .type = BDL_KEY_BOOL, "-", IN_CAMERA(overlay), .def = {1},
     .doc = "draw the text (time, step, field, solver speed) and the colour bar"},
    {S(CAMERA), "outlines", .type = BDL_KEY_BOOL, "-", IN_CAMERA(outlines), .def = {1},
     .doc = "draw the outlines of the domain and the walls"},
    {S(CAMERA), "background", VEC, "-", IN_CAMERA(background), .def = {0.11, 0.12, 0.14}, GE(0),
     LE(1), .doc = "background colour, sRGB red green blue in 0..1"},
    {S(CAMERA), "gas_field", .type = BDL_KEY_ENUM, "-", IN_CAMERA(gas_field),
     .def = {BDL_GAS_FIELD_NONE}, .enum_names = bdl_gas_field_names,
     .doc = "with [gas]: a gas field drawn on a translucent slice of the grid, one flat colour per "
            "cell (sequential map, range of the slice)"},
    {S(CAMERA), "gas_slice_axis", .type = BDL_KEY_ENUM, "-", IN_CAMERA(gas_slice_axis), .def = {1},
     .enum_names = axis_names, .doc = "normal of the slice plane"},
    {S(CAMERA), "gas_slice_position", NUM, "-", IN_CAMERA(gas_slice_position), .def = {0.5}, GE(0),
     LE(1),
     .doc = "where the slice lies along its axis, as a fraction of the domain (1 = the far side "
            "of a front view: behind the particles)"},
    {S(CAMERA), "gas_opacity", NUM, "-", IN_CAMERA(gas_opacity), .def = {0.6}, GE(0), LE(1),
     .doc = "opacity of the slice"},

    // [camera NAME] (kind = dia)
    {S(DIA), "kind", .type = BDL_KEY_ENUM, "-", IN_DIA(kind), REQUIRED,
     .enum_names = dia_kind_names,
     .doc = "what the camera makes: dia, synthetic grey images for digital image analysis with "
            "their ground truth, in dia/NAME/ of the run folder"},
    {S(DIA), "projection", .type = BDL_KEY_ENUM, "-", IN_DIA(projection), .def = {0},
     .enum_names = bdl_dia_projection_names,
     .doc = "orthographic (a telecentric view) or perspective (a pinhole camera)"},
    {S(DIA), "position", VEC, "m", IN_DIA(position), REQUIRED,
     .doc = "perspective: the pinhole; orthographic: the centre of the view, in front of the bed"},
    {S(DIA), "target", VEC, "m", IN_DIA(target), REQUIRED,
     .doc = "a point on the optical axis: the camera looks from position towards it"},
    {S(DIA), "up", VEC, "-", .normalise = 1, IN_DIA(up), .def = {0, 0, 1},
     .doc = "world direction that appears up in the image"},
    {S(DIA), "width", .type = BDL_KEY_INT, "px", IN_DIA(width), .def = {500}, GE(8), LE(8192),
     .doc = "image width"},
    {S(DIA), "height", .type = BDL_KEY_INT, "px", IN_DIA(height), .def = {1000}, GE(8), LE(8192),
     .doc = "image height"},
    {S(DIA), "pixel_size", NUM, "m", IN_DIA(pixel_size), REQUIRED, GT(0),
     .doc = "orthographic: the size of a pixel at the object; perspective: the sensor's pixel "
            "pitch"},
    {S(DIA), "focal_length", NUM, "m", IN_DIA(focal_length), .def = {0.025}, GT(0),
     WHEN("projection", BIT(1)), .doc = "focal length of the lens (perspective)"},
    {S(DIA), "samples", .type = BDL_KEY_INT, "-", IN_DIA(samples), .def = {3}, GE(1), LE(8),
     .doc = "rays per pixel along each axis (samples^2 per pixel): anti-aliasing and the "
            "resolution of the truth"},
    {S(DIA), "lighting", .type = BDL_KEY_ENUM, "-", IN_DIA(lighting), .def = {0},
     .enum_names = bdl_dia_lighting_names,
     .doc = "front: lights on the camera's side, bright spheres on a dark background; back: a "
            "light panel behind the bed, dark silhouettes on a bright background"},
    {S(DIA), "light_position", VEC, "m", IN_DIA(light_position), .has_flag = 1,
     .flag_offset = offsetof(bdl_dia_scene_def, has_light_position),
     .default_text = "the camera position", .doc = "a point light (front lighting)"},
    {S(DIA), "lights", .type = BDL_KEY_INT, "-", IN_DIA(lights), .def = {1}, GE(1), LE(4),
     .doc = "number of lights: 1 at light_position, or 2 to 4 on a ring around it in the image "
            "plane (like LEDs around the lens), sharing light_intensity"},
    {S(DIA), "light_spread", NUM, "m", IN_DIA(light_spread), .def = {0.05}, GE(0),
     .doc = "radius of the ring of lights"},
    {S(DIA), "light_intensity", NUM, "-", IN_DIA(light_intensity), .def = {0.6}, GE(0),
     .doc = "the lights' share of full brightness on a surface facing them (front lighting)"},
    {S(DIA), "ambient", NUM, "-", IN_DIA(ambient), .def = {0.4}, GE(0), LE(1),
     .doc = "brightness every visible sphere surface gets (front lighting)"},
    {S(DIA), "dark", NUM, "-", IN_DIA(dark), .def = {0.05}, GE(0), LE(1),
     .doc = "grey level of the background (front) or of a silhouette (back), 0..1"},
    {S(DIA), "bright", NUM, "-", IN_DIA(bright), .def = {0.95}, GE(0), LE(1),
     .doc = "grey level of a fully lit sphere (front) or of the light panel (back), 0..1"},
    {S(DIA), "fade", NUM, "m", IN_DIA(fade), .def = {0}, GE(0),
     .doc = "front lighting: the light falls off as exp(-s/fade) with the depth s behind the "
            "domain's front face, so particles behind the first layer look darker, as in a "
            "packed bed; 0 = no fall-off"},
    {S(DIA), "blur", NUM, "px", IN_DIA(blur), .def = {0}, GE(0), LE(20),
     .doc = "defocus: Gaussian blur, standard deviation"},
    {S(DIA), "noise", NUM, "-", IN_DIA(noise), .def = {0}, GE(0), LE(1),
     .doc = "sensor noise: Gaussian, standard deviation as a fraction of full scale"},
    {S(DIA), "gamma", NUM, "-", IN_DIA(gamma), .def = {1}, GT(0), LE(5),
     .doc = "stored grey = linear^(1/gamma)"},
    {S(DIA), "bits", .type = BDL_KEY_INT, "-", IN_DIA(bits), .def = {8}, GE(8), LE(16),
     .doc = "bits per pixel of the PNG: 8 or 16"},
    {S(DIA), "start", NUM, "s", IN_DIA(start), .def = {0}, GE(0),
     .doc = "simulated time of the first image"},
    {S(DIA), "interval", NUM, "s", IN_DIA(interval), REQUIRED, GT(0),
     .doc = "simulated time between images (or between the first frames of PIV pairs)"},
    {S(DIA), "stop", NUM, "s", IN_DIA(stop), .def = {0}, GE(0),
     .doc = "simulated time after which no image is taken (a high-speed burst for PTV: a short "
            "interval between start and stop); 0 = to the end of the run"},
    {S(DIA), "pair_dt", NUM, "s", IN_DIA(pair_dt), .def = {0}, GE(0),
     .doc = "0: single images; > 0: double frames this far apart for PIV (rounded to whole "
            "time steps)"},
    {S(DIA), "cells_across", .type = BDL_KEY_INT, "-", IN_DIA(cells_across), .def = {10}, GE(1),
     LE(1000), .doc = "ground-truth grid: image cells across"},
    {S(DIA), "cells_down", .type = BDL_KEY_INT, "-", IN_DIA(cells_down), .def = {20}, GE(1),
     LE(1000), .doc = "ground-truth grid: image cells down"},
    {S(DIA), "seed", .type = BDL_KEY_U64, "-", IN_DIA(seed), .def = {1}, GE(0),
     .doc = "seed of the sensor noise"},

    // [gas]
    {S(GAS), "density", NUM, "kg/m^3", IN_GAS(density), .def = {1.2}, GT(0),
     .doc = "gas density (air at 20 C: 1.2)"},
    {S(GAS), "viscosity", NUM, "Pa s", IN_GAS(viscosity), .def = {1.8e-5}, GT(0),
     .doc = "dynamic viscosity (air at 20 C: 1.8e-5)"},
    {S(GAS), "cells", VEC, "-", IN_GAS(cells), .def = {1, 1, 1}, .default_text = "required", GE(1),
     LE(4096), .doc = "grid cells along x, y, z (whole numbers; 1 along an axis for 2D)"},
    {S(GAS), "convection", .type = BDL_KEY_ENUM, "-", IN_GAS(convection),
     .def = {BDL_CONVECTION_VANLEER}, .enum_names = bdl_convection_names,
     .doc = "momentum convection: upwind, vanleer or superbee (TVD), central (verification only)"},
    {S(GAS), "convection_step", .type = BDL_KEY_ENUM, "-", IN_GAS(convection_step),
     .def = {BDL_CONVECTION_EXPLICIT}, .enum_names = bdl_convection_step_names,
     .doc = "explicit (the gas's step at most a Courant number of 1/2) or point_implicit (the "
            "upwind part's diagonal implicit, the limiter's correction explicit and scaled down "
            "above a Courant number of 1: no Courant limit on the gas's step; with [solids] only)"},
    {S(GAS), "tolerance", NUM, "-", IN_GAS(tolerance), .def = {1e-8}, GT(0), LT(1),
     .doc = "relative residual at which the pressure solver stops"},
    {S(PARALLEL), "decomposition", VEC, "-", IN_SCENE(decomposition), .def = {0, 0, 0},
     .default_text = "0 0 0 (automatic)", GE(0), LE(4096),
     .doc = "MPI ranks along x, y, z (whole numbers whose product is the rank count); 0 0 0 "
            "chooses the division that balances the particles, then the least cut area"},
    {S(GAS), "pressure_solver", .type = BDL_KEY_ENUM, "-", IN_GAS(pressure_solver),
     .def = {BDL_PRESSURE_MGPCG}, .enum_names = bdl_pressure_solver_names,
     .doc =
         "mgpcg (bedlam's multigrid-preconditioned conjugate gradients), hypre (hypre's CG "
         "preconditioned by its PFMG multigrid; builds with -DBDL_WITH_MPI=ON) or direct "
         "(a banded Cholesky factorisation, refactored every step: fastest on narrow grids such as "
         "pseudo-2D beds; no periodic axis of more than one cell, an x row or x-y layer of "
         "at most 1024 cells, cells x band^2 at most 1e9)"},
    GAS_SIDE("xmin", 0),
    GAS_SIDE("xmax", 1),
    GAS_SIDE("ymin", 2),
    GAS_SIDE("ymax", 3),
    GAS_SIDE("zmin", 4),
    GAS_SIDE("zmax", 5),
    {S(GAS), "inlet_velocity", NUM, "m/s", IN_GAS(inlet_velocity), .def = {0}, GE(0),
     .doc = "superficial gas velocity through the inlet sides"},
    {S(GAS), "distributor_resistance", NUM, "Pa s/m", IN_GAS(distributor_resistance), .def = {0},
     .default_text = "0 (uniform inflow)", GE(0),
     .doc = "> 0: the inlets are porous plates over a plenum; the gas crosses each inlet face at "
            "(plenum pressure - pressure above it) / resistance, the plenum pressure keeping the "
            "mean at inlet_velocity (a plate dropping 30 % of a bed's weight per area W at "
            "velocity U: 0.3 W / U); no jet"},
    {S(GAS), "outlet_pressure", NUM, "Pa", IN_GAS(outlet_pressure), .def = {0},
     .doc = "pressure at the outlet sides (gauge)"},
    {S(GAS), "jet_velocity", NUM, "m/s", IN_GAS(jet_velocity), .def = {0}, GE(0),
     .doc = "superficial velocity through the jet rectangle jet_min..jet_max of the inlets"},
    {S(GAS), "jet_min", VEC, "m", IN_GAS(jet_min), .has_flag = 1,
     .flag_offset = offsetof(bdl_scene, gas.has_jet_min), .default_text = "no jet",
     .doc = "low corner of the jet rectangle (the coordinate normal to the inlet is ignored)"},
    {S(GAS), "jet_max", VEC, "m", IN_GAS(jet_max), .has_flag = 1,
     .flag_offset = offsetof(bdl_scene, gas.has_jet_max), .default_text = "no jet",
     .doc = "high corner of the jet rectangle"},
    {S(GAS), "dt", NUM, "s", IN_GAS(dt), .def = {0}, .default_text = "0 (automatic)", GE(0),
     .doc = "gas time step, rounded down to a whole number of particle steps; 0 = CFL 0.5 for "
            "the inflow through the densest packing (plus 0.5 m/s) on the axes with more than one "
            "cell, within the viscous limit, at most 5e-4 s; a run stops with an error when the "
            "gas step exceeds twice the stable one"},
    {S(GAS), "sweep", .type = BDL_KEY_ENUM, "-", IN_GAS(sweep), .def = {0},
     .enum_names = bdl_sweep_names,
     .doc = "a stepwise sweep of the inlet velocity, as a pressure-drop measurement is made: up "
            "from inlet_velocity to sweep_to, down to it, or up and back down to inlet_velocity; "
            "each stage lasts sweep_dwell; diagnostics.csv's inlet_velocity column follows it"},
    {S(GAS), "sweep_to", NUM, "m/s", IN_GAS(sweep_to), .def = {0}, GE(0),
     .doc = "the far end of the sweep"},
    {S(GAS), "sweep_step", NUM, "m/s", IN_GAS(sweep_step), .def = {0.2}, GT(0),
     .doc = "velocity change between stages of the sweep"},
    {S(GAS), "sweep_dwell", NUM, "s", IN_GAS(sweep_dwell), .def = {1}, GT(0),
     .doc = "duration of each stage of the sweep"},
    {S(GAS), "sweep_start", NUM, "s", IN_GAS(sweep_start), .def = {0}, GE(0),
     .doc = "simulated time at which the sweep starts (inlet_velocity before)"},
    {S(GAS), "probe_low", NUM, "m", IN_GAS(probe_low), .has_flag = 1,
     .flag_offset = offsetof(bdl_scene, gas.has_probe_low), .default_text = "no probes", GE(0),
     .doc = "height above the domain's floor (along gravity) of the lower pressure probe; "
            "diagnostics.csv's probe_pressure_drop is the pressure there minus at probe_high"},
    {S(GAS), "probe_high", NUM, "m", IN_GAS(probe_high), .has_flag = 1,
     .flag_offset = offsetof(bdl_scene, gas.has_probe_high), .default_text = "no probes", GT(0),
     .doc = "height of the upper pressure probe, above probe_low and inside the domain"},
    {S(GAS), "bubble_voidage", NUM, "-", IN_GAS(bubble_voidage), .def = {0.85}, GT(0), LE(1),
     .doc = "diagnostics.csv's bubbles are the regions of cells above this voidage that do not "
            "reach the top layer (Kuipers et al. 1992: 0.85); bubble_count and bubble_diameter "
            "(the mean equivalent diameter: of a circle in a bed one cell deep, else a sphere)"},

    // [coupling]
    {S(COUPLING), "drag", .type = BDL_KEY_ENUM, "-", IN_COUPLING(drag), .def = {4},
     .enum_names = bdl_drag_law_names, .default_text = "gidaspow",
     .doc = "drag law: stokes, schiller_naumann, wen_yu, ergun, gidaspow, syamlal_obrien, "
            "di_felice, beetstra, tenneti, tsuji (docs/verification-gas.md); for rods hdf, ste, "
            "sta (docs/theory-rods.md)"},
    {S(COUPLING), "kernel_width", NUM, "m", IN_COUPLING(kernel_width), .def = {0},
     .default_text = "0 (1.5 cells)", GE(0),
     .doc = "half-width of the kernel that spreads particles over the grid; at least one cell, "
            "at most four"},
    {S(COUPLING), "max_solids", NUM, "-", IN_COUPLING(max_solids), .def = {0.7}, GT(0), LT(1),
     .doc = "cap on the solids fraction deposited in a cell"},
    {S(COUPLING), "drag_velocity", .type = BDL_KEY_ENUM, "-", IN_COUPLING(drag_velocity),
     .def = {0}, .enum_names = drag_velocity_names, .default_text = "particle",
     .doc = "the solids velocity in the drag: particle (each particle's own; Sun 2007's "
            "'instantaneous' TF-DEM method) or mean (the solids' volume-weighted mean over the "
            "cells around the particle, read with the kernel: every particle of a cell drawn by "
            "the cell's mean drag, Sun's 'averaged' method, eqs. 7.33-7.34; not for parcels)"},
    {S(COUPLING), "syamlal_c", NUM, "-", IN_COUPLING(syamlal_c), .def = {0.8}, GT(0),
     .doc = "Syamlal-O'Brien C (Sun 2007, table 4.3: 0.8, 0.7, 0.64)"},
    {S(COUPLING), "syamlal_d", NUM, "-", IN_COUPLING(syamlal_d), .def = {2.65}, GT(0),
     .doc = "Syamlal-O'Brien D (2.65, 3.44, 4.03 with the C above)"},

    // [parcels]
    {S(PARCELS), "model", .type = BDL_KEY_ENUM, "-", IN_PARCELS(model), .def = {BDL_PARCEL_STRESS},
     .enum_names = bdl_parcel_model_names, .default_text = "stress",
     .doc = "what keeps parcels from close packing (Patankar & Joseph 2001): stress (model A: an "
            "interparticle stress on the gas grid) or collisions (model B: soft-sphere forces "
            "between parcel spheres and with the domain's sides)"},
    {S(PARCELS), "stress_pressure", NUM, "Pa", IN_PARCELS(stress_pressure), .def = {100}, GE(0),
     LE(1e9), .doc = "P_s of the stress P_s theta^beta / (theta_cs - theta)"},
    {S(PARCELS), "stress_exponent", NUM, "-", IN_PARCELS(stress_exponent), .def = {3}, GE(0),
     LE(10), .doc = "beta of the stress"},
    {S(PARCELS), "close_packing", NUM, "-", IN_PARCELS(close_packing), .def = {0.6}, GT(0), LT(1),
     .doc = "theta_cs: no cell's solids fraction exceeds it (the packing guard)"},
    {S(PARCELS), "stress_floor", NUM, "-", IN_PARCELS(stress_floor), .def = {1e-3}, GT(0), LT(1),
     .doc = "least theta_cs - theta in the stress's denominator: the stress stays finite"},
    {S(PARCELS), "substeps", .type = BDL_KEY_INT, "-", IN_PARCELS(substeps), .def = {1}, GE(1),
     LE(100), .doc = "K: each step's drift in this many parts, the sides met in each"},
    {S(PARCELS), "gas_substeps", .type = BDL_KEY_INT, "-", IN_PARCELS(gas_substeps), .def = {1},
     GE(1), LE(100),
     .doc = "most gas steps per step: the gas sub-cycles as its CFL asks, the parcels keep dt"},
    {S(PARCELS), "wall_restitution", NUM, "-", IN_PARCELS(wall_restitution), .def = {0.9}, GE(0),
     LE(1), .doc = "normal restitution of a parcel reflected at a side of the domain"},
    {S(PARCELS), "display", .type = BDL_KEY_ENUM, "-", IN_SCENE(parcels.display),
     .def = {BDL_PARCEL_DISPLAY_PARCEL}, .enum_names = bdl_parcel_display_names,
     .doc = "how frames and the viewer draw a parcel: parcel (the sphere of its solids volume, "
            "radius cbrt(3 V / (4 pi))) or real (a sphere of one real particle's radius)"},
    {S(PARCELS), "collision_stiffness", NUM, "N/m^1.5", IN_PARCELS(collision_stiffness),
     .def = {800}, GT(0), LE(1e12),
     .doc = "model B: k_c of the force k_c delta^m - eta_c u_n between parcel spheres and with the "
            "sides (the unit is N/m^m)"},
    {S(PARCELS), "collision_exponent", NUM, "-", IN_PARCELS(collision_exponent), .def = {1.5},
     GE(1), LE(2),
     .doc = "model B: m of k_c delta^m (the paper's 3/2; 1 is a linear spring, for which the "
            "damping from collision_restitution is exact)"},
    {S(PARCELS), "collision_damping", NUM, "kg/s", IN_PARCELS(collision_damping), .def = {-1},
     .default_text = "from collision_restitution", GE(0), LE(1e12),
     .doc = "model B: eta_c; by default 2 alpha sqrt(M k_c / (1 + alpha^2)), alpha = -ln(e)/pi, "
            "M the smallest parcel mass (the paper's eq. 18)"},
    {S(PARCELS), "collision_restitution", NUM, "-", IN_PARCELS(collision_restitution), .def = {0.9},
     GT(0), LE(1),
     .doc = "model B: e from which eta_c is built when collision_damping is not given"},
    {S(PARCELS), "collision_range", NUM, "-", IN_PARCELS(collision_range), .def = {0.075}, GE(0),
     LE(1),
     .doc = "model B: force range rho as a fraction of a parcel sphere's diameter: spheres push "
            "from R_ep + R_ej + rho apart, and a side from R_ep + rho"},

    // [solids]
    {S(SOLIDS), "diameter", NUM, "m", IN_SOLIDS(def.diameter), .def = {2.49e-3}, GT(0), LE(1),
     .doc = "particle diameter of the solids phase (the default: Goldschmidt's large glass beads, "
            "Sun 2007, table 5.1)"},
    {S(SOLIDS), "density", NUM, "kg/m^3", IN_SOLIDS(def.density), .def = {2526}, GT(0), LE(1e5),
     .doc = "material density of the solids"},
    {S(SOLIDS), "restitution", NUM, "-", IN_SOLIDS(def.restitution), .def = {0.97}, GT(0), LT(1),
     .doc = "normal restitution of the kinetic theory (made effective by friction, below; "
            "elastic spheres have no balance of granular energy)"},
    {S(SOLIDS), "friction", NUM, "-", IN_SOLIDS(friction), .def = {0}, GE(0), LE(10),
     .doc = "particle friction: above 0 the restitution becomes Jenkins & Zhang's (2002) "
            "effective one, e - a1/2 + a2 b1 / (2 b2) (particle rotation, Sun 2007, ch. 5)"},
    {S(SOLIDS), "tangential_restitution", NUM, "-", IN_SOLIDS(tangential_restitution),
     .def = {0.33}, GE(0), LE(1), .doc = "beta0 of Jenkins & Zhang's effective restitution"},
    {S(SOLIDS), "drag", .type = BDL_KEY_ENUM, "-", IN_SOLIDS(def.drag),
     .def = {BDL_DRAG_SYAMLAL_OBRIEN}, .enum_names = bdl_drag_law_names,
     .default_text = "syamlal_obrien",
     .doc = "drag law between gas and solids (as [coupling] drag)"},
    {S(SOLIDS), "syamlal_c", NUM, "-", IN_SOLIDS(def.drag_params.syamlal_c), .def = {0.8}, GT(0),
     .doc = "Syamlal-O'Brien C (Sun 2007, table 4.3: 0.8, 0.7, 0.64)"},
    {S(SOLIDS), "syamlal_d", NUM, "-", IN_SOLIDS(def.drag_params.syamlal_d), .def = {2.65}, GT(0),
     .doc = "Syamlal-O'Brien D (2.65, 3.44, 4.03 with the C above)"},
    {S(SOLIDS), "plastic_fraction", NUM, "-", IN_SOLIDS(def.eps_star), .def = {0.58}, GT(0), LT(1),
     .doc = "solids fraction where Schaeffer's plastic regime starts (Sun 2007, eq. 7.7)"},
    {S(SOLIDS), "schaeffer_a", NUM, "Pa", IN_SOLIDS(def.schaeffer_a), .def = {1e24}, GT(0),
     LE(1e30),
     .doc = "A of the plastic pressure eps A (eps - plastic_fraction)^n (10^25 dyn/cm^2)"},
    {S(SOLIDS), "schaeffer_n", NUM, "-", IN_SOLIDS(def.schaeffer_n), .def = {10}, GE(1), LE(20),
     .doc = "n of the plastic pressure"},
    {S(SOLIDS), "friction_angle", NUM, "deg", IN_SOLIDS(def.friction_angle), .def = {30}, GE(0),
     LT(90), .doc = "angle of internal friction of the plastic regime's viscosity"},
    {S(SOLIDS), "viscosity_max", NUM, "Pa s", IN_SOLIDS(def.mu_max), .def = {100}, GT(0), LE(1e6),
     .doc = "cap of the plastic regime's viscosity (MFIX's 1000 poise)"},
    {S(SOLIDS), "bed_height", NUM, "m", IN_SOLIDS(bed_height), .def = {0}, GE(0),
     .default_text = "none: required with [solids] (unless every [phase] has its bed_top), > 0 "
                     "and within the domain's height",
     .doc = "the cells whose centres lie below this height above the domain's floor (along z) "
            "start filled"},
    {S(SOLIDS), "fraction", NUM, "-", IN_SOLIDS(fraction), .def = {0.583}, GT(0), LE(0.6),
     .doc = "their solids fraction (the default: Sun's eps_mf 0.417, table 5.2)"},
    {S(SOLIDS), "granular_energy", .type = BDL_KEY_ENUM, "-", IN_SOLIDS(def.granular_energy),
     .def = {BDL_GRANULAR_ENERGY_LOCAL}, .enum_names = bdl_granular_energy_names,
     .doc = "local: production and dissipation balanced in each cell in time (no transport); "
            "transport: the granular energy's transport equation, with convection, Lun et al.'s "
            "conduction (Ma & Ahmadi's gas correction) and, with a specularity, Johnson & "
            "Jackson's energy flux through the walls (Sun 2007, eqs. 5.5, 5.9)"},
    {S(SOLIDS), "kinetic_pressure", .type = BDL_KEY_ENUM, "-", IN_SOLIDS(def.kinetic_pressure),
     .def = {BDL_KINETIC_PRESSURE_EXPLICIT}, .enum_names = bdl_kinetic_pressure_names,
     .doc = "the viscous regime's pressure k1 eps^2 theta: explicit in the momentum step (its "
            "waves limit the step, dt c / h); implicit: its change over the step solved with the "
            "plastic regime's (backward Euler at the step's temperature), so that only the "
            "solids' outflow limits the step (one phase only)"},
    {S(SOLIDS), "wave_weight", NUM, "-", IN_SOLIDS(def.wave_weight), .def = {0}, GE(0), LE(1),
     .doc = "with kinetic_pressure = implicit: the weight w of the kinetic pressure's wave speed "
            "c beside the outflow in the solids' Courant number dt (v_out + w c) / h, which the "
            "adaptive step (courant) keeps and a fixed step is checked against (0: left out; 1: "
            "as with the explicit pressure). The waves are implicit in the fraction, but their "
            "temperature is the step's start's: a small weight keeps long steps from heating "
            "dense cells beside bubbles (retakes)"},
    {S(SOLIDS), "wall_restitution", NUM, "-", IN_SOLIDS(def.wall_restitution), .def = {0.6}, GE(0),
     LE(1),
     .doc = "Johnson & Jackson's particle-wall restitution e_w of the walls' energy flux "
            "(granular_energy = transport with a specularity; 0.6 as Guo et al.'s 2021 MFiX "
            "cases)"},
    {S(SOLIDS), "courant", NUM, "-", IN_SOLIDS(courant), .def = {0}, GE(0), LE(1),
     .default_text = "0 (the step is [run] dt)",
     .doc = "above 0 the step adapts: each step is the largest, at most [run] dt, that keeps "
            "the Courant number at most this: the solids' (their outflow and, with the kinetic "
            "pressure explicit, the speed of their pressure waves, dt (v + c) / h) and, with "
            "explicit convection, the gas's; it lands "
            "on the rows of diagnostics.csv"},
    {S(SOLIDS), "specularity", NUM, "-", IN_SOLIDS(def.specularity), .def = {0}, GE(0), LE(1),
     .doc = "Johnson & Jackson's specularity coefficient phi' of the walls: their shear stress on "
            "the solids pi sqrt(3) phi' rho eps g0 sqrt(theta) v / (6 plastic_fraction) (Sun "
            "2007, ch. 5; the thesis gives no value); 0 = free slip"},
    {S(SOLIDS), "hindrance", NUM, "s/m^2", IN_SOLIDS(def.hindrance), .def = {0}, GE(0), LE(1e9),
     .doc = "with [phase NAME] sections: Gera et al.'s (2004) C1, the drag between two phases "
            "gains C1 times the plastic pressure (the hindrance of packed particles that cannot "
            "pass each other); 0 = Syamlal's drag alone, as Sun's runs"},
    {S(SOLIDS), "phase_friction", NUM, "-", IN_SOLIDS(def.phase_friction), .def = {0}, GE(0),
     LE(10),
     .doc = "with [phase NAME] sections: C_f, the friction coefficient of Syamlal's drag between "
            "two phases (Sun 2007, eq. 3.18; the thesis gives no value)"},

    // [phase NAME]
    {S(PHASE), "diameter", NUM, "m", IN_PHASE(diameter), .def = {2.49e-3}, GT(0), LE(1),
     .doc = "particle diameter of the phase"},
    {S(PHASE), "density", NUM, "kg/m^3", IN_PHASE(density), .def = {2526}, GT(0), LE(1e5),
     .doc = "material density of the phase"},
    {S(PHASE), "restitution", NUM, "-", IN_PHASE(restitution), .def = {0.97}, GT(0), LT(1),
     .doc = "normal restitution of the phase's kinetic theory (made effective by friction)"},
    {S(PHASE), "friction", NUM, "-", IN_PHASE(friction), .def = {0}, GE(0), LE(10),
     .doc = "particle friction: above 0 Jenkins & Zhang's effective restitution (as [solids] "
            "friction)"},
    {S(PHASE), "tangential_restitution", NUM, "-", IN_PHASE(tangential_restitution), .def = {0.33},
     GE(0), LE(1), .doc = "beta0 of Jenkins & Zhang's effective restitution"},
    {S(PHASE), "fraction", NUM, "-", IN_PHASE(fraction), .def = {0}, GT(0), LE(0.6),
     .required = BDL_REQUIRED_ALWAYS,
     .doc = "the phase's solids fraction in its cells at the start (where phases overlap, their "
            "sum at most 0.6)"},
    {S(PHASE), "bed_bottom", NUM, "m", IN_PHASE(bed_bottom), .def = {0}, GE(0),
     .doc = "the cells whose centres lie at or above this height (and below bed_top) start "
            "filled with the phase"},
    {S(PHASE), "bed_top", NUM, "m", IN_PHASE(bed_top), .def = {0}, GE(0),
     .default_text = "[solids] bed_height",
     .doc = "the cells whose centres lie below this height (at or above bed_bottom) start "
            "filled with the phase; above bed_bottom and within the domain's height"},

    // [guards]
    {S(GUARDS), "max_overlap", NUM, "-", IN_SCENE(guards.max_overlap), .def = {0.25}, GT(0), LE(1),
     .doc = "stop when an overlap exceeds this fraction of the smaller radius"},
    {S(GUARDS), "initial_overlap", NUM, "-", IN_SCENE(guards.initial_overlap), .def = {0.01}, GE(0),
     LE(1),
     .doc =
         "refuse initial particles overlapping by more than this fraction of the smaller radius"},
    {S(GUARDS), "dt_refuse", NUM, "-", IN_SCENE(guards.dt_refuse), .def = {0.2}, GT(0), LE(1),
     .doc = "refuse a dt above this fraction of the smallest contact time"},
    {S(GUARDS), "dt_warn", NUM, "-", IN_SCENE(guards.dt_warn), .def = {0.05}, GT(0), LE(1),
     .doc = "warn for a dt above this fraction of the contact time; at most dt_refuse"},
    {S(GUARDS), "energy_growth", NUM, "-", IN_SCENE(guards.energy_growth), .def = {0.05}, GT(0),
     .doc = "stop when the energy grows by this fraction more than the work supplied"},
    {S(GUARDS), "check_interval", .type = BDL_KEY_INT, "steps", IN_SCENE(guards.check_interval),
     .def = {100}, GE(1),
     .doc = "steps between the in-run checks (besides: the state is checked to be finite before "
            "every output, and all but the energy balance before every checkpoint)"},
    {S(GUARDS), "max_memory", NUM, "bytes", IN_SCENE(guards.max_memory), .def = {-1},
     .default_text = "80 % of the physical memory", GT(0),
     .doc = "refuse a scene whose estimated memory (particles, neighbour pairs, gas grid, image "
            "buffers, the fields' grid) is above this, before anything is allocated"},
    {S(GUARDS), "max_steps", NUM, "steps", IN_SCENE(guards.max_steps), .def = {1e10}, GE(1),
     .doc = "refuse a run of more time steps than this (end_time / dt), before anything is "
            "allocated"},
};

const int bdl_scene_key_count = (int)(sizeof bdl_scene_keys / sizeof bdl_scene_keys[0]);
_Static_assert(sizeof bdl_scene_keys / sizeof bdl_scene_keys[0] <= BDL_SCENE_KEY_CAPACITY,
               "raise BDL_SCENE_KEY_CAPACITY");

const bdl_scene_key *bdl_scene_key_find(bdl_section_kind kind, const char *name)
{
    for (int i = 0; i < bdl_scene_key_count; ++i)
        if (bdl_scene_keys[i].section == kind && strcmp(bdl_scene_keys[i].name, name) == 0)
            return &bdl_scene_keys[i];
    return NULL;
}

int bdl_scene_key_index(const bdl_scene_key *key) { return (int)(key - bdl_scene_keys); }

const char *bdl_scene_key_type_name(bdl_key_type type)
{
    static const char *const names[] = {"number",  "vector", "integer", "integer", "integer",
                                        "boolean", "choice", "axes",    "name",    "path"};
    return names[type];
}

// Appends to buf (always terminated, silently truncated).
#if defined(__GNUC__)
__attribute__((format(printf, 3, 4)))
#endif
static void
append(char *buf, size_t size, const char *format, ...)
{
    size_t used = strlen(buf);
    if (used + 1 >= size)
        return;
    va_list args;
    va_start(args, format);
    vsnprintf(buf + used, size - used, format, args);
    va_end(args);
}

static int is_integer_type(bdl_key_type type)
{
    return type == BDL_KEY_INT || type == BDL_KEY_LONG || type == BDL_KEY_U64;
}

/// A vector key's range: its components' bounds (each one) or its length's.
static void vector_range_text(const bdl_scene_key *key, char *buf, size_t size)
{
    if (key->normalise)
        append(buf, size, "3 numbers, not all 0");
    else if (key->lo_kind != BDL_BOUND_NONE && key->hi_kind != BDL_BOUND_NONE)
        append(buf, size, "3 numbers, each in %s%g, %g%s",
               key->lo_kind == BDL_BOUND_OPEN ? "(" : "[", key->lo, key->hi,
               key->hi_kind == BDL_BOUND_OPEN ? ")" : "]");
    else if (key->lo_kind != BDL_BOUND_NONE)
        append(buf, size, "3 numbers, each %s %g",
               key->lo_kind == BDL_BOUND_OPEN ? ">" : ">=", key->lo);
    else if (key->max_length > 0.0)
        append(buf, size, "3 numbers, length <= %g", key->max_length);
    else
        append(buf, size, "3 numbers separated by spaces");
}

void bdl_scene_key_range_text(const bdl_scene_key *key, char *buf, size_t size)
{
    buf[0] = '\0';
    switch (key->type) {
    case BDL_KEY_VECTOR:
        vector_range_text(key, buf, size);
        return;
    case BDL_KEY_BOOL:
        append(buf, size, "true, false, yes, no, on, off, 1, 0");
        return;
    case BDL_KEY_ENUM:
        for (int i = 0; key->enum_names[i]; ++i)
            append(buf, size, "%s%s", i ? ", " : "", key->enum_names[i]);
        return;
    case BDL_KEY_AXES:
        append(buf, size, "none, or any of x y z");
        return;
    case BDL_KEY_NAME:
        append(buf, size, "name of a [species NAME] section");
        return;
    case BDL_KEY_PATH:
        append(buf, size, "readable regular file, relative to the scene folder");
        return;
    default:
        break;
    }
    const char *kind = is_integer_type(key->type) ? "integer " : "";
    if (key->lo_kind != BDL_BOUND_NONE && key->hi_kind != BDL_BOUND_NONE)
        append(buf, size, "%s%s%g, %g%s", *kind ? "integer in " : "",
               key->lo_kind == BDL_BOUND_OPEN ? "(" : "[", key->lo, key->hi,
               key->hi_kind == BDL_BOUND_OPEN ? ")" : "]");
    else if (key->lo_kind != BDL_BOUND_NONE)
        append(buf, size, "%s%s %g", kind, key->lo_kind == BDL_BOUND_OPEN ? ">" : ">=", key->lo);
    else if (key->hi_kind != BDL_BOUND_NONE)
        append(buf, size, "%s%s %g", kind, key->hi_kind == BDL_BOUND_OPEN ? "<" : "<=", key->hi);
    else
        append(buf, size, "any %s", *kind ? "integer" : "number");
}

void bdl_scene_key_default_text(const bdl_scene_key *key, char *buf, size_t size)
{
    buf[0] = '\0';
    if (key->default_text) {
        append(buf, size, "%s", key->default_text);
        return;
    }
    if (key->required == BDL_REQUIRED_ALWAYS) {
        append(buf, size, "required");
        return;
    }
    switch (key->type) {
    case BDL_KEY_VECTOR:
        append(buf, size, "%g %g %g", key->def[0], key->def[1], key->def[2]);
        break;
    case BDL_KEY_BOOL:
        append(buf, size, "%s", key->def[0] != 0 ? "true" : "false");
        break;
    case BDL_KEY_ENUM:
        append(buf, size, "%s", key->enum_names[(int)key->def[0]]);
        break;
    case BDL_KEY_AXES:
        append(buf, size, "none");
        break;
    case BDL_KEY_NAME:
    case BDL_KEY_PATH:
        append(buf, size, "none");
        break;
    default:
        append(buf, size, "%g", key->def[0]);
        break;
    }
}

void *bdl_scene_key_field(const bdl_scene_key *key, bdl_scene *scene, bdl_scene_section *section)
{
    char *base = (char *)scene;
    if (key->target == BDL_TARGET_RECORD)
        base = (char *)section;
    else if (key->section == BDL_SECTION_SPECIES)
        base = (char *)&scene->species[section->index];
    else if (key->section == BDL_SECTION_PAIR)
        base = (char *)&scene->pairs[section->index];
    else if (key->section == BDL_SECTION_WALL)
        base = (char *)&scene->walls[section->index];
    else if (key->section == BDL_SECTION_CREATE)
        base = (char *)&scene->creates[section->index];
    else if (key->section == BDL_SECTION_DIA)
        base = (char *)&scene->dias[section->index];
    else if (key->section == BDL_SECTION_SINK)
        base = (char *)&scene->sinks[section->index];
    else if (key->section == BDL_SECTION_PHASE)
        base = (char *)&scene->solids.phases[section->index];
    return base + key->offset;
}

void bdl_scene_key_value_text(const bdl_scene_key *key, bdl_scene *scene,
                              bdl_scene_section *section, char *buf, size_t size)
{
    const void *field = bdl_scene_key_field(key, scene, section);
    buf[0] = '\0';
    switch (key->type) {
    case BDL_KEY_NUMBER:
        append(buf, size, "%.10g", *(const double *)field);
        break;
    case BDL_KEY_VECTOR: {
        const bdl_vec3 *v = field;
        append(buf, size, "%.10g %.10g %.10g", v->x, v->y, v->z);
        break;
    }
    case BDL_KEY_INT:
    case BDL_KEY_BOOL:
        append(buf, size, "%d", *(const int *)field);
        break;
    case BDL_KEY_LONG:
        append(buf, size, "%ld", *(const long *)field);
        break;
    case BDL_KEY_U64:
        append(buf, size, "%llu", (unsigned long long)*(const uint64_t *)field);
        break;
    case BDL_KEY_ENUM:
        append(buf, size, "%s", key->enum_names[*(const int *)field]);
        break;
    case BDL_KEY_AXES: {
        const int *axes = field;
        for (int a = 0; a < 3; ++a)
            if (axes[a])
                append(buf, size, "%s%c", buf[0] ? " " : "", "xyz"[a]);
        if (!buf[0])
            append(buf, size, "none");
        break;
    }
    case BDL_KEY_NAME:
    case BDL_KEY_PATH:
        append(buf, size, "%s", (const char *)field);
        break;
    }
}

static void write_default(const bdl_scene_key *key, void *field)
{
    switch (key->type) {
    case BDL_KEY_NUMBER:
        *(double *)field = key->def[0];
        break;
    case BDL_KEY_VECTOR:
        *(bdl_vec3 *)field = bdl_v3(key->def[0], key->def[1], key->def[2]);
        break;
    case BDL_KEY_INT:
    case BDL_KEY_BOOL:
    case BDL_KEY_ENUM:
        *(int *)field = (int)key->def[0];
        break;
    case BDL_KEY_LONG:
        *(long *)field = (long)key->def[0];
        break;
    case BDL_KEY_U64:
        *(uint64_t *)field = (uint64_t)key->def[0];
        break;
    case BDL_KEY_AXES:
        memset(field, 0, 3 * sizeof(int));
        break;
    case BDL_KEY_NAME:
    case BDL_KEY_PATH:
        *(char *)field = '\0';
        break;
    }
}

void bdl_scene_apply_defaults(bdl_scene *scene, bdl_scene_section *section)
{
    for (int i = 0; i < bdl_scene_key_count; ++i)
        if (bdl_scene_keys[i].section == section->kind)
            write_default(&bdl_scene_keys[i],
                          bdl_scene_key_field(&bdl_scene_keys[i], scene, section));
}

void bdl_scene_defaults(bdl_scene *scene)
{
    memset(scene, 0, sizeof *scene);
    snprintf(scene->dir, sizeof scene->dir, ".");
    scene->solids.def = bdl_default_solids_def(); // what no key sets (the dilute limit, solver)
    // Only the singleton sections have their fields in bdl_scene itself.
    for (int i = 0; i < bdl_scene_key_count; ++i)
        if (bdl_section_infos[bdl_scene_keys[i].section].name_count == 0)
            write_default(&bdl_scene_keys[i], bdl_scene_key_field(&bdl_scene_keys[i], scene, NULL));
}

// Optimal-string-alignment distance (a transposition counts as one edit), ignoring case.
static int edit_distance(const char *a, const char *b)
{
    enum { MAX = 64 };
    size_t n = strlen(a), m = strlen(b);
    if (n >= MAX || m >= MAX)
        return MAX;
    int d[MAX][MAX];
    for (size_t i = 0; i <= n; ++i)
        d[i][0] = (int)i;
    for (size_t j = 0; j <= m; ++j)
        d[0][j] = (int)j;
    for (size_t i = 1; i <= n; ++i) {
        for (size_t j = 1; j <= m; ++j) {
            int same = tolower((unsigned char)a[i - 1]) == tolower((unsigned char)b[j - 1]);
            int best = d[i - 1][j - 1] + !same;
            if (d[i - 1][j] + 1 < best)
                best = d[i - 1][j] + 1;
            if (d[i][j - 1] + 1 < best)
                best = d[i][j - 1] + 1;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] &&
                d[i - 2][j - 2] + 1 < best)
                best = d[i - 2][j - 2] + 1;
            d[i][j] = best;
        }
    }
    return d[n][m];
}

void bdl_suggest_init(bdl_suggestion *s, const char *typed)
{
    s->typed = typed;
    s->best = NULL;
    s->best_score = 1 << 20;
}

void bdl_suggest_consider(bdl_suggestion *s, const char *candidate)
{
    size_t typed_len = strlen(s->typed), cand_len = strlen(candidate);
    if (typed_len == 0)
        return; // nothing typed: every short word would be "close"
    int distance = edit_distance(s->typed, candidate);
    // Short words are close to everything: allow one edit below four letters, two above.
    int limit = typed_len <= 3 ? 1 : 2;
    int score = distance <= limit ? distance : -1;
    // A prefix either way ("youngs" for "youngs_modulus") ranks after every small edit.
    size_t shorter = typed_len < cand_len ? typed_len : cand_len;
    if (score < 0 && shorter >= 3 && strncmp(s->typed, candidate, shorter) == 0)
        score = limit + 1;
    if (score >= 0 && score < s->best_score) {
        s->best = candidate;
        s->best_score = score;
    }
}

void bdl_suggest_text(const bdl_suggestion *s, char *buf, size_t size)
{
    if (s->best)
        snprintf(buf, size, "; did you mean '%s'?", s->best);
    else if (size > 0)
        buf[0] = '\0';
}
