// bedlam — the world: the modules a scene needs, and one time step.
//
// A world is built from a validated scene. It owns the particles, walls, neighbour lists and
// contact tables, and with [gas] the gas and its coupling, and advances them with
// bdl_world_step. Nothing here starts threads or writes files: the run loop (run/loop.h) does
// that around it.
//
// The next solvers take their places beside the gas: parcels of many real particles
// (src/parcels/) and solids phases on the gas's grid (src/solids/) become members built only
// when a scene asks for them, stepped inside the gas step where they exchange momentum with the
// gas through the same implicit drag coefficients on the faces (cfd/gas.h: beta, bv) as the
// particles do (docs/architecture.md, "The next solvers").
#ifndef BDL_WORLD_H
#define BDL_WORLD_H

#include <stdint.h>

#include "core/rng.h"
#include "dem/contact_force.h"
#include "dem/material.h"
#include "dem/neighbor.h"
#include "dem/particles.h"
#include "dem/walls.h"
#include "scene/scene.h"
#include "world/budget.h"

struct bdl_gas;
struct bdl_coupling;
struct bdl_dist;
struct bdl_parcels;
struct bdl_solids;

/// Live parameters a user may change between steps (commands); logged with their step.
typedef struct bdl_live_params {
    double amplitude_scale[BDL_MAX_WALLS]; ///< multiplies each wall's vibration amplitude
    double frequency_scale[BDL_MAX_WALLS]; ///< multiplies each wall's vibration frequency
    double inlet_scale;                    ///< multiplies the gas inlet and jet velocities
} bdl_live_params;

typedef struct bdl_world {
    bdl_scene scene;
    bdl_particles particles;
    bdl_neighbor neighbor;
    bdl_walls walls;
    bdl_force_work force_work;
    bdl_contact_params pair_params[BDL_MAX_SPECIES * BDL_MAX_SPECIES];
    bdl_contact_params wall_params[BDL_MAX_WALLS * BDL_MAX_SPECIES];
    double background_damping[BDL_MAX_SPECIES]; ///< b per species [1/s]
    uint8_t *coordination;                      ///< particle contacts of each particle this step
    long coordination_capacity;

    int hertz;    ///< Hertz normal law (else linear)
    int friction; ///< any sliding friction: tangential history is kept
    int rolling;  ///< rolling resistance active

    long parallel_min;                     ///< force pass on one thread below this particle count
    double dt;                             ///< time step [s]
    double time;                           ///< simulated time [s]
    long step;                             ///< steps taken
    bdl_rng rng;                           ///< used by pouring
    long poured[BDL_MAX_CREATES];          ///< particles inserted so far by each pour creator
    bdl_mesh region_mesh[BDL_MAX_CREATES]; ///< creators with region_shape = mesh: the mesh

    bdl_live_params live;

    // Energy bookkeeping for the balance check [J].
    double wall_work;       ///< work done by walls on particles
    double inserted_energy; ///< kinetic + potential energy of particles added during the run
    double damping_work;    ///< work done by background damping (negative)
    double removed_energy;  ///< kinetic + potential energy carried out through outlets
    double energy0;         ///< total mechanical energy when the run started

    bdl_budget budget; ///< what the scene was estimated to need before it was built

    double contact_time;          ///< smallest contact time over all pairs [s]
    double contact_time_dt_ratio; ///< dt / contact_time

    int container; ///< the wall whose frame the run is done in ([wall] frame = container), or -1

    // Particles that cross a face where the gas has a pressure outlet leave the run: they are
    // removed (at the end of the step's drift) and counted here, never lost silently.
    int outflow[6];      ///< per face (x min, x max, y min, ...): a gas outlet
    long removed;        ///< particles that left through outlets
    double removed_mass; ///< their mass [kg]
    uint8_t *drop;       ///< scratch: the particles leaving this step
    long drop_capacity;

    // The gas ([gas] in the scene; NULL otherwise): a gas step spans gas_every particle steps,
    // chosen anew before every gas step from the gas's speed unless [gas] dt fixes it.
    struct bdl_gas *gas;
    struct bdl_coupling *coupling;
    long gas_every;          ///< particle steps in the current gas step
    long gas_every_max;      ///< at most this many (the fixed count when gas_fixed)
    int gas_fixed;           ///< [gas] dt given: every gas step spans gas_every particle steps
    long gas_next;           ///< particle step at which the next gas step starts
    double gas_stable;       ///< the stable gas step after the last one (CFL 1/2, viscous) [s]
    long solids_retakes;     ///< adaptive solids steps taken back and retaken (this process)
    int gas_inflow_raised;   ///< the live inlet scale rose since the last gas step
    long gas_steps;          ///< gas steps taken
    double particle_drag[3]; ///< drag of the gas on all particles over the last gas step [N]
    double gas_drag[3];      ///< drag of the particles on the gas over the last gas step [N]
    double gas_work;         ///< work of the gas's forces on the particles since the start [J]
    double gas_seconds;      ///< wall-clock time spent in gas steps [s]
    double coupling_seconds; ///< wall-clock time spent coupling (deposit, interpolate, forces) [s]

    // Parcels (a species made of them; NULL otherwise): they step with the gas, one gas step per
    // step of the world, and have no contacts, neighbour lists or contact time.
    struct bdl_parcels *parcels;
    long parcels_held;     ///< parcels the packing guard held back since the start
    double max_solids;     ///< largest solids fraction of a cell after the last step
    long parcel_pairs;     ///< model B: touching parcel pairs after the last step
    long parcel_walls;     ///< model B: parcel-side contacts after the last step
    double parcel_overlap; ///< model B: largest overlap / R_ep after the last step

    // A solids phase on the gas grid ([solids]; NULL otherwise): it steps with the gas, one step
    // per step of the world; there are no particles. max_solids holds its largest fraction.
    struct bdl_solids *solids;

    // MPI ranks (dist/exchange.h; NULL in one process): `particles` holds this rank's own
    // particles (count of them) and, after them, its ghosts.
    struct bdl_dist *dist;

    /// Why the last bdl_world_step failed, for the caller to report (the world prints nothing).
    char failure[512];
} bdl_world;

