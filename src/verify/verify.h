// bedlam — verification cases: each model against a known answer, at a chosen resolution.
//
// Every case is a function of one refinement number N (steps per contact time, cells per side,
// steps per relaxation time, ...): the cost grows with N and, where the scheme converges, the
// error falls like N^-p. `bedlam verify` runs each case at three or more N and writes the error
// against the wall time (report.c); the ctest programs call the same measurement functions and
// assert tolerances and orders on them, so what is tested is what is reported.
#ifndef BDL_VERIFY_H
#define BDL_VERIFY_H

#include <stdarg.h>

#include "core/error.h"
#include "couple/drag.h"
#include "world/world.h"

#if defined(__GNUC__)
#define BDL_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define BDL_PRINTF(a, b)
#endif

/// One run of a case at one refinement.
typedef struct bdl_verify_result {
    double error; ///< the case's error measure (relative unless the case says otherwise)
    double value; ///< the measured quantity
    double exact; ///< its reference value
    long steps;   ///< time steps taken (particle steps, or gas steps for the gas-only cases)
} bdl_verify_result;

typedef struct bdl_verify_case {
    const char *name;       ///< command-line name, CSV and plot file stem
    const char *title;      ///< one line
    const char *model;      ///< the model or scheme being verified
    const char *reference;  ///< the known answer and its source
    const char *measure;    ///< what `error` is
    const char *param;      ///< what the refinement number N is
    const char *order_note; ///< the order the scheme predicts, and why (or why none applies)
    const char *breaks;     ///< where the model stops being valid or stable
    double tolerance;       ///< acceptance: error at level `tolerance_level` at most this
    int tolerance_level;    ///< index into level[]
    double order_min;       ///< acceptance: observed order over the finest pair (0: none)
    int no_order;           ///< no order of convergence applies (the note says why)
    double diff_order_min;  ///< acceptance: order of the successive differences over the finest
                            ///< three levels, for errors that tend to a floor (0: none)
    int quick;              ///< part of `bedlam verify --quick`
    int quick_levels;       ///< levels run by --quick (the first ones)
    int series_count;       ///< methods or parameters drawn as separate lines
    const char *series[4];  ///< their names
    int level_count;        ///< refinements
    double level[6];        ///< N, increasing (cost increases)
    bdl_result (*run)(int series, double level, bdl_verify_result *out);
} bdl_verify_case;

/// The registry, in report order.
const bdl_verify_case *bdl_verify_cases(int *count);
const bdl_verify_case *bdl_verify_find(const char *name);

/// Observed order between refinements n1 < n2 with errors e1, e2: log(e1/e2)/log(n2/n1).
double bdl_verify_order(double n1, double e1, double n2, double e2);
/// Order of the successive differences of three errors at n1 < n2 < n3 with n3/n2 = n2/n1:
/// log((e1 - e2)/(e2 - e3))/log(n2/n1), which sees the converging part of an error that tends to
/// a floor e_inf + c N^-p (NAN when the differences change sign).
double bdl_verify_difference_order(double n1, double e1, double n2, double e2, double n3,
                                   double e3);

/// Builds a world from scene text; NULL (the scene's message and the text on stderr) on any error.
bdl_world *bdl_verify_world_text(const char *text);
/// The same from printf-formatted scene text.
bdl_world *bdl_verify_world(const char *format, ...) BDL_PRINTF(1, 2);
bdl_world *bdl_verify_world_v(const char *format, va_list ap);
/// Index of the particle with stable id `id`, or -1.
long bdl_verify_find_particle(const bdl_world *w, uint32_t id);

// ---- DEM: one and two spheres (verify_dem.c) ----

/// Contact time of the bounce case's sphere on its plane: linear pi/(w0 sqrt(1 - zeta^2)), Hertz
/// 2.87 (m^2/(r E*^2 v))^(1/5) [s].
double bdl_verify_bounce_contact_time(int hertz, double e, double v);
/// The bounce case's world: one sphere of 10 mm (2500 kg/m^3; k_n 2e6 N/m or E 1 GPa) with its
/// centre at z0 moving down at v above a plane at z = 0, gravity g downwards.
bdl_world *bdl_verify_bounce_world(int hertz, const char *damping, double e, double v, double z0,
                                   double dt, double g);
