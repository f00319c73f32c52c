// bedlam — two-way coupling of particles and gas: the semi-implicit scheme of Patankar & Joseph
// (2001), "Modeling and numerical simulation of particulate flows by the Eulerian-Lagrangian
// approach", Int. J. Multiphase Flow 27, on the staggered grid.
//
// Every particle spreads over the points near it with a tent kernel of half-width w (at least one
// cell): weight prod_a max(0, 1 - |x_p,a - x_a| / w_a), normalised per particle. A rod spreads
// through BDL_ROD_SATELLITES points distributed through its volume (Mahajan 2019, sec. 3.3), each
// with its own kernel and an equal share of the rod's volume and drag. Volume goes to
// the cell centres inside the domain (periodic axes wrap), so it is conserved exactly. Drag goes
// to the faces of each velocity component that carry a momentum equation (not those on walls or
// inlets), and the gas velocity at the particle is interpolated from the same faces with the same
// weights, so what one side gives, the other receives.
//
// One macro step of length dt (bdl_coupling_step):
//  1. voidage: eps_c = 1 - sum_i W_ic V_i / V_c (solids fraction capped at max_solids);
//  2. drag set-up with the gas velocity u^n: per particle the drag law's K_i (= beta/phi) at the
//     particle's voidage and slip, D_i = K_i / rho_p, and the implicit factor
//     a_i = m_i D_i / (1 + D_i dt); deposited as beta_c = sum W a_i / V_c and
//     (beta v)_c = sum W a_i (v_i + dt A_i) / V_c, with A_i the particle's other acceleration;
//  3. the gas step (drag implicit in the gas);
//  4. forces on the particles for the whole macro step:
//     drag f_i = a_i (u_i - v_i - dt A_i), u_i the new gas velocity at the particle — the
//     backward-Euler drag, stable for any D_i dt — and pressure force -V_i grad p, grad p the
//     kernel average of cell gradients: the hydrostatic rho g whole, the rest the mean of the
//     cell's two face differences, where a wall or inlet face (no momentum equation) carries
//     none.
// The drag the gas feels, summed over the faces, equals minus the sum of the f_i to round-off;
// the pressure force on the particles, summed, is their buoyancy less their share (1 - eps_f) of
// every interior or periodic face's dynamic pressure difference, so that the mixture's pressure
// force telescopes to the pressures of the end layers (what the measured pressure drop carries)
// while no particle is in an outlet's layer.
// (Along an axis with no momentum face at all — one cell between two walls — the gas does not
// move and the particles' drag in that direction goes to the walls.)
#ifndef BDL_COUPLING_H
#define BDL_COUPLING_H

#include "cfd/gas.h"
#include "core/error.h"
#include "couple/drag.h"
#include "dem/particles.h"

#define BDL_KERNEL_MAX 8 ///< cells per axis a particle may touch (w <= 4 cells)
/// Points a rod spreads through: four stations along the axis, four points around it at each.
#define BDL_ROD_SATELLITES 16

/// Per-particle loops over fewer particles than this run on one thread (as the force pass: see
/// BDL_PARALLEL_MIN in core/parallel.h).
#define BDL_COUPLING_PARALLEL_MIN 4096

/// Most fields one deposit fills (the drag set-up's beta, beta v, the pressure share and the
/// three factors of the volume flux still to come).
#define BDL_COUPLING_FIELDS 18

/// The deposit chunk of parcels (bdl_coupling_def.chunk): with the parcels in cell order (see
/// bdl_coupling_sort) a chunk is a slab of the bed, and its sums cover little more than it.
#define BDL_COUPLING_CHUNK 4096
/// Most deposit chunks (more particles make longer chunks): the slabs' overlaps stay few.
#define BDL_COUPLING_CHUNKS 64

/// bdl_coupling_sort reorders the particles when more than 1 in this many follow one in a later
/// cell.
#define BDL_COUPLING_DISORDER 8