/// Builds every module the scene needs and creates the initial particles. Bad initial
/// conditions (overlaps, particles outside the domain, a random fill that cannot be placed) fail
/// with BDL_ERR_SCENE and a message in `err` naming the [create] section and its line.
bdl_result bdl_world_create(const bdl_scene *scene, bdl_world **out, bdl_scene_error *err);
/// Under MPI (more than one rank) bdl_world_create divides the particles between the ranks
/// (world_dist.c); this builds the whole world on this rank instead (a reference, a tool).
bdl_result bdl_world_create_whole(const bdl_scene *scene, bdl_world **out, bdl_scene_error *err);
void bdl_world_destroy(bdl_world *world);

/// Advances the world by one time step dt (velocity Verlet). On a failure (BDL_ERR_UNSTABLE: the
/// gas cannot be advanced) `failure` says what, where and when.
bdl_result bdl_world_step(bdl_world *world);

/// The acceleration every particle and the gas feel at time t: gravity, plus, in a vibrating
/// container's frame ([wall] frame = container), the inertial A w^2 sin(w t + phase) along the
/// container's direction (with the live amplitude and frequency scales).
bdl_vec3 bdl_world_gravity(const bdl_world *world, double t);

/// Recomputes forces for the current state (after creation, loading or a parameter change).
bdl_result bdl_world_compute_forces(bdl_world *world);

/// Hash of the full dynamic state (positions, velocities, spins, ids, history and the work in the
/// springs, time).
uint64_t bdl_world_hash(const bdl_world *world);

/// Builds the gas and the coupling of a scene with [gas] (world_create calls it).
bdl_result bdl_world_gas_init(bdl_world *world, bdl_scene_error *err);
void bdl_world_gas_free(bdl_world *world);

/// Builds the gas, coupling and parcel solver of a scene with parcels, and its step (world_create
/// calls it).
bdl_result bdl_world_parcels_init(bdl_world *world, bdl_scene_error *err);
void bdl_world_parcels_free(bdl_world *world);