/// Realised restitution of one impact at speed v, gravity off, the contact starting a fraction
/// `phi` into a step; -1 if the sphere never left. `damping`: "exact" or "closed_form".
double bdl_verify_restitution(int hertz, const char *damping, double e, double v, double dt,
                              double phi, long *steps);
/// Worst |e_measured - e|/e over 8 contact phases.
double bdl_verify_restitution_worst(int hertz, double e, double v, double dt, long *steps);

/// Hertz contact duration theory, 2.8683 (m*^2/(R* E*^2 v))^(1/5) [s], of the duration case.
double bdl_verify_hertz_time(int pair, double v);
/// Measured elastic Hertz contact duration [s] (start and end interpolated between steps);
/// pair = 0 sphere on a plane, 1 two spheres head-on at relative speed v. `rebound` gets the
/// separation speed over the impact speed. -1 if the contact never ended.
double bdl_verify_hertz_duration(int pair, double v, double dt, double *rebound, long *steps);

typedef struct bdl_verify_slide {
    double t_fit;       ///< zero of the line fitted to the sliding phase's slip [s]
    long forward;       ///< sliding steps where the friction force pointed along the slip
    double max_forward; ///< the largest such force over mu F_n
    double v_roll;      ///< v_x at 2 t_s [m/s]
    double slip_end;    ///< |slip| at 2 t_s [m/s]
    long steps;
} bdl_verify_slide;
/// A sphere launched at v0 without spin on a rough plane (dt in s).
bdl_verify_slide bdl_verify_slide_roll(int hertz, double mu, double v0, double dt);

/// Contact time of the elastic head-on collision case at relative speed v [s].
double bdl_verify_collision_contact_time(int hertz, double v);
/// Relative kinetic-energy error after one elastic head-on collision (contact starting a fraction
/// phi into a step); INFINITY if the spheres never touched.
double bdl_verify_collision_energy(int hertz, double v, double dt, double phi, long *steps);

#define BDL_VERIFY_COLUMN 5
typedef struct bdl_verify_column {
    double overlap[BDL_VERIFY_COLUMN]; ///< contact c: 0 wall-bottom, c sphere c on c-1 [m]
    double theory[BDL_VERIFY_COLUMN];  ///< static overlap of the spring law [m]
    double lateral;                    ///< largest lateral offset [m]
    double kinetic, kinetic_limit;     ///< kinetic energy at the end, and the rest criterion [J]
    double time, dt_ratio;             ///< settling time [s]; dt / t_c
    long steps;
} bdl_verify_column;
/// Five spheres stacked on a plane under gravity, settled: the overlaps against the spring law.
bdl_verify_column bdl_verify_static_column(int hertz, double dt_fraction);

// ---- oblique impact of an elastic sphere on a plane (verify_oblique.c) ----

/// kappa = 2 (1 - nu)/(2 - nu), the ratio of tangential to normal stiffness at one overlap.
double bdl_verify_oblique_kappa(void);
/// chi = (1 - nu)/(2 - nu) (1 + m r^2/I) of Maw, Barber & Fawcett (1976): 1.4412 here.
double bdl_verify_oblique_chi(void);
/// Contact time of the oblique case's normal impact [s].
double bdl_verify_oblique_contact_time(void);
/// Tangential contact-point speed of reduced incidence psi1 = kappa v_t/(mu v_n) [m/s].
double bdl_verify_oblique_speed(double psi1, double mu);

