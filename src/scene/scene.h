// bedlam — the validated scene description.
//
// A scene file (INI, parsed with libinih) becomes a bdl_scene: plain data in SI units, every
// value checked against its allowed range, no physics. The solver modules are built from it.
// The key-by-key documentation (unit, default, range) is docs/scene-format.md; the table of keys
// in scene_keys.c is the single source the parser, the "did you mean" hints and the docs test
// read from.
#ifndef BDL_SCENE_H
#define BDL_SCENE_H

#include <stdint.h>

#include "core/error.h"
#include "core/vec3.h"

#define BDL_MAX_SPECIES 16
#define BDL_MAX_PAIRS   64
#define BDL_MAX_WALLS   16
#define BDL_MAX_CREATES 16
#define BDL_MAX_DIA     4
#define BDL_NAME_LEN    32
#define BDL_PATH_LEN    512

/// Normal contact law, chosen per scene ([contact] law).
typedef enum bdl_normal_law {
    BDL_LAW_LINEAR = 0, ///< linear spring-dashpot: F = k_n delta - gamma v_n
    BDL_LAW_HERTZ = 1,  ///< Hertz-Mindlin with delta^(1/4)-scaled (restitution-based) damping
} bdl_normal_law;

/// How the damping coefficient is obtained from the restitution ([contact] damping).
typedef enum bdl_damping_mode {
    BDL_DAMPING_EXACT = 0,       ///< solved numerically once per pair so the realised e matches
    BDL_DAMPING_CLOSED_FORM = 1, ///< the closed form of LIGGGHTS/EDEM (approximate at low e)
} bdl_damping_mode;

/// Rolling resistance model ([contact] rolling).
typedef enum bdl_rolling_model {
    BDL_ROLLING_NONE = 0,
    BDL_ROLLING_CONSTANT =
        1, ///< constant directional torque mu_r R* |F_n| against relative rolling
} bdl_rolling_model;

/// Diameter distribution of a species.
typedef enum bdl_size_dist {
    BDL_SIZE_SINGLE = 0,  ///< all particles have `diameter`
    BDL_SIZE_UNIFORM = 1, ///< uniform in [diameter_min, diameter_max]
    BDL_SIZE_NORMAL =
        2, ///< normal(diameter, diameter_std) truncated to [diameter_min, diameter_max]
} bdl_size_dist;

/// Material and contact parameters shared by species, pair overrides and walls.
/// A value < 0 means "not given" where a default is derived (documented per key).
typedef struct bdl_material {
    double youngs_modulus;           ///< E [Pa] (Hertz law); < 0 if not given
    double poisson_ratio;            ///< nu [-]
    double stiffness;                ///< k_n [N/m] (linear law); < 0 if not given
    double tangential_stiffness;     ///< k_t [N/m] (linear law); < 0 -> 2/7 k_n
    double restitution;              ///< normal coefficient of restitution e in (0, 1]
    double tangential_damping_ratio; ///< gamma_t / gamma_n [-] (default 0: no tangential dashpot)
    double friction;                 ///< sliding friction coefficient mu [-]
    double rolling_friction;         ///< rolling friction coefficient mu_r [-]
} bdl_material;

typedef struct bdl_species_def {
    char name[BDL_NAME_LEN];
    bdl_size_dist size_dist;
    double diameter;           ///< [m] (mean for distributions)
    double diameter_min;       ///< [m]
    double diameter_max;       ///< [m]
    double diameter_std;       ///< [m] (normal distribution)
    double density;            ///< [kg/m^3]
    double background_damping; ///< b [1/s]: force -b m v on every particle of the species
    bdl_material material;
    int line; ///< line of the section header in the scene file (for messages)
} bdl_species_def;

/// Override of contact parameters for one pair of species ([pair A B]), or a species with a
/// wall. Only the fields flagged in `has_*` replace the mixed values.
typedef struct bdl_pair_def {
    int species_a, species_b; ///< indices into bdl_scene.species
    int has_restitution, has_friction, has_rolling_friction, has_stiffness;
    double restitution, friction, rolling_friction, stiffness;
    int line;
} bdl_pair_def;

typedef enum bdl_wall_kind {
    BDL_WALL_PLANE = 0,    ///< half-space boundary: particles stay on the side `normal` points to
    BDL_WALL_BOX = 1,      ///< the inside of an axis-aligned box (six planes)
    BDL_WALL_CYLINDER = 2, ///< the inside of a cylinder around an axis (infinite unless capped)
} bdl_wall_kind;

