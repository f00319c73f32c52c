// bedlam — range checks of a state restored from a checkpoint.
//
// A checkpoint is input from outside: a file from someone else, or one damaged in a way its
// checksum cannot see (a crafted file carries a valid one). Before the next step reads it, every
// number it holds is checked against what the step relies on: indices within their arrays (the
// neighbour lists' partners and wall primitives, species), flags that index or count, counters
// that are never negative, and floating-point state that is finite (and positive where the
// physics divides by it: radii, masses, moments of inertia, voidage). The first violation is
// reported by name and index.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cfd/gas.h"
#include "solids/phase.h"
#include "output/checkpoint_parts.h"

/// What a number must be besides finite.
typedef enum range { ANY, POSITIVE, NON_NEGATIVE, FRACTION } range;

static int in_range(double x, range r)
{
    return isfinite(x) &&
           (r == ANY || (r == POSITIVE && x > 0.0) || (r == NON_NEGATIVE && x >= 0.0) ||
            (r == FRACTION && x > 0.0 && x <= 1.0));
}

/// The first of `count` numbers out of range, or -1.
static long first_bad(const double *v, long count, range r)
{
    for (long i = 0; i < count; ++i)
        if (!in_range(v[i], r))
            return i;
    return -1;
}

/// What is wrong with the floating-point state of particle i, or NULL.
static const char *particle_fault(const bdl_particles *p, long i)
{
    if (!bdl_v3_isfinite(p->pos[i]) || !bdl_v3_isfinite(p->pos_at_build[i]))
        return "a position that is not finite";
    if (!bdl_v3_isfinite(p->vel[i]) || !bdl_v3_isfinite(p->omega[i]))
        return "a velocity or angular velocity that is not finite";
    if (!bdl_v3_isfinite(p->load[i].force) || !bdl_v3_isfinite(p->load[i].torque))
        return "a force or torque that is not finite";
    if (!in_range(p->radius[i], POSITIVE) || !in_range(p->inv_mass[i], POSITIVE))
        return "a radius or inverse mass that is not finite and > 0";
    if (p->fluid && (!bdl_v3_isfinite(p->fluid_accel[i]) || !bdl_v3_isfinite(p->vel_mark[i]) ||
                     !bdl_v3_isfinite(p->drag_accel[i])))
        return "a gas force, or a velocity at the gas step's start, that is not finite";
    if (!p->rods)
        return NULL;
    const bdl_quat q = p->orient[i];
    if (!isfinite(q.w) || !isfinite(q.x) || !isfinite(q.y) || !isfinite(q.z) ||
        !bdl_v3_isfinite(p->axis[i]) || !bdl_v3_isfinite(p->axis_at_build[i]) ||
        !bdl_v3_isfinite(p->ang_mom[i]))
        return "an orientation, axis or angular momentum that is not finite";
    const bdl_vec3 ii = p->inv_inertia[i];
    if (!in_range(ii.x, POSITIVE) || !in_range(ii.y, POSITIVE) || !in_range(ii.z, POSITIVE))
        return "an inverse moment of inertia that is not finite and > 0";
    if (!in_range(p->half_length[i], NON_NEGATIVE))
        return "a half length that is not finite and >= 0";
    return NULL;
}

/// Whether x lies within the domain grown by its own length on every side. A run stops when a
/// particle leaves the domain (the guards); one that has flown further is no state to go on from.
static int near_domain(const bdl_scene *s, bdl_vec3 x)
{
    for (int a = 0; a < 3; ++a) {
        const double lo = bdl_v3_comp(s->domain_min, a), hi = bdl_v3_comp(s->domain_max, a);
        const double v = bdl_v3_comp(x, a);
        if (!(v >= lo - (hi - lo) && v <= hi + (hi - lo)))
            return 0;
    }
    return 1;
}