typedef struct bdl_coupling_def {
    bdl_drag_law drag;
    bdl_drag_params drag_params;
    double kernel_width; ///< tent half-width [m]; raised to one cell, lowered to four
    double max_solids;   ///< cap on the deposited solids fraction
    /// The solids velocity the drag sees: 0 each particle's own; 1 the solids' mean around it
    /// (Sun 2007 eqs. 7.33-7.34, the TF-DEM's "averaged" drag): every particle of a cell drawn by
    /// the drag of the cell's mean solids velocity (bdl_coupling_drag_setup)
    int mean_drag;
    /// Particles per deposit chunk: 0, one pass in particle order; else the particles in chunks
    /// of this many (of more when that makes over BDL_COUPLING_CHUNKS), each summed on its own
    /// (in parallel), the chunks' sums added cell by cell in chunk order (the same on any number
    /// of threads, not the bits of one pass)
    long chunk;
} bdl_coupling_def;

/// The defaults on a grid: Gidaspow's drag with the Syamlal-O'Brien defaults, a kernel half-width
/// of 1.5 of the grid's largest cell size, solids fraction capped at 0.7.
bdl_coupling_def bdl_default_coupling_def(const bdl_grid *grid);

/// The kernel's points per axis, when the loops over them are spelt out: two along each (the
/// trilinear kernel of one cell), two along x and z on a grid one cell deep, or any other.
typedef enum bdl_kernel_shape {
    BDL_KERNEL_GENERAL,
    BDL_KERNEL_TRILINEAR,
    BDL_KERNEL_FLAT_Y
} bdl_kernel_shape;

typedef struct bdl_coupling {
    bdl_coupling_def def;
    long capacity;       ///< particles
    long point_capacity; ///< kernel points
    long *first;         ///< per particle: its first kernel point (count + 1 entries)
    // Per kernel point (a sphere's centre, a rod's satellites), six separable kernels: slots 0-2
    // over the cell centres along x, y, z; slots 3-5 over the momentum faces of component x, y, z
    // along its own axis.
    // Each slot holds points[a] entries along its axis a (those of positive weight, then weight
    // 0 on the last of them), kmax apart; an axis one cell across with no outlet on it has one.
    int points[3];       ///< entries per slot along each axis
    int kmax;            ///< the largest of points[]
    int shape;           ///< bdl_kernel_shape of points[]: the loops spelt out for the common ones
    int *offset;         ///< padded-index offsets per slot (periodic axes wrapped)
    double *weight;      ///< normalised weights per slot
    int *lo, *hi;        ///< per point: the lowest and highest padded index of its slots
    double *factor;      ///< per particle: a_i = m D / (1 + D dt) [kg/s]
    double width[3];     ///< kernel half-width per axis [m]
    double inv_h[3];     ///< 1 / cell size per axis [1/m]
    double reach[3];     ///< half-width in cells per axis
    double inv_reach[3]; ///< 1 / reach
    long parallel_min;   ///< per-particle loops go parallel from this many particles
    /// MPI ranks (world/world_dist.c): each holds part of the particles and the whole gas, so
    /// every deposit is summed over the ranks (in rank order) before the gas, the same on each,
    /// steps: the gas grid is replicated, not divided.
    int divided;
    double *grad[3]; ///< scratch: cell-centred pressure gradient (padded grid fields)
    double *mean[7]; ///< with def.mean_drag: the cells' solids volume, mean v and mean A
    // Per particle, for one coupling step:
    bdl_vec3 *accel;    ///< acceleration other than the drag over the last step [m/s^2]
    bdl_vec3 *drag;     ///< drag force for the coming step [N]
    bdl_vec3 *pressure; ///< pressure force for the coming step [N]
    bdl_vec3 *target;   ///< with def.mean_drag: the mean v + dt A at the particle [m/s]
    bdl_vec3 *mean_vel; ///< with def.mean_drag: the mean v at the particle (the slip's) [m/s]
    int32_t *listed;    ///< scratch: the particles bdl_coupling_relocate locates
    // Scratch of bdl_coupling_sort:
    long order_capacity;  ///< particles
    int32_t *order_key;   ///< per particle: its cell
    int32_t *order_perm;  ///< per particle: the new order
    void *order_scratch;  ///< for bdl_particles_permute
    int32_t *order_start; ///< per cell (and one more): the first of its particles
    // The deposits' chunks (def.chunk; couple/coupling_deposit.c), planned for the kernels now:
    long chunks;          ///< 0: one pass in particle order
    long chunk_particles; ///< particles per chunk (the last may have fewer)
    long chunk_planned;   ///< the particle count planned for
    long chunk_capacity;  ///< chunk records allocated
    long *chunk_lo;       ///< per chunk: the lowest padded index its particles reach
    long *chunk_hi;       ///< per chunk: the highest
    long *chunk_base;     ///< per chunk: where its sums start in the pool
    long pool_capacity;   ///< doubles
    double *pool;         ///< per chunk BDL_COUPLING_FIELDS fields over its range; zero between
} bdl_coupling;