typedef struct bdl_verify_oblique {
    double vt1, vn1;      ///< contact point before: tangential velocity, approach speed [m/s]
    double vt2, vn2;      ///< after separation: tangential velocity, normal speed [m/s] (NAN: none)
    double energy_error;  ///< (E after - E before)/E before, E kinetic + rotational
    double worst_balance; ///< largest |energy balance|/E before over the steps (diagnostics)
    long steps;
} bdl_verify_oblique;
/// The case's world: a steel sphere (d = 10 mm, E = 200 GPa, nu = 0.3, e = 1, Hertz-Mindlin,
/// friction mu) moving at (vt, 0, -1) m/s without spin onto a plane, touching it a fraction phi
/// into the 4th step; gravity off.
bdl_world *bdl_verify_oblique_world(double vt, double mu, double dt, double phi);
/// One impact of that world, measured after the sphere has left the plane.
bdl_verify_oblique bdl_verify_oblique_impact(double vt, double mu, double dt, double phi);
/// The same impact under bedlam's law in the limit dt -> 0, by RK4 of the same equations of motion
/// (lever arm r - delta/2): sliding = 0 in full stick (the spring never capped), 1 in gross
/// sliding throughout (F_t = -mu F_n sign v_t). `steps`: RK4 steps; worst_balance unset.
bdl_verify_oblique bdl_verify_oblique_reference(double vt, double mu, int sliding);
/// psi2 of Maw, Barber & Fawcett's theory at psi1 for Poisson's ratio nu and 1 + m r^2/I =
/// inertia_factor (3.5 for a solid sphere), by the method of dimensionality reduction on
/// `springs` springs (2000: converged to 1e-5).
double bdl_verify_mbf_psi2(double nu, double inertia_factor, double psi1, int springs);

// ---- rods (verify_rods.c) ----

#define BDL_VERIFY_TILT_BINS 9
/// The thesis's small rod bed (Mahajan 2019, table 4.1; scenes/rod_bed_packed.ini), packed.
typedef struct bdl_verify_rod_bed {
    double height;       ///< the bed's surface (analysis/granular.h: bdl_bed_surface_of) [m]
    double bulk;         ///< solids fraction below it
    double vertical_cos; ///< mean |cos| of the axes to the vertical (1/2 isotropic)
    double order;        ///< nematic order parameter S
    double tilt[BDL_VERIFY_TILT_BINS]; ///< fraction of the rods at 0-10, 10-20, ... 80-90 degrees
                                       ///< from the horizontal
    double kinetic;                    ///< kinetic energy per rod / (m g d) at the end
    double time;                       ///< simulated [s]
    long steps;
} bdl_verify_rod_bed;
/// 8070 rods dropped with random axes into the 0.1 x 0.014 m column, settled (kinetic energy
/// below 1e-4 m g d per rod after at least 0.4 s, at most 3 s) at dt = dt_fraction of the shortest
/// contact time.
bdl_result bdl_verify_rod_bed_run(double dt_fraction, bdl_verify_rod_bed *out);

// ---- gas and coupling (verify_gas.c) ----

/// Steady plane Poiseuille flow on `cells` across the channel: max |u - exact| / u_max. `cross`
/// gets the largest cross-stream velocity over u_max (must be round-off).
double bdl_verify_poiseuille(int cells, double *cross, long *steps);

/// Lid-driven cavity at Re 100 on n x n cells against Ghia, Ghia & Shin (1982): the largest
/// difference of u on the vertical and v on the horizontal centreline (lid speed 1). With `table`
/// set, prints the profiles. Returns -1 when the solver failed.
double bdl_verify_cavity(int n, int scheme, double *worst_u, double *worst_v, int table,
                         long *steps);

typedef struct bdl_verify_terminal {
    double slip, expected, re, gas_speed, voidage;
    long steps;
} bdl_verify_terminal;
/// One sphere settling through gas in a periodic box 24 d wide and 32 d tall on `cells` x `cells`
/// x 4/3 `cells` cells (a multiple of 3), its volume and drag spread by a kernel of half-width
/// 6 d. The mean slip over the last third of 6 tau (tau = v_t/g) against the drag law's at the
/// particle's voidage.
bdl_verify_terminal bdl_verify_terminal_slip(double d, double rho_p, bdl_drag_law law, int cells);
/// Slip s with K(eps, s) s = target: the drag law's terminal slip, by bisection.
double bdl_verify_implied_slip(bdl_drag_law law, double eps, double d, double rho, double mu,
                               double target, double hi);