typedef enum bdl_motion_kind {
    BDL_MOTION_NONE = 0,
    BDL_MOTION_VIBRATE = 1, ///< displacement A sin(2 pi f t + phase) along `direction`
} bdl_motion_kind;

/// The frame a vibrating wall is seen from.
typedef enum bdl_wall_frame {
    BDL_FRAME_LAB = 0,       ///< the wall moves through the fixed domain
    BDL_FRAME_CONTAINER = 1, ///< the whole container moves with it; the run is done in its frame
} bdl_wall_frame;

typedef struct bdl_wall_def {
    char name[BDL_NAME_LEN];
    bdl_wall_kind kind;
    bdl_vec3 point;            ///< plane: a point on it; cylinder: a point on the axis [m]
    bdl_vec3 normal;           ///< plane: unit normal into the particle side; cylinder: unit axis
    bdl_vec3 box_min, box_max; ///< box corners [m]
    double radius;             ///< cylinder radius [m]
    bdl_motion_kind motion;
    bdl_vec3 direction;    ///< vibration direction (unit)
    double amplitude;      ///< A [m]
    double frequency;      ///< f [Hz]
    double phase;          ///< [rad]
    double start;          ///< simulated time the vibration starts; still before [s]
    bdl_wall_frame frame;  ///< lab, or container (every wall and the gas grid move with this one)
    bdl_material material; ///< wall material; fields < 0 fall back to the particle species'
    int line;
} bdl_wall_def;

typedef enum bdl_create_kind {
    BDL_CREATE_RANDOM = 0,  ///< non-overlapping random fill of a box region
    BDL_CREATE_LATTICE = 1, ///< simple cubic lattice in a box region
    BDL_CREATE_POUR = 2,    ///< insert particles in a region at a rate during the run
    BDL_CREATE_FILE = 3,    ///< positions (and optionally diameter, velocity) from a CSV file
} bdl_create_kind;

typedef struct bdl_create_def {
    char name[BDL_NAME_LEN];
    bdl_create_kind kind;
    int species;             ///< index into bdl_scene.species
    bdl_vec3 region_min;     ///< [m]
    bdl_vec3 region_max;     ///< [m]
    long count;              ///< number of particles (random, lattice, pour); -1 if not given
    double volume_fraction;  ///< target solids fraction of the region (random); < 0 if not given
    double spacing;          ///< lattice spacing [m]; < 0 -> 1.0001 max diameter
    double rate;             ///< pour rate [particles/s]
    double start_time;       ///< pour start [s]
    bdl_vec3 velocity;       ///< initial velocity [m/s]
    double velocity_jitter;  ///< random velocity magnitude added [m/s]
    char file[BDL_PATH_LEN]; ///< CSV path (relative to the scene file's folder)
    int line;
} bdl_create_def;

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
} bdl_output_def;

/// Preset camera orientations.
typedef enum bdl_view_preset {
    BDL_VIEW_ISO,   ///< from the front-right, above
    BDL_VIEW_FRONT, ///< along +y: the x-z plane, as a camera sees the front wall of a pseudo-2D bed
    BDL_VIEW_SIDE,  ///< along -x: the y-z plane
    BDL_VIEW_TOP,   ///< along -z: the x-y plane
} bdl_view_preset;

typedef enum bdl_projection { BDL_PROJ_PERSPECTIVE, BDL_PROJ_ORTHOGRAPHIC } bdl_projection;

/// What the particle colour shows.
typedef enum bdl_color_mode {
    BDL_COLOR_SPECIES,
    BDL_COLOR_COORDINATION,
    BDL_COLOR_SPEED,
    BDL_COLOR_VX,
    BDL_COLOR_VY,
    BDL_COLOR_VZ,
    BDL_COLOR_VOIDAGE,
    BDL_COLOR_MODE_COUNT
} bdl_color_mode;

/// [camera]: how frames and the viewer look at the scene.
/// Names of the colour modes, in enum order, NULL-terminated (the scene key `[camera] color`).
extern const char *const bdl_color_mode_names[];
/// Scene names of the drag laws ([coupling] drag), NULL-terminated.
extern const char *const bdl_scene_drag_names[];