/// One coupling step: its length, the last one's, and the acceleration both phases feel.
typedef struct bdl_coupling_step_def {
    double dt;        ///< this gas step [s]
    double dt_last;   ///< the previous gas step [s]; 0 for the first
    bdl_vec3 gravity; ///< at mid-step: gravity, and in a vibrating container its inertia [m/s^2]
} bdl_coupling_step_def;

/// What a coupling step did, for the balances and the timing.
typedef struct bdl_coupling_report {
    double particle_drag[3]; ///< drag on all particles for the coming step [N]
    double gas_drag[3];      ///< drag of the particles on the gas [N]
    double work;             ///< work of the gas's forces over the previous step [J]
    double stable_dt;        ///< the gas's stable step after this one [s]; 0 if it failed
    double gas_seconds;      ///< wall time of the gas step [s]
    double coupling_seconds; ///< wall time of deposition, interpolation and forces [s]
} bdl_coupling_report;

bdl_result bdl_coupling_init(bdl_coupling *c, const bdl_coupling_def *def, const bdl_gas *gas);
void bdl_coupling_free(bdl_coupling *c);

/// One macro step of length def->dt: the voidage, the drag set-up, the gas step, and the drag
/// and pressure forces the particles carry until the next one (p->fluid_accel, p->drag_accel,
/// with p->vel_mark their velocity now). BDL_ERR_UNSTABLE when the gas step failed
/// (report->stable_dt 0: the pressure solver did not converge or a velocity is not finite) or
/// went beyond twice its stable step (report->stable_dt says it); the particles are untouched
/// then.
bdl_result bdl_coupling_step(bdl_coupling *c, bdl_gas *gas, bdl_particles *p,
                             const bdl_coupling_step_def *def, bdl_coupling_report *report);

/// Work of the gas's forces on particle i over the first `span` seconds of the current gas step,
/// as the next coupling step will book it [J].
double bdl_coupling_work(const bdl_particles *p, long i, double span);

/// The steps one by one (bdl_coupling_step runs them in order).

/// Reorders the particles (bdl_particles_permute, c->order_perm: new slot k holds old particle
/// order_perm[k]) by the gas cell holding their centre, z slowest and x fastest, when more than 1
/// in BDL_COUPLING_DISORDER of them follow a particle in a later cell: neighbours in space are
/// then neighbours in memory for the kernels. The order is a function of the positions and the
/// order before alone (a stable counting sort), never of the threads. Arrays the caller keeps per
/// particle must be filled after this (or permuted with order_perm when *sorted says it moved
/// them; sorted may be NULL).
bdl_result bdl_coupling_sort(bdl_coupling *c, const bdl_gas *gas, bdl_particles *p, int *sorted);

/// Kernel weights of every particle at its current position (and orientation).
bdl_result bdl_coupling_locate(bdl_coupling *c, const bdl_gas *gas, const bdl_particles *p);