/// Ergun's pressure gradient [Pa/m].
double bdl_verify_ergun(double eps, double U, double d, double rho, double mu);
/// Packed bed of 1400 2 mm beads, `cells_z` layers (cells_z/5 per side across): the measured
/// interior pressure gradient over Ergun's at each of `n` superficial velocities U[k] (ratio[k]),
/// with the mean voidage of the layers used. Returns BDL_OK or the failing step's result.
bdl_result bdl_verify_packed_bed(int cells_z, const double *U, int n, double *ratio,
                                 double *eps_mean, long *steps);

/// The particle momentum balance of a slugging bed, per base area [Pa], time-averaged over a
/// window: the pressure drop between the lowest and highest cell layers less the gas column
/// between them, the beads' weight less buoyancy, the walls' vertical force on the beads (their
/// contact forces summed: every pair's action and reaction cancel), and the rate of change of
/// the beads' vertical momentum. residual = pressure - weight + wall - momentum_rate, 0 when the
/// pressure drop carries exactly what the gas does to the beads. It splits into the gas's part,
/// gas_residual = pressure - fluid (fluid: the gas's force on the beads less their buoyancy in a
/// gas at rest, so that the gas's momentum budget — its acceleration, the walls' shear — shows
/// here), and the beads' part, residual - gas_residual (Newton for the beads as integrated).
/// inflow_momentum: the gas's momentum flux in through the inlet less out through the outlet,
/// rho U^2 (mean 1/eps of the lowest layer - 1), which lowers the pressure drop the gas needs.
typedef struct bdl_verify_balance {
    double pressure, weight, wall, momentum_rate, residual;
    double fluid, gas_residual, inflow_momentum;
    long steps;
} bdl_verify_balance;
/// scenes/fluidized_bed.ini's slugging slot (800 beads of 3 mm, air at 3.2 m/s) with its floor
/// on the inlet plane (raised 0) or `raised` gas cells above it, averaged over `window` seconds
/// after `settle` seconds. BDL_ERR_UNSTABLE if a bead leaves the slot.
bdl_result bdl_verify_bed_balance(int raised, double settle, double window,
                                  bdl_verify_balance *out);

/// Minimum fluidization from a decreasing then an increasing velocity sweep (dwell seconds per
/// velocity): U_mf of each and Wen-Yu's for the same beads [m/s]. With `table`, prints the sweeps.
bdl_result bdl_verify_umf(double dwell, double *umf_down, double *umf_up, double *wen_yu, int table,
                          long *steps);

typedef struct bdl_verify_settling {
    double measured, expected, vt, re_t, n;
    long steps;
} bdl_verify_settling;
/// Hindered settling of a periodic suspension at solids fraction phi (Wen-Yu), the gas stepped
/// every `substeps` particle steps (0: the automatic gas step): the settling speed relative to
/// the zero-volume-flux frame against the drag law's.
bdl_result bdl_verify_suspension(double phi, int substeps, bdl_verify_settling *out);

// ---- parcels (verify_parcels.c) ----

/// Hindered settling of parcels (MP-PIC, model A, the patankar drag) in a closed column one cell
/// across at solids fraction phi: `per_cell` parcels per cell, `cells` along the column, step
/// dt. The speed of the top interface (from the solids above a level in the suspension) by least
/// squares over 5-35 s, against the model's own v = eps w, K(eps, w) w = eps (rho_p - rho) g.
bdl_result bdl_verify_parcel_settling(int per_cell, int cells, double dt, double phi, int seed,
                                      bdl_verify_settling *out);