/// The particles' state, species and ids.
static int check_particles(const bdl_world *w, char *why, size_t len)
{
    const bdl_particles *p = &w->particles;
    for (long i = 0; i < p->count; ++i) {
        const char *fault = particle_fault(p, i);
        if (fault) {
            snprintf(why, len, "particle %ld (id %u) has %s", i, p->id[i], fault);
            return 0;
        }
        if (!near_domain(&w->scene, p->pos[i])) {
            snprintf(why, len,
                     "particle %ld (id %u) is at (%g, %g, %g) m, more than the domain's "
                     "size outside it",
                     i, p->id[i], p->pos[i].x, p->pos[i].y, p->pos[i].z);
            return 0;
        }
        if (p->species[i] < 0 || p->species[i] >= w->scene.species_count) {
            snprintf(why, len, "particle %ld is of species %d; the scene has %d", i,
                     (int)p->species[i], w->scene.species_count);
            return 0;
        }
        if (p->id[i] >= p->next_id) {
            snprintf(why, len, "particle %ld has id %u, not below the next id %u", i, p->id[i],
                     p->next_id);
            return 0;
        }
    }
    return 1;
}

/// How far the time step a checkpoint was written with may lie from the scene's.
#define DT_FACTOR 1e6

/// Time, step, counters, energies, live parameters and the random generator.
static int check_scalars(const bdl_world *w, double saved_dt, char *why, size_t len)
{
    if (!isfinite(saved_dt) || !(saved_dt > 0.0)) {
        snprintf(why, len, "its time step is %g s (must be finite and > 0)", saved_dt);
        return 0;
    }
    // The run steps with the scene's time step; the saved one only tells how the state was made.
    // Changed contact parameters move it by the square root of their ratio: a million-fold
    // difference is no changed scene but a damaged or crafted file.
    if (saved_dt < w->dt / DT_FACTOR || saved_dt > w->dt * DT_FACTOR) {
        snprintf(why, len, "its time step is %g s, not within a factor %g of the scene's %g s",
                 saved_dt, DT_FACTOR, w->dt);
        return 0;
    }
    if (!isfinite(w->time) || w->time < 0.0 || w->step < 0) {
        snprintf(why, len, "its time is %g s at step %ld (must be finite, >= 0)", w->time, w->step);
        return 0;
    }
    for (int c = 0; c < BDL_MAX_CREATES; ++c)
        if (w->poured[c] < 0 || w->poured[c] > (long)w->particles.next_id ||
            (c >= w->scene.create_count && w->poured[c] != 0)) {
            snprintf(why, len, "creator %d has poured %ld particles (ids issued: %u)", c,
                     w->poured[c], w->particles.next_id);
            return 0;
        }
    const double energies[] = {w->wall_work,       w->inserted_energy, w->damping_work,
                               w->energy0,         w->removed_energy,  w->removed_mass,
                               w->live.inlet_scale};
    int finite = first_bad(energies, 7, ANY) < 0 && w->removed >= 0 &&
                 first_bad(w->live.amplitude_scale, BDL_MAX_WALLS, ANY) < 0 &&
                 first_bad(w->live.frequency_scale, BDL_MAX_WALLS, ANY) < 0 &&
                 first_bad(w->walls.angle, BDL_MAX_WALLS, ANY) < 0;
    if (!finite) {
        snprintf(why, len,
                 "its energy bookkeeping, outflow counters, live parameters or walls' turned "
                 "angles are not finite (or a count is negative)");
        return 0;
    }
    if ((w->rng.s[0] | w->rng.s[1] | w->rng.s[2] | w->rng.s[3]) == 0) {
        snprintf(why, len, "its random generator's state is all zero (it would draw only zeros)");
        return 0;
    }
    return 1;
}

