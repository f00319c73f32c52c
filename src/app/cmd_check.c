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
#include "world/world.h"

static const char check_usage[] =
    "usage: bedlam check SCENE [--set SECTION.KEY=VALUE]... [--threads N]\n"
    "\n"
    "Parses and validates SCENE, estimates its memory and steps against [guards] max_memory and\n"
    "max_steps before anything is built, builds its particles, and prints the active modules, the\n"
    "contact time of every species pair and wall, the estimate, the stable time-step limit, and\n"
    "the estimated cost of the run (measured on a few steps). Exit codes: 0 valid, 2 invalid (the\n"
    "message names file, line, key, value and the allowed range or limit).\n";

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

static void print_modules(const bdl_world *w)
{
    const bdl_scene *s = &w->scene;
    printf("scene: %s — valid\n", s->path);
    printf("modules:\n");
    if (w->parcels) {
        char parcels[512];
        bdl_world_parcels_describe(w, parcels, sizeof parcels);
        printf("  %s\n", parcels);
    } else
        printf("  dem: %s normal law%s; %s%s\n",
               w->hertz ? "Hertz-Mindlin" : "linear spring-dashpot",
               w->hertz ? (s->damping == BDL_DAMPING_EXACT ? " with exact restitution damping"
                                                           : " with closed-form damping")
                        : "",
               w->friction ? "tangential spring with history, Coulomb friction"
                           : "frictionless (no tangential history)",
               w->rolling ? "; rolling resistance" : "");
    if (!w->parcels)
        printf("  walls: %d (%d surfaces)%s\n", s->wall_count, w->walls.prim_count,
               bdl_walls_max_speed(&w->walls) > 0 ? ", moving" : "");
    if (w->container >= 0)
        printf("  frame: the vibrating container [wall %s]; its walls stand still and particles "
               "and gas feel gravity plus the inertial acceleration\n",
               s->walls[w->container].name);
    char gas[256];
    bdl_world_gas_describe(w, gas, sizeof gas);
    printf("  gas: %s\n", gas);
    printf("  periodic axes: %s%s%s%s\n", s->periodic[0] ? "x " : "", s->periodic[1] ? "y " : "",
           s->periodic[2] ? "z " : "",
           s->periodic[0] || s->periodic[1] || s->periodic[2] ? "" : "none");
    printf("particles at start: %ld (species: %d)\n", w->particles.count, s->species_count);
}

/// The time step against its limits; an error when the guards refuse it.
static bdl_result print_time_step(const bdl_world *w)
{
    const bdl_scene *s = &w->scene;
    char message[1024], warning[1024];
    bdl_result r = bdl_guards_check_dt(w, message, sizeof message, warning, sizeof warning);
    if (w->parcels) {
        printf("time step: dt = %.4g s; parcels: at most twice the stable step %.4g s (CFL 1/2 "
               "for the inflow through close packing, the gas's viscous limit)",
               w->dt, bdl_world_parcels_stable_dt(w));
        const double collision = bdl_world_parcels_collision_dt(w);
        if (isfinite(collision))
            printf(", and below %.4g s for the collisions", collision);
        printf("\n");
    } else {
        printf("time step: dt = %.4g s = t_c / %.1f (smallest contact time %.4g s)\n", w->dt,
               1.0 / w->contact_time_dt_ratio, w->contact_time);
        printf("  stable limit: dt <= %.4g s ([guards] dt_refuse = %g t_c); accurate below %.4g "
               "s (dt_warn = %g t_c)\n",
               s->guards.dt_refuse * w->contact_time, s->guards.dt_refuse,
               s->guards.dt_warn * w->contact_time, s->guards.dt_warn);
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
    printf("resources (estimated before anything was built): %.3g particles, %.3g neighbour "
           "pairs, %.3g gas cells (ghost layers included)\n",
           b->particles, b->pairs, b->gas_cells);
    printf("  memory: about %.3g MB (particles and pairs %.3g MB, gas %.3g MB, images %.3g MB); "
           "limit [guards] max_memory = %.3g MB%s\n",
           b->bytes / 1e6, b->particle_bytes / 1e6, b->gas_bytes / 1e6, b->image_bytes / 1e6,
           b->max_memory / 1e6, g->max_memory > 0.0 ? "" : " (80 % of the physical memory)");
    printf("  steps: %.4g; limit [guards] max_steps = %g\n", b->steps, g->max_steps);
}

/// The cost of the run, from a few timed steps of this very scene.
static void print_cost(bdl_world *w)
{
    const bdl_scene *s = &w->scene;
    const double steps_total = ceil(w->budget.steps);
    double t0 = bdl_wall_seconds();
    long trial = 0;
    while (trial < 2000 && (trial < 5 || bdl_wall_seconds() - t0 < 0.5)) {
        if (bdl_world_step(w) != BDL_OK) {
            bdl_error("%s", w->failure);
            break;
        }
        ++trial;
    }
    double per_step = (bdl_wall_seconds() - t0) / (double)(trial > 0 ? trial : 1);
    long n = w->particles.count > 0 ? w->particles.count : 1;
    double rate = (double)n / per_step;
    // Pouring scenes grow: cost the run at the particle count the scene will reach.
    long total = bdl_create_estimate_total(s->creates, s->create_count, s->species);
    if (total < n)
        total = n;
    double wall = (double)total / rate * steps_total;
    printf("cost: %.0f steps to t = %g s; measured %.3g particle-steps/s on %d threads (%ld "
           "particles) -> about %.3g s wall time for %ld particles (%.3gx real time)\n",
           steps_total, s->end_time, rate, omp_get_max_threads(), n, wall, total,
           s->end_time / wall);
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
    if (!w->parcels) // parcels: their model's parameters are in the modules
        print_contacts(w, bdl_world_reference_speed(w));
    print_resources(w);
    if ((r = print_time_step(w)) == BDL_OK)
        print_cost(w);
    bdl_world_destroy(w);
    return r;
}