/// Bimodal sedimentation of parcels (the paper's sec. 4.1 in a column one cell across): the heavy
/// front's speed (least squares from 20 s to t_end) and the light parcels' mean speed in the
/// light-only zone above it (from 0.3 t_end), which the top interface moves with [m/s].
typedef struct bdl_verify_bimodal {
    double heavy_front, light_zone;
    long steps;
} bdl_verify_bimodal;
bdl_result bdl_verify_parcel_bimodal(int case_b, double t_end, bdl_verify_bimodal *out);

/// The Boycott effect (the paper's sec. 4.2): the 35-degree column of scenes/parcels_inclined.ini
/// (gravity tilted, 18 111 parcels at random, 32 x 72 cells, dt 0.005 s with up to 8 liquid
/// sub-steps), or with `vertical` the same column
/// upright. The interface's axial position y(t) on the column's centre line (the crossing of
/// half the initial solids fraction), every 20 s up to t_end, against the Ponder-Nakamura-
/// Kuroda estimate y(t) = (y0 + b / (sin a cos a)) exp(-v0 t sin a / b) - b / (sin a cos a)
/// (digest of seed 001, sec. 4.2) with v0 the model's hindered speed at phi 0.1; and against the
/// same estimate above the sediment: the clear liquid made under the interface and the
/// downward-facing wall above the sediment only, dy/dt = -v0 (1 / cos a + S sin a / b), where
/// the suspension's length S = (y - r y0) / (1 - r), r = phi / theta_sed, keeps phi and the
/// sediment below it takes the settled solids at model A's mean theta_sed (its 1-D balance under
/// gravity's axial part): y(t) = r y0 - s' + (y0 (1 - r) + s') exp(-v0 t sin a / (b (1 - r))),
/// s' = (1 - r) b / (sin a cos a), down to r y0 (all settled). Without the sediment the
/// estimate falls below the height of the settled solids themselves (8.4 cm at 800 s; the solids
/// fill at least phi y0 / theta_cs = 8.7 cm of the axis).
#define BDL_VERIFY_BOYCOTT_SAMPLES 64
typedef struct bdl_verify_boycott {
    double v0;                                ///< the model's hindered speed [m/s]
    int samples;                              ///< taken, every 20 s from 20 s
    double t[BDL_VERIFY_BOYCOTT_SAMPLES];     ///< [s]
    double y[BDL_VERIFY_BOYCOTT_SAMPLES];     ///< measured [m]
    double y_pnk[BDL_VERIFY_BOYCOTT_SAMPLES]; ///< PNK (vertical: y0 - v0 t) [m]
    double y_sed[BDL_VERIFY_BOYCOTT_SAMPLES]; ///< PNK above the sediment [m]
    double theta_sed;                         ///< model A's sediment's mean solids fraction
    double worst;                             ///< largest |y / y_sed - 1| from 100 s on
    double worst_pnk;                         ///< largest |y / y_pnk - 1| from 100 to 500 s
    double speed_200;                         ///< mean axial speed over the first 200 s [m/s]
    double speed_200_pnk;                     ///< PNK's [m/s]
    long steps;
} bdl_verify_boycott;
bdl_result bdl_verify_parcel_boycott(int vertical, double t_end, bdl_verify_boycott *out);

/// Solids volume of the particles (parcels) above height z [m^3].
double bdl_verify_solids_above(const bdl_world *w, double z);
/// Height of the highest crossing of the horizontally averaged solids fraction through `level`,
/// from the top down, interpolated between cell centres [m].
double bdl_verify_parcel_interface(const bdl_world *w, double level);

