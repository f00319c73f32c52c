// bedlam check SCENE — validate, report the active modules, stability limits and cost.
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>

#include "app/app.h"
#include "core/log.h"
#include "core/timer.h"
#include "dem/create.h"
#include "run/guards.h"
#include "solids/phase.h"
#include "world/world.h"

static const char check_usage[] =
    "usage: bedlam check SCENE [--set SECTION.KEY=VALUE]... [--threads N]\n"
    "\n"
    "Parses and validates SCENE, estimates its memory and steps against [guards] max_memory and\n"
    "max_steps before anything is built, builds its particles, and prints the active modules, the\n"
    "contact time of every species pair and wall, the estimate, the stable time-step limit, and\n"
    "the estimated cost of the run (measured on a few steps). A scene of parcels (MP-PIC) has no\n"
    "contacts: it prints the parcels, the real particles they stand for, the parcels per filled\n"
    "gas cell, the model A stress and the parcels' stable step instead; a scene with a solids\n"
    "phase ([solids], the two-fluid model) its bed, the gas's expected stable step and the cost\n"
    "in cell-steps per second. Exit codes: 0 valid, 2\n"
    "invalid (the message names file, line, key, value and the allowed range or limit).\n";

/// One line of the contacts table: the pair, its contact time and parameters.
static void print_contact(const bdl_world *w, const char *a, const char *b, double tc,
                          const bdl_contact_params *cp)
{
    printf("  %-12s - %-12s t_c = %-10.4g s  e = %-5.3g mu = %-5.3g mu_r = %-5.3g %s = %.4g\n", a,
           b, tc, cp->restitution, cp->friction, cp->rolling_friction, w->hertz ? "c" : "zeta",
           cp->damping);
}

static void print_contacts(const bdl_world *w, double v_ref)
{
    const bdl_scene *s = &w->scene;
    int ns = s->species_count;
    if (w->hertz)
        printf("contacts (Hertz times at impact speed %.3g m/s):\n", v_ref);
    else
        printf("contacts (linear springs: the times do not depend on the impact speed):\n");
    for (int a = 0; a < ns; ++a) {
        const char *name = s->species[a].name;
        for (int b = a; b < ns; ++b)
            print_contact(w, name, s->species[b].name, bdl_world_pair_contact_time(w, a, b, v_ref),
                          &w->pair_params[a * ns + b]);
        for (int k = 0; k < s->wall_count; ++k) {
            char wall[128];
            snprintf(wall, sizeof wall, "wall %-7s", s->walls[k].name);
            print_contact(w, name, wall, bdl_world_wall_contact_time(w, a, k, v_ref),
                          &w->wall_params[k * ns + a]);
        }
    }
}

/// The particles' module: DEM contacts and walls, or parcels.
static void print_solids_module(const bdl_world *w)
{
    const bdl_scene *s = &w->scene;
    if (w->parcels) {
        char parcels[512];
        bdl_world_parcels_describe(w, parcels, sizeof parcels);
        printf("  %s; no contacts, no walls: the domain's sides bound them\n", parcels);
        return;
    }
    if (w->solids) {
        char solids[1024];
        bdl_world_solids_describe(w, solids, sizeof solids);
        printf("  %s; no particles, no walls: the domain's sides bound it\n", solids);
        return;
    }
    printf("  dem: %s normal law%s; %s%s\n", w->hertz ? "Hertz-Mindlin" : "linear spring-dashpot",
           w->hertz ? (s->damping == BDL_DAMPING_EXACT ? " with exact restitution damping"
                                                       : " with closed-form damping")
                    : "",
           w->friction ? "tangential spring with history, Coulomb friction"
                       : "frictionless (no tangential history)",
           w->rolling ? "; rolling resistance" : "");
    printf("  walls: %d (%ld surfaces)%s\n", s->wall_count, bdl_wall_surfaces(&w->walls),
           bdl_walls_max_speed(&w->walls) > 0 ? ", moving" : "");
}

/// Random sequential insertion of equal spheres jams near this solids fraction (Feder 1980;
/// Talbot, Tarjus & Schaaf 2000 give 0.38 in three dimensions).
#define RSA_JAMMING 0.38