/// The gas's fields, counters and schedule. With the world's own time step, a gas step spans at
/// most the scene's largest number of particle steps (with another, the load reschedules it).
static int check_gas(const bdl_world *w, double saved_dt, char *why, size_t len)
{
    const struct bdl_gas *g = w->gas;
    if (!g)
        return 1;
    if (w->gas_every < 1 || (saved_dt == w->dt && w->gas_every > w->gas_every_max) ||
        w->gas_next < 0 || w->gas_next > w->step + w->gas_every || w->gas_steps < 0 ||
        g->steps < 0 || g->last_solve.iterations < 0 ||
        (w->gas_inflow_raised != 0 && w->gas_inflow_raised != 1)) {
        snprintf(why, len,
                 "its gas schedule is out of range: a gas step of %ld particle steps, "
                 "the next at step %ld (now %ld), %ld gas steps taken, inflow-raised flag %d",
                 w->gas_every, w->gas_next, w->step, w->gas_steps, w->gas_inflow_raised);
        return 0;
    }
    const double numbers[] = {w->gas_stable,       w->gas_work,         w->particle_drag[0],
                              w->particle_drag[1], w->particle_drag[2], w->gas_drag[0],
                              w->gas_drag[1],      w->gas_drag[2],      g->time};
    if (first_bad(numbers, 9, ANY) >= 0) {
        snprintf(why, len, "its gas's time, drag or work is not finite");
        return 0;
    }
    const long cells = g->grid.size;
    const struct {
        const double *v;
        range r;
        const char *what;
    } fields[] = {{g->u[0], ANY, "gas velocity x"}, {g->u[1], ANY, "gas velocity y"},
                  {g->u[2], ANY, "gas velocity z"}, {g->p, ANY, "gas pressure"},
                  {g->eps, FRACTION, "voidage"},    {g->eps_old, FRACTION, "voidage"}};
    for (size_t f = 0; f < sizeof fields / sizeof fields[0]; ++f) {
        const long i = first_bad(fields[f].v, cells, fields[f].r);
        if (i >= 0) {
            snprintf(why, len, "the %s in cell %ld of %ld is %g (%s)", fields[f].what, i, cells,
                     fields[f].v[i], fields[f].r == FRACTION ? "must be in (0, 1]" : "not finite");
            return 0;
        }
    }
    return 1;
}

/// The solids phase's fields: fractions in [0, 1), velocities and fluxes finite.
static int check_solids(const bdl_world *w, char *why, size_t len)
{
    const bdl_solids *s = w->solids;
    if (!s)
        return 1;
    const long cells = s->grid.size;
    for (int m = 0; m < s->count; ++m) {
        const bdl_solids_phase *p = &s->phase[m];
        if (first_bad(p->theta, cells, NON_NEGATIVE) >= 0) {
            snprintf(why, len, "a granular temperature is negative or not finite");
            return 0;
        }
        for (long i = 0; i < cells; ++i)
            if (!(p->eps[i] >= -1e-9 && p->eps[i] < 1.0)) { // round-off below zero is a state
                snprintf(why, len,
                         "the solids fraction of phase %d in cell %ld of %ld is %g (must be in "
                         "[-1e-9, 1))",
                         m + 1, i, cells, p->eps[i]);
                return 0;
            }
        for (int a = 0; a < 3; ++a)
            if (first_bad(p->v[a], cells, ANY) >= 0 || first_bad(p->flux[a], cells, ANY) >= 0) {
                snprintf(why, len, "a solids velocity or flux along %c is not finite", "xyz"[a]);
                return 0;
            }
    }
    return isfinite(s->time) && s->steps >= 0;
}

int bdl_ckpt_check_state(const bdl_world *w, double saved_dt, char *why, size_t why_len)
{
    char what[384];
    const bdl_particles *p = &w->particles;
    int ok = check_scalars(w, saved_dt, what, sizeof what) &&
             check_particles(w, what, sizeof what) &&
             bdl_neighbor_check(&w->neighbor, p->count, bdl_wall_surfaces(&w->walls), what,
                                sizeof what) &&
             check_gas(w, saved_dt, what, sizeof what) && check_solids(w, what, sizeof what);
    if (!ok)
        snprintf(why, why_len, "is not a consistent state: %s", what);
    return ok;
}