/// Kernel weights anew for the particles with which[i] set, after they moved (the others, and
/// the particle count, as the last bdl_coupling_locate left them). BDL_ERR_NOMEM.
bdl_result bdl_coupling_relocate(bdl_coupling *c, const bdl_gas *gas, const bdl_particles *p,
                                 const uint8_t *which);

/// Where kernel point k of particle i lies (k < BDL_ROD_SATELLITES for a rod, 0 otherwise).
bdl_vec3 bdl_coupling_point(const bdl_particles *p, long i, int k);
/// The gas velocity at particle i, as the drag sees it (after bdl_coupling_locate) [m/s].
bdl_vec3 bdl_coupling_gas_velocity(const bdl_coupling *c, const bdl_gas *gas, long i);
/// Sets gas->eps from the particle volumes (gas->eps_old is left alone).
void bdl_coupling_voidage(const bdl_coupling *c, bdl_gas *gas, const bdl_particles *p);

/// Drag coefficients for a macro step of length dt: fills gas->beta and gas->bv. `accel`: each
/// particle's acceleration other than drag (NULL: none). With def.mean_drag each particle's
/// velocity v and acceleration A are replaced, in the slip |u - v| and in the drag's v + dt A,
/// by their solids-volume-weighted means over the cells (deposited and read back with the
/// kernel), so
/// that all the particles of a cell feel the drag of its mean solids velocity (per unit volume)
/// and the gas the same in sum (parcels: not with mean_drag). A gas with a pressure share (the
/// parcels' implicit scheme) gets it too: gas->share = 1 - C_pr on the faces, C_pr = sum W V /
/// (1 + D dt) / V_cell, the part of the particles' volume the drag does not tie to the gas; and
/// the particles' volume flux still to come (gas->flux_u, flux_p, flux_0): the particles moved
/// by dt (v + moved) in this step (`moved`: NULL for none) and go on to move by dt (v^{n+1} - v -
/// moved) once their velocity v^{n+1} is implicit in the drag (parcels/parcels.h).
void bdl_coupling_drag_setup(bdl_coupling *c, bdl_gas *gas, const bdl_particles *p,
                             const bdl_vec3 *accel, const bdl_vec3 *moved, double dt);

/// After the gas step: drag and pressure force on every particle [N] for the macro step. NULL
/// outputs are skipped.
void bdl_coupling_forces(const bdl_coupling *c, const bdl_gas *gas, const bdl_particles *p,
                         const bdl_vec3 *accel, double dt, bdl_vec3 *drag, bdl_vec3 *pressure);

/// Total drag force on the gas [N] after its step, with the face velocities u (the gas's, or
/// their mean over its steps): sum over the gas's momentum faces of ((beta v) - beta u) V_cell.
void bdl_coupling_gas_drag(const bdl_gas *gas, double *const u[3], double total[3]);

/// A gas quantity at a particle: the kernel average of cell values f (padded cell array).
double bdl_coupling_interpolate(const bdl_coupling *c, long i, const double *f);

/// Whether any cell to which particle i's kernel gives weight holds a positive value of f (padded
/// cell array): for f >= 0 the same as bdl_coupling_interpolate(c, i, f) > 0, without the sums.
int bdl_coupling_touches(const bdl_coupling *c, long i, const double *f);
/// Whether particle i's kernel (where it was last located) gives more weight to a cell holding a
/// positive value of f (padded cell array) than its kernel at `from` would: whether its move
/// from there added to such a cell. Particles of one kernel point.
int bdl_coupling_gains(const bdl_coupling *c, const bdl_gas *gas, long i, bdl_vec3 from,
                       const double *f);

/// A face quantity at particle i: component a the kernel average of f[a] over the momentum faces
/// of component a (the weights the drag is deposited with).
bdl_vec3 bdl_coupling_face_average(const bdl_coupling *c, long i, double *const f[3]);

/// Two face quantities at particle i in one pass over its weights: each the same as
/// bdl_coupling_face_average gives.
void bdl_coupling_face_average2(const bdl_coupling *c, long i, double *const f[3],
                                double *const g[3], bdl_vec3 *at_f, bdl_vec3 *at_g);

#endif