/// Warnings on what the scene allows but will not work as meant: gas cells smaller than the
/// particles (the voidage of a cell then jumps by whole particles), random fills of spheres above
/// the fraction random insertion can reach.
static void print_warnings(const bdl_world *w)
{
    const bdl_scene *s = &w->scene;
    double d_max = 0.0;
    for (int k = 0; k < s->species_count; ++k)
        d_max = fmax(d_max, bdl_species_max_diameter(&s->species[k]));
    if (w->gas && !w->parcels) {
        const bdl_grid *g = &w->gas->grid;
        for (int a = 0; a < 3; ++a)
            if (g->n[a] > 1 && g->h[a] < d_max)
                printf("  warning: gas cells are %.3g m along %c, smaller than the largest "
                       "particle (%.3g m): a cell's voidage jumps by whole particles; cells of "
                       "1.5-3 diameters are usual for CFD-DEM\n",
                       g->h[a], "xyz"[a], d_max);
    }
    for (int c = 0; c < s->create_count; ++c) {
        const bdl_create_def *cd = &s->creates[c];
        if (cd->kind != BDL_CREATE_RANDOM || w->parcels) // parcels overlap: no jamming
            continue;
        const bdl_species_def *sp = &s->species[cd->species];
        const double vp = bdl_species_volume(sp, sp->diameter);
        const double vol = bdl_create_region_volume(cd);
        const double phi =
            cd->volume_fraction > 0.0 ? cd->volume_fraction : (double)cd->count * vp / vol;
        if (sp->shape == BDL_SHAPE_SPHERE && phi > RSA_JAMMING)
            printf("  warning: [create %s] asks for a solids fraction of %.3g of its region; "
                   "random insertion jams near %.2g, so the fill will stop short and the run be "
                   "refused: fill a taller region and let the bed settle, or use type = "
                   "lattice\n",
                   cd->name, phi, RSA_JAMMING);
    }
}

static void print_modules(const bdl_world *w)
{
    const bdl_scene *s = &w->scene;
    printf("scene: %s — valid\n", s->path);
    printf("modules:\n");
    print_solids_module(w);
    if (w->container >= 0)
        printf("  frame: the vibrating container [wall %s]; its walls stand still and particles "
               "and gas feel gravity plus the inertial acceleration\n",
               s->walls[w->container].name);
    char gas[384];
    bdl_world_gas_describe(w, gas, sizeof gas);
    printf("  gas: %s\n", gas);
    if (s->sink_count > 0)
        printf("  sinks: %d (particles entering them are removed and counted)\n", s->sink_count);
    printf("  periodic axes: %s%s%s%s\n", s->periodic[0] ? "x " : "", s->periodic[1] ? "y " : "",
           s->periodic[2] ? "z " : "",
           s->periodic[0] || s->periodic[1] || s->periodic[2] ? "" : "none");
    if (w->solids) {
        char bed[512];
        bdl_world_solids_bed(w, bed, sizeof bed);
        printf("solids at start: %.4g m^3, %s\n", bdl_solids_volume(w->solids, -1), bed);
    } else
        printf("%s at start: %ld (species: %d)\n", w->parcels ? "parcels" : "particles",
               w->particles.count, s->species_count);
    print_warnings(w);
}

/// A world of parcels: what they stand for, how they fill the gas's cells, the stress that keeps
/// them from close packing.
static bdl_result print_parcels(const bdl_world *w)
{
    bdl_parcels_census c;
    if (bdl_world_parcels_census(w, &c) != BDL_OK)
        return BDL_ERR_NOMEM;
    const bdl_parcels_def *d = &w->scene.parcels.def;
    printf("parcels: %ld standing for %.4g real particles (%.4g per parcel on average)\n",
           c.parcels, c.real_particles, c.parcels > 0 ? c.real_particles / c.parcels : 0.0);
    printf("  parcels per filled cell: mean %.3g, min %.0f, max %.0f (initial deposit: centres "
           "in %ld of the %ld gas cells)\n",
           c.per_cell_mean, c.per_cell_min, c.per_cell_max, c.filled_cells, c.cells);
    printf("  largest solids fraction of a cell: %.3g (the kernels' deposit; close packing "
           "theta_cs = %g)\n",
           c.max_solids, d->close_packing);
    const double theta = d->close_packing - d->stress_floor;
    printf("  model A stress at close packing minus the floor: tau(%.4g) = %.4g Pa (P_s = %g Pa, "
           "beta = %g, floor = %g); the most it gives\n",
           theta, bdl_parcels_stress(d, theta), d->stress_pressure, d->stress_exponent,
           d->stress_floor);
    return BDL_OK;
}

