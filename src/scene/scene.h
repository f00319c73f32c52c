// bedlam — the validated scene description.
//
// A scene file (INI, parsed with libinih) becomes a bdl_scene: plain data in SI units, every
// value checked against its allowed range, no physics. The solver modules own the definitions
// they are built from (species, materials, walls and creators in dem/, the gas's sides and
// convection in cfd/, the drag laws in couple/); a scene is a set of them plus what the run,
// the outputs and the cameras need, and the world (world/) builds the solvers from it.
// The key-by-key documentation (unit, default, range) is docs/scene-format.md; the table of keys
// in scene_keys.c is the single source the parser, the "did you mean" hints and the docs test
// read from.
#ifndef BDL_SCENE_H
#define BDL_SCENE_H

#include <stdint.h>

#include "cfd/gas.h"
#include "core/error.h"
#include "core/names.h"
#include "core/vec3.h"
#include "couple/drag.h"
#include "dem/create.h"
#include "dem/material.h"
#include "dem/species.h"
#include "dem/walls.h"
#include "parcels/parcels.h"
#include "solids/phase.h"

#define BDL_MAX_PAIRS   64
#define BDL_MAX_CREATES 16
#define BDL_MAX_DIA     4
#define BDL_MAX_SINKS   8

/// A region that removes the particles whose centres enter it ([sink NAME]), counting them with
/// those that leave the domain.
typedef struct bdl_sink_def {
    char name[BDL_NAME_LEN];
    bdl_vec3 min, max; ///< the box [m]
    double start_time; ///< simulated time it starts removing [s]
} bdl_sink_def;

/// Largest length of [run] gravity [m/s^2]: about 1e5 g, above the strongest fields granular
/// beds are studied in (geotechnical and rotating-bed centrifuges reach a few hundred g); a
/// typo in an exponent is refused rather than run with forces near overflow.
#define BDL_MAX_GRAVITY 1e6
/// Largest |coordinate| of the domain's corners [m]: a thousand kilometres, with a resolution of
/// doubles there (1e-10 m) still far below any particle's size.
#define BDL_MAX_COORDINATE 1e6
/// Most outputs of one kind a run may write (rows, files or images up to end_time): the output
/// times are stepped through one interval at a time, so an interval of 1e-300 s would never
/// advance.
#define BDL_MAX_OUTPUTS 1e9
/// Most cells of the grid of the time-averaged solids fields ([output] fields_cell; bedlam analyze
/// fields --cell): 5e7 cells hold 1.6 GB of sums and write a .vti file of several GB.
#define BDL_MAX_FIELD_CELLS 5e7

typedef struct bdl_output_def {
    double diagnostics_interval;   ///< [s] between rows of diagnostics.csv
    double vtk_interval;           ///< [s] between particle VTK files; 0 = none
    double checkpoint_interval;    ///< [s] between checkpoints; 0 = only at the end / on failure
    double progress_interval;      ///< wall seconds between progress lines
    double frame_interval;         ///< [s] between PNG frames; 0 = none
    int frame_width, frame_height; ///< [px]
    int frame_samples;             ///< multisample anti-aliasing samples (0 = none)
    double contacts_interval;      ///< [s] between contact files in contacts/; 0 = none
    bdl_vec3 mixing_cells;         ///< Lacey index grid in species.csv; 0 0 0 = the default
    double orientation_interval;   ///< [s] between rows of orientation.csv (rods); 0 = none
    double fields_interval;        ///< [s] between samples for fields.vti; 0 = none
    double fields_start;           ///< [s] the first sample counted in fields.vti
    double fields_cell;            ///< [m] cell of fields.vti; < 0: three mean diameters
    double rheology_interval;      ///< [s] between rows of rheology.csv; 0 = none
    double rheology_margin;        ///< [m] left out of the bulk region at each z face
    int rheology_bins;             ///< slabs of the mean velocity across the bulk region
} bdl_output_def;

/// Preset camera orientations ([camera] view).
#define BDL_VIEW_PRESETS(X)                                                                        \
    X(VIEW_ISO, "iso", "from the front-right, above")                                              \
    X(VIEW_FRONT, "front", "along +y: the x-z plane, as a camera sees a pseudo-2D bed's front")    \
    X(VIEW_SIDE, "side", "along -x: the y-z plane")                                                \
    X(VIEW_TOP, "top", "along -z: the x-y plane")