/// Discharge of a flat-bottomed silo through a central orifice (scenes/silo_discharge.ini):
/// `count` glass beads of d = 3 mm in a cylinder 72 mm across settle on a floor (a mesh annulus
/// written to a temporary OBJ file) held shut by a plug taken away at t_open = 0.5 s. The bulk
/// density rho_b is measured in the settled bed at t_open (centres in r < 25 mm, 10 < z < 40 mm);
/// the rate W is the least-squares slope of the mass out (removed 30 mm below the floor) over
/// [t_open + 0.2 s, t_end]; Beverloo's W = C rho_b sqrt(g) (D - k d)^2.5 with C = 0.58, k = 1.5
/// (Beverloo, Leniger & van de Velde 1961; Nedderman 1992, ch. 10).
typedef struct bdl_verify_silo {
    double orifice;        ///< D [m]
    double bulk_density;   ///< rho_b [kg/m^3]
    double rate;           ///< W measured [kg/s]
    double rate_beverloo;  ///< W predicted [kg/s]
    long out;              ///< beads removed
    long left;             ///< beads in the silo at the end
    double mass_imbalance; ///< |mass in + mass out - mass at start| / mass at start
    long steps;
} bdl_verify_silo;
bdl_result bdl_verify_silo_discharge(double orifice, long count, double t_end,
                                     bdl_verify_silo *out);

/// A rotating drum (scenes/rotating_drum.ini): 2600 glass beads of 3 mm fill 39 % of a drum of
/// radius 50 mm, periodic along its axis (y, 20 mm), turning at `omega` [rad/s] from 0.3 s. The
/// dynamic angle of repose is the slope of a line fitted to the free surface (the highest centre
/// in each 6 mm bin of x across the middle 50 mm) every 0.1 s from 1.2 to 2.5 s; the wall drives
/// the bed without slip when the beads touching the drum meet it at its speed: the tangential
/// velocity of their surface at the wall (centre plus spin) over omega R, in the drum's bottom
/// quarter. The drum's wall
/// friction is 1.0 (a rough drum; at 0.5 the bed slips back at 3 rad/s).
typedef struct bdl_verify_drum {
    double friction, omega; ///< of the beads and the drum; [rad/s]
    double angle;           ///< mean dynamic angle of repose [degrees]
    double angle_sd;        ///< its standard deviation over the samples [degrees]
    double carried;         ///< mean speed ratio of the beads touching the drum's bottom quarter
    int samples;
    long steps;
} bdl_verify_drum;
bdl_result bdl_verify_drum_repose(double friction, double omega, bdl_verify_drum *out);

/// Janssen's silo (scenes/silo_janssen.ini): `count` glass beads of 3 mm settle in a cylinder
/// 40 mm across on a flat floor (wall friction 0.5), which creeps down at 5 mm/s from 0.6 s to
/// the end at 1 s, so that the beads slide down the wall. Averaged over the last 0.1 s: the
/// floor's force, the bulk density in the core, the fill height H = mass / (rho_b A), and in
/// slabs of the bed's middle half the ratio K = sigma_h / sigma_v of the wall's normal stress to
/// the vertical stress the column above carries (its weight less the wall's friction on it), and
/// the friction the wall mobilises, |tau_w| / sigma_h. Janssen (1895): the floor carries
/// rho_b g A lambda (1 - exp(-H / lambda)), lambda = R / (2 mu_w K).
typedef struct bdl_verify_janssen {
    long count;
    double height;       ///< H [m]
    double bulk_density; ///< rho_b [kg/m^3]
    double floor_mass;   ///< the floor's force over g [kg]
    double fill_mass;    ///< the beads' mass [kg]
    double k;            ///< K measured (NAN when the bed is too shallow for slabs)
    double mobilised;    ///< |tau_w| / sigma_h at the wall of the same slabs
    long steps;
} bdl_verify_janssen;
bdl_result bdl_verify_janssen_silo(long count, bdl_verify_janssen *out);