/// The step against the smallest contact time and the guards' fractions of it.
static void print_contact_step(const bdl_world *w)
{
    const bdl_scene *s = &w->scene;
    printf("time step: dt = %.4g s = t_c / %.1f (smallest contact time %.4g s)\n", w->dt,
           1.0 / w->contact_time_dt_ratio, w->contact_time);
    printf("  stable limit: dt <= %.4g s ([guards] dt_refuse = %g t_c); accurate below %.4g s "
           "(dt_warn = %g t_c)\n",
           s->guards.dt_refuse * w->contact_time, s->guards.dt_refuse,
           s->guards.dt_warn * w->contact_time, s->guards.dt_warn);
}

/// The time step against its limits; an error when the guards refuse it.
static bdl_result print_time_step(const bdl_world *w)
{
    char message[1024], warning[1024];
    bdl_result r = bdl_guards_check_dt(w, message, sizeof message, warning, sizeof warning);
    if (w->parcels) {
        const double stable = bdl_world_parcels_stable_dt(w);
        printf("time step: dt = %.4g s = %.3g of the parcels' stable step %.4g s (%s); refused "
               "above twice it",
               w->dt, w->dt / stable, stable, bdl_world_parcels_stable_basis(w));
        const double collision = bdl_world_parcels_collision_dt(w);
        if (isfinite(collision))
            printf(", and dt / substeps below %.4g s for the collisions", collision);
        printf("\n");
    } else if (w->solids) {
        const double stable = bdl_world_inflow_gas_dt(w);
        if (w->scene.solids.courant > 0.0)
            printf("time step: adaptive, Courant number %.3g ([solids] courant), at most %.4g s; "
                   "the first %.4g s (the gas's expected stable step %.4g s)\n",
                   w->scene.solids.courant, w->scene.dt, w->dt, stable);
        else
            printf("time step: dt = %.4g s = %.3g of the gas's expected stable step %.4g s (CFL "
                   "1/2 for the inflow through the packed bed, plus 0.5 m/s for bubbles); refused "
                   "above twice it\n",
                   w->dt, w->dt / stable, stable);
    } else {
        print_contact_step(w);
    }
    if (r != BDL_OK)
        fprintf(stderr, "error: %s\n", message);
    else if (warning[0])
        printf("  warning: %s\n", warning);
    return r;
}

/// What the scene was estimated to need before anything was built, against the limits.
static void print_resources(const bdl_world *w)
{
    const bdl_budget *b = &w->budget;
    const bdl_guard_def *g = &w->scene.guards;
    if (w->solids)
        printf("resources (estimated before anything was built): %.3g gas cells (ghost layers "
               "included)\n",
               b->gas_cells);
    else if (w->parcels)
        printf("resources (estimated before anything was built): %.3g parcels, %.3g gas cells "
               "(ghost layers included)\n",
               b->particles, b->gas_cells);
    else
        printf("resources (estimated before anything was built): %.3g particles, %.3g neighbour "
               "pairs, %.3g gas cells (ghost layers included)\n",
               b->particles, b->pairs, b->gas_cells);
    printf("  memory: about %.3g MB (particles and pairs %.3g MB, gas %.3g MB, images %.3g MB, "
           "fields %.3g MB); limit [guards] max_memory = %.3g MB%s\n",
           b->bytes / 1e6, b->particle_bytes / 1e6, b->gas_bytes / 1e6, b->image_bytes / 1e6,
           b->fields_bytes / 1e6, b->max_memory / 1e6,
           g->max_memory > 0.0 ? "" : " (80 % of the physical memory)");
    printf("  steps: %.4g; limit [guards] max_steps = %g\n", b->steps, g->max_steps);
}