BDL_CHOICES(bdl_view_preset, BDL_VIEW_PRESETS);

#define BDL_PROJECTIONS(X)                                                                         \
    X(PROJ_PERSPECTIVE, "perspective", "perspective")                                              \
    X(PROJ_ORTHOGRAPHIC, "orthographic", "orthographic")
BDL_CHOICES(bdl_projection, BDL_PROJECTIONS);

/// What the particle colour shows ([camera] color): X(NAME, "word", "label", "unit"). The rods'
/// orientation modes come last, so that a viewer of a scene without rods cycles through the
/// modes before them only.
#define BDL_COLOR_MODES(X)                                                                         \
    X(COLOR_SPECIES, "species", "species", "")                                                     \
    X(COLOR_COORDINATION, "coordination", "coordination number", "contacts")                       \
    X(COLOR_SPEED, "speed", "speed", "m/s")                                                        \
    X(COLOR_VX, "vx", "velocity x", "m/s")                                                         \
    X(COLOR_VY, "vy", "velocity y", "m/s")                                                         \
    X(COLOR_VZ, "vz", "velocity z", "m/s")                                                         \
    X(COLOR_VOIDAGE, "voidage", "voidage", "")                                                     \
    X(COLOR_SOLIDS, "solids", "solids fraction", "")                                               \
    X(COLOR_TILT, "tilt", "tilt from vertical", "deg")                                             \
    X(COLOR_AZIMUTH, "azimuth", "azimuth mod 180", "deg")
#define BDL_X_COLOR_ITEM(name, word, label, unit) BDL_##name,
typedef enum bdl_color_mode {
    BDL_COLOR_MODES(BDL_X_COLOR_ITEM) BDL_COLOR_MODE_COUNT
} bdl_color_mode;
#undef BDL_X_COLOR_ITEM
extern const char *const bdl_color_mode_names[];  ///< scene words, NULL-terminated
extern const char *const bdl_color_mode_labels[]; ///< what a colour bar says ("speed")
extern const char *const bdl_color_mode_units[];  ///< its unit ("m/s"; "" when none)

/// A gas field drawn as a translucent slice behind or through the particles ([camera]
/// gas_field): X(NAME, "word", "label", "unit").
#define BDL_GAS_FIELDS(X)                                                                          \
    X(GAS_FIELD_NONE, "none", "", "")                                                              \
    X(GAS_FIELD_VOIDAGE, "voidage", "voidage", "")                                                 \
    X(GAS_FIELD_PRESSURE, "pressure", "pressure", "Pa")                                            \
    X(GAS_FIELD_SPEED, "speed", "gas speed", "m/s")
#define BDL_X_FIELD_ITEM(name, word, label, unit) BDL_##name,
typedef enum bdl_gas_field { BDL_GAS_FIELDS(BDL_X_FIELD_ITEM) } bdl_gas_field;
#undef BDL_X_FIELD_ITEM
extern const char *const bdl_gas_field_names[];  ///< scene words, NULL-terminated
extern const char *const bdl_gas_field_labels[]; ///< what the overlay says ("gas speed")
extern const char *const bdl_gas_field_units[];  ///< gauge pressure in Pa, |u| of the gas in m/s

/// [camera]: how frames and the viewer look at the scene.
typedef struct bdl_camera_def {
    bdl_view_preset view;
    bdl_projection projection;
    bdl_color_mode color;
    double color_min, color_max; ///< fixed colour range (unit of the field); else automatic
    int has_color_min, has_color_max;
    bdl_vec3 target; ///< point looked at [m]; default the domain centre
    int has_target;
    double distance; ///< eye to target [m]; 0 = fit the domain
    double yaw;      ///< [deg] about +z, 0 = looking along +y; default from the preset
    double pitch;    ///< [deg] above the horizontal; default from the preset
    int has_yaw, has_pitch;
    double fov;          ///< vertical field of view of the perspective projection [deg]
    int clip;            ///< cut the bed open: hide particles whose centre is on the normal's side
    bdl_vec3 clip_point; ///< a point on the clipping plane [m]; default the target
    int has_clip_point;
    bdl_vec3 clip_normal;      ///< unit normal; particles on this side are hidden
    int lighting;              ///< shaded spheres (else flat colour)
    int overlay;               ///< text and colour bar
    int outlines;              ///< domain and wall outlines
    bdl_vec3 background;       ///< sRGB 0..1
    bdl_gas_field gas_field;   ///< a gas field on a slice of the grid
    int gas_slice_axis;        ///< normal of the slice (0 x, 1 y, 2 z)
    double gas_slice_position; ///< where along that axis, 0..1 of the domain
    double gas_opacity;        ///< of the slice, 0..1
} bdl_camera_def;