/// A gas field drawn as a translucent slice behind or through the particles ([camera] gas_field).
typedef enum bdl_gas_field {
    BDL_GAS_FIELD_NONE = 0,
    BDL_GAS_FIELD_VOIDAGE = 1,
    BDL_GAS_FIELD_PRESSURE = 2, ///< gauge pressure [Pa]
    BDL_GAS_FIELD_SPEED = 3,    ///< |u| of the interstitial gas [m/s]
} bdl_gas_field;

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

/// A synthetic camera ([camera NAME], kind = dia): images of the particles as a DIA rig sees them,
/// with the ground truth beside every image (src/dia).
typedef struct bdl_dia_scene_def {
    char name[BDL_NAME_LEN];
    int line;
    int kind;          ///< 0: dia
    int projection;    ///< 0 orthographic, 1 perspective (bdl_dia_projection)
    bdl_vec3 position; ///< perspective: the pinhole; orthographic: centre of the view [m]
    bdl_vec3 target;   ///< point on the optical axis [m]
    bdl_vec3 up;       ///< world direction shown up
    int width, height; ///< [px]
    double pixel_size; ///< orthographic: m per pixel; perspective: sensor pixel pitch [m]
    double focal_length;
    int samples;  ///< rays per pixel along each axis
    int lighting; ///< 0 front-lit, 1 back-lit (bdl_dia_lighting)
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
} bdl_guard_def;

/// Boundary of the gas on one side of the domain ([gas] xmin ... zmax).
typedef enum bdl_gas_boundary {
    BDL_GAS_WALL,   ///< no-slip wall
    BDL_GAS_SLIP,   ///< free-slip wall
    BDL_GAS_INLET,  ///< gas enters at [gas] inlet_velocity (superficial), a jet optional
    BDL_GAS_OUTLET, ///< pressure outlet at [gas] outlet_pressure
} bdl_gas_boundary;

/// Convection scheme of the gas momentum ([gas] convection).
typedef enum bdl_gas_convection {
    BDL_GAS_UPWIND,
    BDL_GAS_VANLEER,
    BDL_GAS_SUPERBEE,
    BDL_GAS_CENTRAL,
} bdl_gas_convection;

/// [gas]: the gas phase. Absent: no grid, no gas, no cost.
typedef struct bdl_gas_scene {
    int enabled;      ///< the scene has a [gas] section
    double density;   ///< [kg/m^3]
    double viscosity; ///< dynamic [Pa s]
    bdl_vec3 cells;   ///< cells per axis (whole numbers)
    bdl_gas_convection convection;
    double tolerance;          ///< relative residual of the pressure solver
    bdl_gas_boundary side[6];  ///< xmin xmax ymin ymax zmin zmax (periodic axes: ignored)
    double inlet_velocity;     ///< superficial velocity into the domain through inlets [m/s]
    double outlet_pressure;    ///< [Pa]
    double jet_velocity;       ///< superficial velocity through the jet rectangle [m/s]
    bdl_vec3 jet_min, jet_max; ///< jet rectangle on the inlet sides [m]
    int has_jet_min, has_jet_max;
    double dt;                    ///< gas time step [s]; 0: automatic
    double probe_low, probe_high; ///< heights of the two pressure probes above the floor [m]
    int has_probe_low, has_probe_high;
    int sweep;          ///< 0 none, 1 up, 2 down, 3 up then down (a pressure-drop sweep)
    double sweep_to;    ///< the far end of the sweep [m/s]
    double sweep_step;  ///< velocity change per stage [m/s]
    double sweep_dwell; ///< time per stage [s]
    double sweep_start; ///< time the sweep starts [s]
} bdl_gas_scene;

/// [coupling]: how particles and gas exchange momentum.
typedef struct bdl_coupling_scene {
    int drag;            ///< drag law (index into the couple module's registry)
    double kernel_width; ///< half-width of the deposition kernel [m]; 0: 1.5 cells
    double max_solids;   ///< cap on the deposited solids fraction
    double syamlal_c, syamlal_d;
} bdl_coupling_scene;

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

    bdl_output_def output;
    bdl_guard_def guards;
    bdl_camera_def camera;
    bdl_gas_scene gas;
    bdl_coupling_scene coupling;
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

/// Same from a string (tests); `name` stands for the file name in messages.
bdl_result bdl_scene_load_string(const char *text, const char *name, const char *const *overrides,
                                 int override_count, bdl_scene *scene, bdl_scene_error *err);

#endif