/// The work of a particle in a settled bed, in units of a free particle's, less one: the pairs
/// it lists (about 3 contacts of a half list, and the skin's near ones) at about a particle's
/// cost each. Fitted to the ratio of the whole run's time to the trial's for three scenes whose
/// beds start loose (silo_discharge 4.5, rotating_drum 5.5, settling_box 4.1, with 0.9, 1.9 and
/// 0.1 pairs a particle in the trial): their runs then come out within 17 % of the estimate (95,
/// 67, 54 s estimated; 91, 77, 46 s run, alone on two cores).
#define PACKED_PAIRS 4.7

/// The cost of the run, from timed steps of this very scene after 20 untimed ones (the first
/// list build and the first touches). A step costs about the same per particle as per listed
/// pair (dem/contact_force.c), so the time measured on the particles and pairs of now is scaled
/// to the particles the scene will hold, packed: a bed that starts as a falling cloud is not
/// taken for a cheap one.
static void print_cost(bdl_world *w)
{
    const bdl_scene *s = &w->scene;
    const double steps_total = ceil(w->budget.steps);
    for (int k = 0; k < 20; ++k)
        if (bdl_world_step(w) != BDL_OK) {
            bdl_error("%s", w->failure);
            return;
        }
    double t0 = bdl_wall_seconds();
    long trial = 0;
    while (trial < 5000 && (trial < 5 || bdl_wall_seconds() - t0 < 0.5)) {
        if (bdl_world_step(w) != BDL_OK) {
            bdl_error("%s", w->failure);
            break;
        }
        ++trial;
    }
    double per_step = (bdl_wall_seconds() - t0) / (double)(trial > 0 ? trial : 1);
    if (w->solids) {
        const bdl_grid *g = &w->gas->grid;
        const double cells = (double)g->n[0] * g->n[1] * g->n[2], wall = per_step * steps_total;
        printf("cost: %.0f steps to t = %g s%s; measured %.3g cell-steps/s on %d threads (%.0f "
               "cells) -> about %.3g s wall time (%.3gx real time)\n",
               steps_total, s->end_time,
               s->solids.courant > 0.0 ? " at the first step's size (the adaptive step grows)" : "",
               cells / per_step, omp_get_max_threads(), cells, wall, s->end_time / wall);
        return;
    }
    long n = w->particles.count > 0 ? w->particles.count : 1;
    double rate = (double)n / per_step;
    // Pouring scenes grow: cost the run at the particle count the scene will reach.
    long total = bdl_create_estimate_total(s->creates, s->create_count, s->species);
    if (total < n)
        total = n;
    double work_now = (double)n, work_end = (double)total;
    if (!w->parcels) {
        work_now += (double)w->neighbor.pair_count;
        work_end *= 1.0 + PACKED_PAIRS;
        if (work_end < work_now)
            work_end = work_now;
    }
    double wall = per_step * work_end / work_now * steps_total;
    const char *what = w->parcels ? "parcel" : "particle";
    printf("cost: %.0f steps to t = %g s; measured %.3g %s-steps/s on %d threads (%ld %ss, "
           "%.1f pairs each) -> about %.3g s wall time for %ld %ss%s (%.3gx real time)\n",
           steps_total, s->end_time, rate, what, omp_get_max_threads(), n, what,
           w->parcels ? 0.0 : (double)w->neighbor.pair_count / (double)n, wall, total, what,
           w->parcels ? "" : " packed", s->end_time / wall);
}

bdl_result bdl_cmd_check(int argc, char **argv)
{
    bdl_scene_opts o;
    bdl_result r = bdl_parse_scene_opts(argc, argv, check_usage, &o);
    if (r != BDL_OK || o.help)
        return r;
    if (o.threads > 0)
        omp_set_num_threads(o.threads);
    bdl_world *w = NULL;
    if ((r = bdl_load_world(o.scene, o.overrides, o.override_count, &w)) != BDL_OK)
        return r;
    print_modules(w);
    if (!w->parcels && !w->solids)
        print_contacts(w, bdl_world_reference_speed(w));
    else if (w->parcels && (r = print_parcels(w)) != BDL_OK) {
        bdl_world_destroy(w);
        return r;
    }
    print_resources(w);
    if ((r = print_time_step(w)) == BDL_OK)
        print_cost(w);
    bdl_world_destroy(w);
    return r;
}