/// The stable step of a world of parcels: CFL 1/2 for the inflow through close packing, and
/// the gas's viscous limit [s] (the drag is implicit, the stress damped by it); with gas
/// sub-steps G times that, up to CFL 1 for the parcels.
double bdl_world_parcels_stable_dt(const bdl_world *world);
/// What bdl_world_parcels_stable_dt stands on, in words for messages.
const char *bdl_world_parcels_stable_basis(const bdl_world *world);

/// One line on the parcels' model and its parameters (as resolved: eta_c), for logs.
void bdl_world_parcels_describe(const bdl_world *world, char *buf, size_t size);

/// The smallest mass of a parcel the scene's species make [kg]; INFINITY without parcels.
double bdl_world_parcel_mass_min(const bdl_world *world);

/// The longest step parcel collisions (model B) allow: bdl_parcels_collision_dt for the smallest
/// parcel mass [s]; INFINITY for model A.
double bdl_world_parcels_collision_dt(const bdl_world *world);

/// One step of a world of parcels (bdl_world_step calls it).
bdl_result bdl_world_parcels_step(bdl_world *world);

/// Builds the gas and the solids phase of a scene with [solids], and fills the bed (world_create
/// calls it).
bdl_result bdl_world_solids_init(bdl_world *world, bdl_scene_error *err);
void bdl_world_solids_free(bdl_world *world);

/// One step of a world with a solids phase (bdl_world_step calls it).
bdl_result bdl_world_solids_step(bdl_world *world);

/// The solids' bed at the start, for logs: "a bed 0.15 m tall at a solids fraction of 0.583", or
/// each phase's fraction and layer.
void bdl_world_solids_bed(const bdl_world *world, char *buf, size_t size);

/// One line on the solids phase and its parameters, for logs.
void bdl_world_solids_describe(const bdl_world *world, char *buf, size_t size);

/// How the parcels of a world fill the gas's cells, for check and run.log.
typedef struct bdl_parcels_census {
    long parcels;
    double real_particles; ///< the real particles they stand for
    long cells;            ///< cells of the gas grid
    long filled_cells;     ///< cells holding a parcel's centre
    double per_cell_mean;  ///< parcels per filled cell (their centres)
    double per_cell_min, per_cell_max;
    double max_solids; ///< largest solids fraction of a cell, as the gas holds it (the kernels)
} bdl_parcels_census;

/// The census of the parcels where they are now; BDL_ERR_NOMEM.
bdl_result bdl_world_parcels_census(const bdl_world *world, bdl_parcels_census *out);

/// The largest particle's extent (a diameter, or a rod's length) plus the neighbour skin, which
/// goes to `skin` [m].
double bdl_world_contact_reach(const bdl_scene *scene, double *skin);

/// MPI ranks (world_dist.c): divides the particles of a world built on every rank between the
/// ranks (world_create calls it when there is more than one). BDL_ERR_SCENE, with the reason in
/// err, for a scene the ranks cannot share yet (parcels, a solids phase, rods, pouring,
/// Lees–Edwards boundaries) or a domain too small for the rank count. A gas is replicated: each
/// rank steps the whole grid with the deposits of every rank's particles.
bdl_result bdl_world_dist_init(bdl_world *world, bdl_scene_error *err);

/// MPI ranks: before a force pass, the ghosts from their owners and, when any rank's lists need
/// it, the collective rebuild (world.c's force pass calls it).
bdl_result bdl_world_dist_lists(bdl_world *world, double max_move2);

/// MPI ranks, collective: the worst of every rank's result `r` of a step (so that they all go on
/// or all stop); a rank whose own step went well but another's did not says so in its failure.
bdl_result bdl_world_dist_agree(bdl_world *w, bdl_result r);

/// MPI ranks, collective: the divided world `w` copied whole into `mirror` on rank `root` (a
/// world built whole from the same scene; NULL elsewhere): its particles in the order of their
/// ids with every array and their coordination, the time and the walls, the energy booked
/// (summed over the ranks), and lists built for them with every touching contact's spring. A
/// checkpoint of the mirror is the run's whole state, to resume on any number of ranks.
bdl_result bdl_world_dist_mirror(bdl_world *w, bdl_world *mirror, int root);

/// One line naming the active modules and their models, for run.log.
void bdl_world_describe(const bdl_world *world, char *buf, size_t size);

/// One line describing the gas module ("none (...)" without gas), for check and run.log.
void bdl_world_gas_describe(const bdl_world *world, char *buf, size_t size);