/// How a synthetic camera projects ([camera NAME] projection).
#define BDL_DIA_PROJECTIONS(X)                                                                     \
    X(DIA_ORTHOGRAPHIC, "orthographic", "orthographic")                                            \
    X(DIA_PERSPECTIVE, "perspective", "perspective")
BDL_CHOICES(bdl_dia_projection, BDL_DIA_PROJECTIONS);

/// Where a synthetic camera's light comes from ([camera NAME] lighting): lights on the camera's
/// side (bright spheres, dark background) or a light panel behind the bed (dark silhouettes on a
/// bright background).
#define BDL_DIA_LIGHTINGS(X)                                                                       \
    X(DIA_FRONT_LIT, "front", "front-lit")                                                         \
    X(DIA_BACK_LIT, "back", "back-lit")
BDL_CHOICES(bdl_dia_lighting, BDL_DIA_LIGHTINGS);
extern const char *const bdl_dia_lighting_labels[]; ///< "front-lit", "back-lit"

/// A stepwise sweep of the inlet velocity ([gas] sweep).
#define BDL_SWEEPS(X)                                                                              \
    X(SWEEP_NONE, "none", "none")                                                                  \
    X(SWEEP_UP, "up", "from inlet_velocity up to sweep_to")                                        \
    X(SWEEP_DOWN, "down", "from inlet_velocity down to sweep_to")                                  \
    X(SWEEP_UP_DOWN, "up_down", "to sweep_to and back to inlet_velocity")
BDL_CHOICES(bdl_sweep, BDL_SWEEPS);

/// What becomes of a particle whose centre crosses a face of the domain ([domain] outside).
#define BDL_OUTSIDES(X)                                                                            \
    X(OUTSIDE_REMOVE, "remove", "removed and counted (particles_out, mass_out in diagnostics)")    \
    X(OUTSIDE_STOP, "stop",                                                                        \
      "the run stops with the particle named (a container that should "                            \
      "hold every particle)")
BDL_CHOICES(bdl_outside, BDL_OUTSIDES);

/// A synthetic camera ([camera NAME], kind = dia): images of the particles as a DIA rig sees them,
/// with the ground truth beside every image (src/dia).
typedef struct bdl_dia_scene_def {
    char name[BDL_NAME_LEN];
    int line;
    int kind; ///< 0: dia
    bdl_dia_projection projection;
    bdl_vec3 position; ///< perspective: the pinhole; orthographic: centre of the view [m]
    bdl_vec3 target;   ///< point on the optical axis [m]
    bdl_vec3 up;       ///< world direction shown up
    int width, height; ///< [px]
    double pixel_size; ///< orthographic: m per pixel; perspective: sensor pixel pitch [m]
    double focal_length;
    int samples; ///< rays per pixel along each axis
    bdl_dia_lighting lighting;
    bdl_vec3 light_position;
    int has_light_position; ///< else a light at the camera
    int lights;             ///< 1: one light; 2-4: a ring around light_position
    double light_spread;    ///< radius of the ring [m]
    double light_intensity, ambient;
    double dark, bright; ///< grey levels of the darkest and brightest things imaged
    double fade;         ///< e-folding depth of the light behind the front wall [m]; 0 none
    double blur, noise, gamma;
    int bits;
    double start, interval, pair_dt; ///< first image, images (or pairs) apart, pair separation [s]
    double stop;                     ///< no image after this time [s]; 0 = to the end
    int cells_across, cells_down;    ///< ground-truth grid of image cells
    uint64_t seed;
} bdl_dia_scene_def;