/// A shear cell of frictionless spheres (scenes/shear_cell.ini: 5.3 mm, 1395 kg/m^3, k_n = 6e5
/// N/m, restitution e): with `walls` 0 between Lees–Edwards images at 100/s in `box` (0: the
/// thesis's 72 x 48 x 48 mm), else in the thesis's box (`box` ignored) between the plates of
/// scenes/shear_cell_walls.ini moving at -+2.4 m/s (the bulk 12 mm from each). The bulk's
/// rheology.csv quantities averaged every 2 ms from `from` to `to`, beside Lun et al. (1984) at
/// its solids fraction and shear rate, and their pressure and shear stress at its own
/// temperature.
typedef struct bdl_verify_shear_setup {
    double solids_fraction, restitution;
    int walls;
    double box[3]; ///< Lees–Edwards only [m]; zeros: 72 x 48 x 48 mm
    double from, to;
    /// Lees–Edwards only: background damping b [1/s] (a medium moving with the shear)
    double damping;
} bdl_verify_shear_setup;
typedef struct bdl_verify_shear {
    double solids_fraction, shear_rate, temperature, pressure, shear_stress, n1;
    double lun_temperature, lun_pressure, lun_shear_stress; ///< at the run's nu and shear rate
    double lun_pressure_at_t, lun_shear_stress_at_t;        ///< at the run's nu, rate and T
    long samples, steps;
} bdl_verify_shear;
bdl_result bdl_verify_shear_cell(const bdl_verify_shear_setup *set, bdl_verify_shear *out);
/// Janssen's floor mass for a fill of height H [kg].
double bdl_verify_janssen_mass(double bulk_density, double radius, double mu_wall, double k,
                               double height);

// ---- the two-fluid model (verify_tfm.c) ----

struct bdl_solids_def;
/// Haff's time scale of a homogeneous cooling state at solids fraction eps from theta0: theta =
/// theta0 / (1 + t / tau)^2 with tau = 3 rho eps / (gamma / theta^(3/2)) / sqrt(theta0), gamma
/// Lun et al.'s (1984) collisional dissipation [s].
double bdl_verify_tfm_cooling_time(double eps, double theta0, const struct bdl_solids_def *sd);
/// Goldschmidt's beads at rest at solids fraction 0.3 from theta0 = 0.01 m^2/s^2, per_tau full
/// steps of solids and gas per tau, to t = 3 tau: `error` |theta / theta_Haff - 1| (Haff: theta0
/// / 16).
bdl_result bdl_verify_tfm_cooling(int per_tau, double *error, long *steps);

/// A settling column: 100 um glass (Stokes drag) at solids fraction 0.3 in the lower half of a
/// closed column 0.2 m tall of `cells` cells, from rest, to 0.5 s, dt a quarter of the cell
/// crossing time at the fall speed on 20 cells, times (20 / cells)^2.
typedef struct bdl_verify_sediment {
    double interface;  ///< the suspension's top at 0.08 s: 0.05 m + solids volume above / 0.3 [m]
    double expected;   ///< Kynch: 0.1 m less the fall of a uniform suspension from rest
    double fall_speed; ///< the suspension's terminal fall speed [m/s]
    double eps_peak;   ///< largest solids fraction after any step
    double eps_low;    ///< smallest
    double eps_bed;    ///< the bottom cell's at 0.5 s
    double eps_bed_expected; ///< Schaeffer's fraction that carries the bed's buoyant weight there
    double volume_drift;     ///< relative change of the solids volume
    double speed_end;        ///< largest solids speed at 0.5 s [m/s]
    long steps;
} bdl_verify_sediment;
bdl_result bdl_verify_tfm_settling(int cells, bdl_verify_sediment *out);

/// The granular energy's transport equation against a manufactured solution: solids at rest in a
/// layer periodic along x (0.04 m, `cells` cells), two cells of 1 cm between Johnson & Jackson
/// walls (phi' 0.3, e_w 0.6), fraction eps(x) = 0.3 + 0.05 sin(2 pi x / L) and temperature theta(x)
/// = C / (eps^2 g0), which keeps Syamlal's pressure uniform (the solids stay at rest); the source
/// that makes theta(x) steady given to the cells; 4 s of steps of 1 ms.
typedef struct bdl_verify_energy {
    double error;            ///< largest |theta / theta(x) - 1| of the cells at the end
    double conduction_share; ///< the conduction's largest share of the source
    double speed;            ///< largest solids speed over the run [m/s]
    long steps;
} bdl_verify_energy;
bdl_result bdl_verify_tfm_energy(int cells, bdl_verify_energy *out);

#endif