/// One gas step with its coupling, at the start of a particle step that begins one
/// (bdl_world_step calls it). BDL_ERR_UNSTABLE when the gas cannot be advanced stably.
bdl_result bdl_world_gas_step(bdl_world *world);

/// CFL 1/2 for the fastest gas to expect at a superficial inflow: the inflow through the densest
/// packing plus a margin, at most 5e-4 s and the gas's own stable step [s].
double bdl_world_expected_gas_dt(const bdl_world *world, double inflow);
/// The same for the scene's inflow: the faster of its inlet and jet velocities.
double bdl_world_inflow_gas_dt(const bdl_world *world);

/// Says in world->failure why a gas step (`what`: "gas step", "parcel step") of length dt failed:
/// beyond twice the stable step stable_dt, or (stable_dt 0) the pressure solver or a velocity;
/// `key` names the scene key that sets the step.
void bdl_world_gas_failure(bdl_world *world, const char *what, const char *key, double dt,
                           double stable_dt);

/// The superficial inlet velocity at time t: [gas] inlet_velocity, or the stage of its sweep,
/// times the live inlet scale [m/s].
double bdl_world_inlet_velocity(const bdl_world *world, double t);

/// Work the gas's forces have done on particle i since the current gas step began, not yet in
/// gas_work (which books a gas step's work when the next one starts) [J]; 0 without a gas.
double bdl_world_gas_work_pending(const bdl_world *world, long i);

/// Contact time of the smallest particles of species a and b [s], and of species a with a wall;
/// Hertz contacts at impact speed `v_ref`.
double bdl_world_pair_contact_time(const bdl_world *world, int a, int b, double v_ref);
double bdl_world_wall_contact_time(const bdl_world *world, int a, int wall, double v_ref);

/// Smallest contact time over species pairs and species-wall pairs [s], with the pair that has
/// it described in `which` (may be NULL). Hertz uses the impact speed `v_ref`.
double bdl_world_min_contact_time(const bdl_world *world, double v_ref, char *which, int which_len);

/// Reference impact speed for Hertz contact times [m/s]: free fall over the domain height, the
/// fastest wall, and the initial particle speeds.
double bdl_world_reference_speed(const bdl_world *world);

/// The axis gravity points along (z without gravity) and the sign of "up" on it (+1 or -1).
int bdl_world_vertical_axis(const bdl_world *world, double *up);

/// A contact as the outputs see it.
typedef struct bdl_world_contact {
    bdl_vec3 n;     ///< unit normal, from the partner (or the wall) towards particle i
    double overlap; ///< [m], > 0
    double r_eff;   ///< effective radius of the contact law [m]
    bdl_vec3 point; ///< the contact point, in the middle of the overlap [m]
    bdl_vec3 v_c;   ///< relative velocity of the contact point (i minus the partner) [m/s]
    bdl_vec3 arm_j; ///< rods: the contact point from the partner's centre [m]
    double normal;  ///< normal force the law gives now, the dashpot included [N]
    int prim;       ///< a wall contact's primitive (-1 for a pair)
} bdl_world_contact;

/// The listed pair (i, j): 0 when they do not touch, else the contact (spheres: centres; rods:
/// the shafts' closest points, as the force pass has them).
int bdl_world_pair_contact(const bdl_world *world, long i, long j, bdl_world_contact *c);

/// The force on particle i of pair k of its list, as the law gives it now (with friction, from
/// the spring as stored: the force the next step starts from); zero when the pair does not touch.
bdl_vec3 bdl_world_pair_force(const bdl_world *world, long i, int32_t k);

/// Entry k of particle i's wall list: 0 when it does not touch, else the contact.
int bdl_world_wall_contact(const bdl_world *world, long i, int32_t k, bdl_world_contact *c);

/// Applies live parameters (after a command changed them).
void bdl_world_apply_live(bdl_world *world);

/// Sets a live parameter by its command key ("gas.inlet_scale", "wall.NAME.amplitude_scale",
/// "wall.NAME.frequency_scale") and applies it; returns 0 for an unknown key.
int bdl_world_set_parameter(bdl_world *world, const char *key, double value);

#endif