typedef struct bdl_guard_def {
    double max_overlap;     ///< stop when any overlap exceeds this fraction of the smaller radius
    double initial_overlap; ///< refuse initial overlaps above this fraction of the smaller radius
    double dt_refuse;       ///< refuse dt above this fraction of the smallest contact time
    double dt_warn;         ///< warn for dt above this fraction
    double energy_growth;   ///< stop when energy grows by this fraction over work supplied
    int check_interval;     ///< steps between in-run checks
    double max_memory;      ///< refuse an estimate above this [bytes]; < 0: 80 % of the machine's
    double max_steps;       ///< refuse more steps than this (end_time / dt)
} bdl_guard_def;

/// [gas]: the gas phase. Absent: no grid, no gas, no cost.
typedef struct bdl_gas_scene {
    int enabled;      ///< the scene has a [gas] section
    double density;   ///< [kg/m^3]
    double viscosity; ///< dynamic [Pa s]
    bdl_vec3 cells;   ///< cells per axis (whole numbers)
    bdl_convection convection;
    bdl_convection_step convection_step;
    double tolerance;                    ///< relative residual of the pressure solver
    bdl_pressure_solver pressure_solver; ///< bedlam's MG-PCG, or hypre's (MPI builds)
    bdl_gas_side_type side[6];           ///< xmin xmax ymin ymax zmin zmax (periodic axes: ignored)
    double inlet_velocity;         ///< superficial velocity into the domain through inlets [m/s]
    double outlet_pressure;        ///< [Pa]
    double distributor_resistance; ///< inlets as porous plates [Pa s/m]; 0: uniform inflow
    double jet_velocity;           ///< superficial velocity through the jet rectangle [m/s]
    bdl_vec3 jet_min, jet_max;     ///< jet rectangle on the inlet sides [m]
    int has_jet_min, has_jet_max;
    double dt;                    ///< gas time step [s]; 0: automatic
    double probe_low, probe_high; ///< heights of the two pressure probes above the floor [m]
    int has_probe_low, has_probe_high;
    double bubble_voidage; ///< diagnostics' bubbles: cells above this voidage (analysis/bubbles.h)
    bdl_sweep sweep;       ///< a pressure-drop sweep of the inlet velocity
    double sweep_to;       ///< the far end of the sweep [m/s]
    double sweep_step;     ///< velocity change per stage [m/s]
    double sweep_dwell;    ///< time per stage [s]
    double sweep_start;    ///< time the sweep starts [s]
} bdl_gas_scene;

/// [coupling]: how particles and gas exchange momentum.
typedef struct bdl_coupling_scene {
    bdl_drag_law drag;   ///< drag law
    double kernel_width; ///< half-width of the deposition kernel [m]; 0: 1.5 cells
    double max_solids;   ///< cap on the deposited solids fraction
    double syamlal_c, syamlal_d;
    int drag_velocity; ///< 0 each particle's own velocity, 1 the solids' mean (Sun's "averaged")
} bdl_coupling_scene;

/// How frames and the viewer draw a parcel ([parcels] display).
#define BDL_PARCEL_DISPLAYS(X)                                                                     \
    X(PARCEL_DISPLAY_PARCEL, "parcel", "the sphere of the parcel's solids volume")                 \
    X(PARCEL_DISPLAY_REAL, "real", "a sphere of one real particle's radius")
BDL_CHOICES(bdl_parcel_display, BDL_PARCEL_DISPLAYS);

/// [parcels]: how parcels (species with parcel_particles or parcel_volume) move; the scene has
/// parcels when a species is made of them.
typedef struct bdl_parcels_scene {
    int enabled;                ///< a species is made of parcels
    bdl_parcels_def def;        ///< model and its parameters
    bdl_parcel_display display; ///< how the pictures draw them
} bdl_parcels_scene;

/// [solids]: a solids phase on the gas grid (the two-fluid model, docs/theory-tfm.md); the scene
/// has one when the section is given, and then no particles.
/// [phase NAME]: one phase of a [solids] mixture.
typedef struct bdl_phase_scene {
    char name[BDL_NAME_LEN];
    double diameter, density, restitution; ///< [m], [kg/m^3], -
    double friction;                       ///< particle friction for Jenkins & Zhang's e_eff
    double tangential_restitution;         ///< beta0 of Jenkins & Zhang
    double fraction;                       ///< its solids fraction in the bed at the start
    double bed_bottom, bed_top; ///< the cells it fills [m] (bed_top 0: [solids] bed_height)
} bdl_phase_scene;

