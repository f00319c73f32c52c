// bedlam check SCENE — validate, report the active modules, stability limits and cost.
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>

#include "app/app.h"
#include "core/timer.h"
#include "dem/create.h"
#include "run/guards.h"
#include "world/world.h"

static const char check_usage[] =
    "usage: bedlam check SCENE [--set SECTION.KEY=VALUE]... [--threads N]\n"
    "\n"
    "Parses and validates SCENE, builds its particles, and prints the active modules, the contact\n"
    "time of every species pair and wall, the stable time-step limit, and the estimated cost of\n"
    "the run (measured on a few steps). Exit codes: 0 valid, 2 invalid (the message names file,\n"
    "line, key, value and the allowed range).\n";

static void print_contacts(const bdl_world *w, double v_ref)
{
    const bdl_scene *s = &w->scene;
    int ns = s->species_count;
    if (w->hertz)
        printf("contacts (Hertz times at impact speed %.3g m/s):\n", v_ref);
    else
        printf("contacts (linear springs: the times do not depend on the impact speed):\n");
    for (int a = 0; a < ns; ++a) {
        const bdl_species_def *sa = &s->species[a];
        double da = sa->size_dist == BDL_SIZE_SINGLE ? sa->diameter : sa->diameter_min;
        double ma = sa->density * 3.14159265358979323846 / 6.0 * da * da * da;
        for (int b = a; b < ns; ++b) {
            const bdl_species_def *sb = &s->species[b];
            double db = sb->size_dist == BDL_SIZE_SINGLE ? sb->diameter : sb->diameter_min;
            double mb = sb->density * 3.14159265358979323846 / 6.0 * db * db * db;
            const bdl_contact_params *cp = &w->pair_params[a * ns + b];
            double tc =
                bdl_contact_time(cp, s->law, ma * mb / (ma + mb), 0.5 * da * db / (da + db), v_ref);
            printf(
                "  %-12s - %-12s t_c = %-10.4g s  e = %-5.3g mu = %-5.3g mu_r = %-5.3g %s = %.4g\n",
                sa->name, sb->name, tc, cp->restitution, cp->friction, cp->rolling_friction,
                w->hertz ? "c" : "zeta", cp->damping);
        }
        for (int k = 0; k < s->wall_count; ++k) {
            const bdl_contact_params *cp = &w->wall_params[k * ns + a];
            double tc = bdl_contact_time(cp, s->law, ma, 0.5 * da, v_ref);
            printf("  %-12s - wall %-7s t_c = %-10.4g s  e = %-5.3g mu = %-5.3g mu_r = %-5.3g %s = "
                   "%.4g\n",
                   sa->name, s->walls[k].name, tc, cp->restitution, cp->friction,
                   cp->rolling_friction, w->hertz ? "c" : "zeta", cp->damping);
        }
    }
}

bdl_result bdl_cmd_check(int argc, char **argv)
{
    bdl_scene_opts o;
    bdl_result rc = bdl_parse_scene_opts(argc, argv, check_usage, &o);
    if (rc != BDL_OK || o.help)
        return rc;
    if (o.threads > 0)
        omp_set_num_threads(o.threads);
    bdl_scene *scene = calloc(1, sizeof *scene);
    bdl_scene_error err;
    if (!scene)
        return BDL_ERR_NOMEM;
    if ((rc = bdl_scene_load(o.scene, o.overrides, o.override_count, scene, &err)) != BDL_OK) {
        fprintf(stderr, "error: %s\n", err.message);
        free(scene);
        return rc;
    }
    bdl_world *w = NULL;
    bdl_result r = bdl_world_create(scene, &w, &err);
    free(scene);
    if (r != BDL_OK) {
        fprintf(stderr, "error: %s\n", r == BDL_ERR_SCENE ? err.message : bdl_result_text(r));
        return r;
    }
    const bdl_scene *s = &w->scene;
    printf("scene: %s — valid\n", s->path);
    printf("modules:\n");
    printf("  dem: %s normal law%s; %s%s\n", w->hertz ? "Hertz-Mindlin" : "linear spring-dashpot",
           w->hertz ? (s->damping == BDL_DAMPING_EXACT ? " with exact restitution damping"
                                                       : " with closed-form damping")
                    : "",
           w->friction ? "tangential spring with history, Coulomb friction"
                       : "frictionless (no tangential history)",
           w->rolling ? "; rolling resistance" : "");
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
    double v_ref = bdl_world_reference_speed(w);
    print_contacts(w, v_ref);
    char message[1024], warning[1024];
    r = bdl_guards_check_dt(w, message, sizeof message, warning, sizeof warning);
    printf("time step: dt = %.4g s = t_c / %.1f (smallest contact time %.4g s)\n", w->dt,
           1.0 / w->contact_time_dt_ratio, w->contact_time);
    printf("  stable limit: dt <= %.4g s ([guards] dt_refuse = %g t_c); accurate below %.4g s "
           "(dt_warn = %g t_c)\n",
           s->guards.dt_refuse * w->contact_time, s->guards.dt_refuse,
           s->guards.dt_warn * w->contact_time, s->guards.dt_warn);
    if (r != BDL_OK) {
        fprintf(stderr, "error: %s\n", message);
        bdl_world_destroy(w);
        return r;
    }
    if (warning[0])
        printf("  warning: %s\n", warning);
    // Cost: time a few steps of this very scene.
    long steps_total = (long)ceil(s->end_time / w->dt);
    double t0 = bdl_wall_seconds();
    long trial = 0;
    while (trial < 2000 && (trial < 5 || bdl_wall_seconds() - t0 < 0.5)) {
        if (bdl_world_step(w) != BDL_OK)
            break;
        ++trial;
    }
    double per_step = (bdl_wall_seconds() - t0) / (double)(trial > 0 ? trial : 1);
    long n = w->particles.count > 0 ? w->particles.count : 1;
    double rate = (double)n / per_step;
    // Pouring scenes grow: cost the run at the particle count the scene will reach.
    long total = bdl_create_estimate_total(s->creates, s->create_count, s->species);
    if (total < n)
        total = n;
    double wall = (double)total / rate * (double)steps_total;
    printf("cost: %ld steps to t = %g s; measured %.3g particle-steps/s on %d threads (%ld "
           "particles) -> about %.3g s wall time for %ld particles (%.3gx real time)\n",
           steps_total, s->end_time, rate, omp_get_max_threads(), n, wall, total,
           s->end_time / wall);
    bdl_world_destroy(w);
    return BDL_OK;
}
