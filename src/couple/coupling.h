// bedlam — two-way coupling of particles and gas (seed 001's semi-implicit scheme, on the
// staggered grid).
//
// Every particle spreads over the points near it with a tent kernel of half-width w (at least one
// cell): weight prod_a max(0, 1 - |x_p,a - x_a| / w_a), normalised per particle. Volume goes to
// the cell centres inside the domain (periodic axes wrap), so it is conserved exactly. Drag goes
// to the faces of each velocity component that carry a momentum equation (not those on walls or
// inlets), and the gas velocity at the particle is interpolated from the same faces with the same
// weights, so what one side gives, the other receives.
//
// One macro step of length dt:
//  1. voidage: eps_c = 1 - sum_i W_ic V_i / V_c (solids fraction capped at max_solids);
//  2. drag set-up with the gas velocity u^n: per particle the drag law's K_i (= beta/phi) at the
//     particle's voidage and slip, D_i = K_i / rho_p, and the implicit factor
//     a_i = m_i D_i / (1 + D_i dt); deposited as beta_c = sum W a_i / V_c and
//     (beta v)_c = sum W a_i (v_i + dt A_i) / V_c, with A_i the particle's other acceleration;
//  3. the gas step (drag implicit in the gas);
//  4. forces on the particles for the whole macro step:
//     drag f_i = a_i (u_i - v_i - dt A_i), u_i the new gas velocity at the particle — the
//     backward-Euler drag, stable for any D_i dt — and pressure force -V_i grad p.
// The drag the gas feels, summed over the faces, equals minus the sum of the f_i to round-off.
// (Along an axis with no momentum face at all — one cell between two walls — the gas does not
// move and the particles' drag in that direction goes to the walls.)
#ifndef BDL_COUPLING_H
#define BDL_COUPLING_H

#include "cfd/gas.h"
#include "couple/drag.h"
#include "core/error.h"

#define BDL_KERNEL_MAX 8 ///< cells per axis a particle may touch (w <= 4 cells)

/// Per-particle loops over fewer particles than this run on one thread (as the force pass: see
/// BDL_PARALLEL_MIN in dem/contact_force.h).
#define BDL_COUPLING_PARALLEL_MIN 4096

typedef struct bdl_coupling_def {
    bdl_drag_law drag;
    bdl_drag_params drag_params;
    double kernel_width; ///< tent half-width [m]; raised to one cell, lowered to four
    double max_solids;   ///< cap on the deposited solids fraction (0.7 when 0)
} bdl_coupling_def;

typedef struct bdl_coupling {
    bdl_coupling_def def;
    long capacity;
    // Per particle, six separable kernels: slots 0-2 over the cell centres along x, y, z;
    // slots 3-5 over the momentum faces of component x, y, z along its own axis.
    int *offset;       ///< BDL_KERNEL_MAX padded-index offsets per slot (periodic axes wrapped)
    int *span;         ///< points touched in each slot
    double *weight;    ///< BDL_KERNEL_MAX normalised weights per slot
    double *factor;    ///< per particle: a_i = m D / (1 + D dt) [kg/s]
    double width[3];   ///< kernel half-width per axis [m]
    double inv_h[3];   ///< 1 / cell size per axis [1/m]
    double reach[3];   ///< half-width in cells per axis
    long parallel_min; ///< per-particle loops go parallel from this many particles
    double *grad[3];   ///< scratch: cell-centred pressure gradient (padded grid fields)
} bdl_coupling;

typedef struct bdl_coupling_particles {
    long count;
    const double *pos;     ///< xyz [m]
    const double *vel;     ///< xyz [m/s]
    const double *accel;   ///< xyz: acceleration other than drag over the last step [m/s^2]
    const double *radius;  ///< [m]
    const double *density; ///< [kg/m^3]
} bdl_coupling_particles;

bdl_result bdl_coupling_init(bdl_coupling *c, const bdl_coupling_def *def, const bdl_gas *gas);
void bdl_coupling_free(bdl_coupling *c);

/// Kernel weights of every particle at its current position.
bdl_result bdl_coupling_locate(bdl_coupling *c, const bdl_gas *gas, long count, const double *pos);

/// Sets gas->eps from the particle volumes (gas->eps_old is left alone).
void bdl_coupling_voidage(const bdl_coupling *c, bdl_gas *gas, const bdl_coupling_particles *p);

/// Drag coefficients for a macro step of length dt: fills gas->beta and gas->bv.
void bdl_coupling_drag_setup(bdl_coupling *c, bdl_gas *gas, const bdl_coupling_particles *p,
                             double dt);

/// After the gas step: drag and pressure force on every particle (xyz, [N]) for the macro step.
/// NULL outputs are skipped.
void bdl_coupling_forces(const bdl_coupling *c, const bdl_gas *gas, const bdl_coupling_particles *p,
                         double dt, double *drag, double *pressure);

/// Total drag force on the gas [N] after its step: sum over the gas's momentum faces of
/// ((beta v) - beta u) V_cell.
void bdl_coupling_gas_drag(const bdl_gas *gas, double total[3]);

/// A gas quantity at a particle: the kernel average of cell values f (padded cell array).
double bdl_coupling_interpolate(const bdl_coupling *c, long i, const double *f);

#endif