typedef struct bdl_solids_scene {
    int enabled;
    bdl_solids_def def;
    double friction;               ///< particle friction for Jenkins & Zhang's e_eff (0: none)
    double tangential_restitution; ///< beta0 of Jenkins & Zhang
    double bed_height;             ///< the cells below this height start filled [m]
    double fraction;               ///< with this solids fraction
    double courant;  ///< > 0: each step min([run] dt, this Courant number's step); 0: [run] dt
    int phase_count; ///< [phase NAME] sections: 0 (one phase, the above) or 2-4
    bdl_phase_scene phases[BDL_SOLIDS_PHASES];
} bdl_solids_scene;

typedef struct bdl_scene {
    char path[BDL_PATH_LEN]; ///< file the scene was read from ("" for a string)
    char dir[BDL_PATH_LEN];  ///< folder of the scene file (for relative paths)

    // [run]
    double dt;          ///< time step [s]; <= 0 -> dt_fraction * smallest contact time
    double dt_fraction; ///< used when dt is not given
    double end_time;    ///< [s]
    bdl_vec3 gravity;   ///< [m/s^2]
    uint64_t seed;      ///< random seed
    int threads;        ///< 0 = all cores

    // [domain]
    bdl_vec3 domain_min, domain_max; ///< [m]
    int periodic[3];                 ///< periodic flags per axis
    bdl_outside outside;             ///< a particle crossing a non-periodic face
    double shear_rate;               ///< Lees–Edwards shear rate du_x/dz [1/s]; 0 = none
    bdl_vec3 decomposition;          ///< [parallel]: MPI ranks per axis; 0 0 0 automatic

    // [contact]
    bdl_normal_law law;
    bdl_damping_mode damping;
    bdl_rolling_model rolling;
    double skin; ///< Verlet skin as a fraction of the largest diameter

    int species_count;
    bdl_species_def species[BDL_MAX_SPECIES];
    int pair_count;
    bdl_pair_def pairs[BDL_MAX_PAIRS];
    int wall_count;
    bdl_wall_def walls[BDL_MAX_WALLS];
    int create_count;
    bdl_create_def creates[BDL_MAX_CREATES];
    int dia_count;
    bdl_dia_scene_def dias[BDL_MAX_DIA];
    int sink_count;
    bdl_sink_def sinks[BDL_MAX_SINKS];

    /// Lines of the section headers in the scene file, for messages (0: not from the file).
    struct {
        int species[BDL_MAX_SPECIES], pairs[BDL_MAX_PAIRS], walls[BDL_MAX_WALLS],
            creates[BDL_MAX_CREATES];
    } line;

    bdl_output_def output;
    bdl_guard_def guards;
    bdl_camera_def camera;
    bdl_gas_scene gas;
    bdl_coupling_scene coupling;
    bdl_parcels_scene parcels;
    bdl_solids_scene solids;
} bdl_scene;

/// A problem found while reading or validating a scene. Messages look like
/// `scenes/x.ini:12: [species glass] density = -3: must be > 0 (kg/m^3)`.
typedef struct bdl_scene_error {
    char message[1024];
} bdl_scene_error;

/// Scene with every default filled in and no species, walls or creators.
void bdl_scene_defaults(bdl_scene *scene);

/// Reads and validates a scene file. `overrides` are `section.key=value` strings (from --set),
/// applied after the file as if they were written at its end; a section with a name is written
/// `species.glass.density=2500`. On failure returns BDL_ERR_SCENE and fills `err`.
bdl_result bdl_scene_load(const char *path, const char *const *overrides, int override_count,
                          bdl_scene *scene, bdl_scene_error *err);

/// Changes the end time of a loaded scene (bedlam run --until), checked as [run] end_time is:
/// its range, and that no output interval then asks for more than BDL_MAX_OUTPUTS outputs. On
/// failure returns BDL_ERR_SCENE with a message starting "--until T:" and leaves the scene as it
/// was.
bdl_result bdl_scene_set_end_time(bdl_scene *scene, double end_time, bdl_scene_error *err);

/// Same from a string (tests); `name` stands for the file name in messages.
bdl_result bdl_scene_load_string(const char *text, const char *name, const char *const *overrides,
                                 int override_count, bdl_scene *scene, bdl_scene_error *err);

#endif
