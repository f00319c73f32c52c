// The world: builds the modules a scene needs and advances them by one step.
#include "world/world.h"

#include "cfd/gas.h"
#include "core/memory.h"
#include "core/comm.h"
#include "core/parallel.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dem/capsule.h"
#include "solids/phase.h"
#include "dem/create.h"
#include "dem/contact_force.h"
#include "dem/rod_force.h"
#include "dem/integrate.h"
#include "dist/exchange.h"

#define PI 3.14159265358979323846

static bdl_force_def force_def(const bdl_world *w)
{
    bdl_force_def def;
    def.pair_params = w->pair_params;
    def.wall_params = w->wall_params;
    def.species_count = w->scene.species_count;
    def.background_damping = w->background_damping;
    def.shear_rate = w->scene.shear_rate;
    def.shear_middle = 0.5 * (w->scene.domain_min.z + w->scene.domain_max.z);
    def.gravity = bdl_world_gravity(w, w->time);
    def.hertz = w->hertz;
    def.friction = w->friction;
    def.rolling = w->rolling;
    def.dt = w->dt;
    def.parallel_min = w->parallel_min;
    def.loads_cleared = 0;
    return def;
}

static double max_diameter(const bdl_scene *scene)
{
    double d = 0.0;
    for (int s = 0; s < scene->species_count; ++s) {
        double ds = bdl_species_max_diameter(&scene->species[s]);
        if (ds > d)
            d = ds;
    }
    return d;
}

static double sphere_mass(double d, double density) { return density * PI / 6.0 * d * d * d; }

double bdl_world_reference_speed(const bdl_world *w)
{
    const bdl_scene *s = &w->scene;
    double g = bdl_v3_len(s->gravity);
    bdl_vec3 span = bdl_v3_sub(s->domain_max, s->domain_min);
    double h = fmax(span.x, fmax(span.y, span.z));
    // Lees–Edwards: a pair across the z faces meets at the images' speed on top of its own.
    double v = sqrt(2.0 * g * h) + bdl_walls_max_speed(&w->walls) + fabs(s->shear_rate) * span.z;
    if (w->container >= 0) { // the container's walls stand still, but hit as hard as moving ones
        const bdl_wall_def *d = &s->walls[w->container];
        v += d->amplitude * 2.0 * PI * d->frequency;
    }
    double vmax = 0.0;
    for (long i = 0; i < w->particles.count; ++i) {
        double vi = bdl_v3_len(w->particles.vel[i]);
        if (vi > vmax)
            vmax = vi;
    }
    for (int c = 0; c < s->create_count; ++c)
        vmax = fmax(vmax, bdl_v3_len(s->creates[c].velocity) + s->creates[c].velocity_jitter);
    v += vmax;
    return v > 0.1 ? v : 0.1;
}

/// The smallest particle of species a: its diameter and mass (the shortest contacts). A rod's
/// mass is the smallest it shows at a contact point, struck at a tip across its axis:
/// 1 / (1/m + h^2 / I_t), h half the shaft (0.347 m for the thesis's small rod), as the contact
/// damping takes it (dem/rod_force.h).
static void smallest(const bdl_scene *s, int a, double *d, double *m)
{
    const bdl_species_def *sp = &s->species[a];
    *d = bdl_species_min_diameter(sp);
    if (sp->shape == BDL_SHAPE_ROD) {
        double mass, axial, transverse;
        const double h = 0.5 * (sp->length - *d);
        bdl_rod_mass_properties(0.5 * *d, sp->length - *d, sp->density, &mass, &axial, &transverse);
        *m = 1.0 / (1.0 / mass + h * h / transverse);
    } else {
        *m = sphere_mass(*d, sp->density);
    }
}

double bdl_world_pair_contact_time(const bdl_world *w, int a, int b, double v_ref)
{
    const bdl_scene *s = &w->scene;
    double da, ma, db, mb;
    smallest(s, a, &da, &ma);
    smallest(s, b, &db, &mb);
    return bdl_contact_time(&w->pair_params[a * s->species_count + b], s->law, ma * mb / (ma + mb),
                            0.25 * da * db / (0.5 * (da + db)), v_ref);
}

double bdl_world_wall_contact_time(const bdl_world *w, int a, int wall, double v_ref)
{
    const bdl_scene *s = &w->scene;
    double da, ma;
    smallest(s, a, &da, &ma);
    return bdl_contact_time(&w->wall_params[wall * s->species_count + a], s->law, ma, 0.5 * da,
                            v_ref);
}

double bdl_world_min_contact_time(const bdl_world *w, double v_ref, char *which, int which_len)
{
    const bdl_scene *s = &w->scene;
    double best = INFINITY;
    for (int a = 0; a < s->species_count; ++a) {
        for (int b = a; b < s->species_count; ++b) {
            double tc = bdl_world_pair_contact_time(w, a, b, v_ref);
            if (tc < best) {
                best = tc;
                if (which)
                    snprintf(which, (size_t)which_len, "species '%s' with '%s'", s->species[a].name,
                             s->species[b].name);
            }
        }
        for (int wall = 0; wall < s->wall_count; ++wall) {
            double tc = bdl_world_wall_contact_time(w, a, wall, v_ref);
            if (tc < best) {
                best = tc;
                if (which)
                    snprintf(which, (size_t)which_len, "species '%s' with wall '%s'",
                             s->species[a].name, s->walls[wall].name);
            }
        }
    }
    return best;
}

void bdl_world_describe(const bdl_world *w, char *buf, size_t size)
{
    const bdl_scene *s = &w->scene;
    char gas[384];
    bdl_world_gas_describe(w, gas, sizeof gas);
    if (w->parcels) {
        char parcels[384];
        bdl_world_parcels_describe(w, parcels, sizeof parcels);
        snprintf(buf, size, "%s, gas: %s", parcels, gas);
        return;
    }
    if (w->solids) {
        char solids[1024];
        bdl_world_solids_describe(w, solids, sizeof solids);
        snprintf(buf, size, "%s, gas: %s", solids, gas);
        return;
    }
    snprintf(buf, size, "dem (%s normal law%s, %s%s), walls: %d, gas: %s",
             w->hertz ? "Hertz" : "linear",
             w->hertz ? (s->damping == BDL_DAMPING_EXACT ? ", exact restitution damping"
                                                         : ", closed-form damping")
                      : "",
             w->friction ? "tangential history + Coulomb friction"
                         : "frictionless, no tangential history",
             w->rolling ? ", rolling resistance" : "", s->wall_count, gas);
}

void bdl_world_apply_live(bdl_world *w)
{
    if (w->gas) // inlet and jet velocities of every inlet side, as a factor on the scene's
        bdl_gas_set_inflow(w->gas, bdl_world_inlet_velocity(w, w->time),
                           w->live.inlet_scale * w->scene.gas.jet_velocity);
    for (int k = 0; k < w->scene.wall_count; ++k) {
        const bdl_wall_def *d = &w->scene.walls[k];
        if (d->motion == BDL_MOTION_ROTATE) // the rate, as a factor on the scene's
            w->walls.omega[k] = w->live.frequency_scale[k];
        if (d->motion != BDL_MOTION_VIBRATE || d->frame == BDL_FRAME_CONTAINER)
            continue; // a container wall's motion is read by bdl_world_gravity
        w->walls.amplitude[k] = d->amplitude * w->live.amplitude_scale[k];
        w->walls.omega[k] = 2.0 * PI * d->frequency * w->live.frequency_scale[k];
    }
    bdl_walls_update(&w->walls, w->time);
    if (w->scene.shear_rate != 0.0)
        bdl_neighbor_set_shear(&w->neighbor, w->scene.shear_rate, w->time);
}

int bdl_world_set_parameter(bdl_world *w, const char *key, double value)
{
    if (strcmp(key, "gas.inlet_scale") == 0 && w->gas) {
        if (value > w->live.inlet_scale)
            w->gas_inflow_raised = 1; // the next gas step starts short (world_gas.c)
        w->live.inlet_scale = value;
        bdl_world_apply_live(w);
        return 1;
    }
    for (int k = 0; k < w->scene.wall_count; ++k) {
        char a[96], f[96];
        snprintf(a, sizeof a, "wall.%s.amplitude_scale", w->scene.walls[k].name);
        snprintf(f, sizeof f, "wall.%s.frequency_scale", w->scene.walls[k].name);
        if (strcmp(key, a) == 0)
            w->live.amplitude_scale[k] = value;
        else if (strcmp(key, f) == 0)
            w->live.frequency_scale[k] = value;
        else
            continue;
        bdl_world_apply_live(w);
        return 1;
    }
    return 0;
}

/// Rebuilds the lists if needed, then evaluates all forces; with kick > 0 the closing half kick
/// of the step is applied in the same pass, and the forces are taken as cleared by the kick and
/// drift that opened the step.
static bdl_result forces(bdl_world *w, double max_move2, double kick)
{
    bdl_particles *p = &w->particles;
    if (w->dist) {
        bdl_result r = bdl_world_dist_lists(w, max_move2);
        if (r != BDL_OK)
            return r;
        p->count += bdl_dist_ghosts(w->dist); // the force pass runs over the ghosts too
    }
    if (w->coordination_capacity < p->capacity) {
        if (!bdl_grow((void **)&w->coordination, p->capacity, 1))
            return BDL_ERR_NOMEM;
        w->coordination_capacity = p->capacity;
    }
    w->neighbor.parallel_min = w->parallel_min;
    if (!w->dist && bdl_neighbor_needs_build(&w->neighbor, p, &w->walls, max_move2)) {
        bdl_result r = bdl_neighbor_build(&w->neighbor, p, &w->walls, NULL);
        if (r != BDL_OK)
            return r;
    }
    bdl_force_def def = force_def(w);
    def.loads_cleared = kick > 0.0;
    bdl_result r;
    if (p->rods)
        r = bdl_rod_forces(p, &w->neighbor, &w->walls, &def, &w->force_work, w->coordination, kick);
    else
        r = bdl_dem_forces(p, &w->neighbor, &w->walls, &def, &w->force_work, w->coordination, kick);
    if (w->dist)
        p->count = bdl_dist_owned(w->dist);
    return r;
}

bdl_result bdl_world_compute_forces(bdl_world *w) { return forces(w, -1.0, 0.0); }

static double particle_energy(const bdl_particles *p, long i, bdl_vec3 g)
{
    double m = 1.0 / p->inv_mass[i];
    double iner = p->rods ? 0.0 : 1.0 / bdl_particle_inv_inertia(p, i);
    double rotation = p->rods ? 0.5 * bdl_v3_dot(p->omega[i], p->ang_mom[i])
                              : 0.5 * iner * bdl_v3_len2(p->omega[i]);
    return 0.5 * m * bdl_v3_len2(p->vel[i]) + rotation - m * bdl_v3_dot(g, p->pos[i]);
}

/// What the scene's creators draw on.
static bdl_create_context create_context(bdl_world *w)
{
    return (bdl_create_context){.species = w->scene.species,
                                .species_count = w->scene.species_count,
                                .walls = &w->walls,
                                .rng = &w->rng};
}

static bdl_result pour(bdl_world *w)
{
    bdl_create_context ctx = create_context(w);
    for (int c = 0; c < w->scene.create_count; ++c) {
        if (w->scene.creates[c].kind != BDL_CREATE_POUR)
            continue;
        ctx.region = &w->region_mesh[c];
        long before = w->particles.count;
        long added =
            bdl_create_pour(&w->scene.creates[c], &ctx, w->time, &w->poured[c], &w->particles);
        if (added < 0)
            return BDL_ERR_NOMEM;
        for (long i = before; i < w->particles.count; ++i) {
            w->inserted_energy += particle_energy(&w->particles, i, w->scene.gravity);
            w->particles.load[i].force = bdl_v3_zero();
        }
    }
    return BDL_OK;
}

/// True when x lies beyond a face of the domain that removes particles (a gas outlet, or any
/// with [domain] outside = remove), or in a [sink] that has started.
static int beyond_outlet(const bdl_world *w, bdl_vec3 x)
{
    for (int a = 0; a < 3; ++a) {
        double c = bdl_v3_comp(x, a);
        if ((w->outflow[2 * a] && c < bdl_v3_comp(w->scene.domain_min, a)) ||
            (w->outflow[2 * a + 1] && c > bdl_v3_comp(w->scene.domain_max, a)))
            return 1;
    }
    for (int k = 0; k < w->scene.sink_count; ++k) {
        const bdl_sink_def *s = &w->scene.sinks[k];
        if (w->time >= s->start_time && x.x >= s->min.x && x.x <= s->max.x && x.y >= s->min.y &&
            x.y <= s->max.y && x.z >= s->min.z && x.z <= s->max.z)
            return 1;
    }
    return 0;
}

/// Removes the particles that crossed a removing face or entered a sink during the drift, booking
/// their number, mass and energy; the lists are rebuilt without them (`*max_move2` then 0).
static bdl_result remove_outflow(bdl_world *w, double *max_move2)
{
    bdl_particles *p = &w->particles;
    const long n = p->count;
    long leaving = 0;
    for (long i = 0; i < n; ++i)
        leaving += beyond_outlet(w, p->pos[i]);
    if (leaving == 0)
        return BDL_OK;
    if (w->drop_capacity < n) {
        if (!bdl_grow((void **)&w->drop, p->capacity, 1))
            return BDL_ERR_NOMEM;
        w->drop_capacity = p->capacity;
    }
    for (long i = 0; i < n; ++i) {
        w->drop[i] = (uint8_t)beyond_outlet(w, p->pos[i]);
        if (w->drop[i]) { // its gas work so far is booked now: the next gas step will not see it
            w->gas_work += bdl_world_gas_work_pending(w, i);
            w->removed_mass += 1.0 / p->inv_mass[i];
            w->removed_energy += particle_energy(p, i, w->scene.gravity);
        }
    }
    w->removed += leaving;
    if (w->dist) { // the ranks rebuild together in the force pass
        *max_move2 = INFINITY;
        return bdl_dist_remove(w->dist, p, w->drop);
    }
    *max_move2 = 0.0;
    w->neighbor.parallel_min = w->parallel_min;
    return bdl_neighbor_build(&w->neighbor, p, &w->walls, w->drop);
}

bdl_vec3 bdl_world_gravity(const bdl_world *w, double t)
{
    const int k = w->container;
    if (k < 0)
        return w->scene.gravity;
    const bdl_wall_def *d = &w->scene.walls[k];
    if (t < d->start)
        return w->scene.gravity;
    const double A = d->amplitude * w->live.amplitude_scale[k];
    const double omega = 2.0 * PI * d->frequency * w->live.frequency_scale[k];
    // The container accelerates by -A w^2 sin(w t + phase) along d; in its frame everything in it
    // feels the opposite.
    return bdl_v3_madd(w->scene.gravity, d->direction, // unit: the scene normalises it
                       A * omega * omega * sin(omega * (t - d->start) + d->phase));
}

/// Momentum of the particles along the container's direction [kg m/s].
static double container_momentum(const bdl_world *w)
{
    const bdl_particles *p = &w->particles;
    const bdl_vec3 dir = w->scene.walls[w->container].direction;
    double sum = 0.0;
    for (long i = 0; i < p->count; ++i)
        sum += bdl_v3_dot(p->vel[i], dir) / p->inv_mass[i];
    return sum;
}

/// One step of the particles (and the gas when one starts here).
static bdl_result particles_step(bdl_world *w)
{
    bdl_particles *p = &w->particles;
    // In a container's frame the inertial force does the work the container's walls would:
    // its acceleration at mid-step times the mean momentum along it over the step.
    const double momentum0 = w->container >= 0 ? container_momentum(w) : 0.0;
    const bdl_vec3 g_mid = bdl_world_gravity(w, w->time + 0.5 * w->dt);
    if (w->gas && w->step >= w->gas_next) {
        bdl_result r = bdl_world_gas_step(w);
        if (r != BDL_OK)
            return r;
    }
    double h = 0.5 * w->dt;
    const bdl_vec3 g_now = bdl_world_gravity(w, w->time);
    double max_move2 = p->rods ? bdl_dem_kick_drift_rods(p, g_now, h, w->dt)
                               : bdl_dem_kick_drift(p, g_now, h, w->dt);
    w->step++;
    w->time += w->dt;
    bdl_walls_turn(&w->walls, w->dt);
    bdl_walls_update(&w->walls, w->time);
    if (w->scene.shear_rate != 0.0)
        bdl_neighbor_set_shear(&w->neighbor, w->scene.shear_rate, w->time);
    const int outflow = w->outflow[0] | w->outflow[1] | w->outflow[2] | w->outflow[3] |
                        w->outflow[4] | w->outflow[5] | (w->scene.sink_count > 0);
    bdl_result r = outflow ? remove_outflow(w, &max_move2) : BDL_OK;
    if (r == BDL_OK)
        r = pour(w);
    if (r != BDL_OK)
        return r;
    r = forces(w, max_move2, h);
    if (r != BDL_OK)
        return r;
    w->wall_work += w->dt * bdl_dem_wall_power(p, &w->neighbor, &w->walls);
    if (w->container >= 0)
        w->wall_work +=
            w->dt * 0.5 * (momentum0 + container_momentum(w)) *
            bdl_v3_dot(bdl_v3_sub(g_mid, w->scene.gravity), w->scene.walls[w->container].direction);
    return BDL_OK;
}

bdl_result bdl_world_step(bdl_world *w)
{
    if (w->parcels)
        return bdl_world_parcels_step(w);
    if (w->solids)
        return bdl_world_solids_step(w);
    const bdl_result r = particles_step(w);
    // Divided between ranks: they all go on or all stop, with the same result.
    return w->dist ? bdl_world_dist_agree(w, r) : r;
}

uint64_t bdl_world_hash(const bdl_world *w)
{
    const bdl_particles *p = &w->particles;
    uint64_t h = BDL_HASH_INIT;
    size_t n = (size_t)p->count;
    h = bdl_hash_bytes(h, p->pos, n * sizeof(bdl_vec3));
    h = bdl_hash_bytes(h, p->vel, n * sizeof(bdl_vec3));
    h = bdl_hash_bytes(h, p->omega, n * sizeof(bdl_vec3));
    h = bdl_hash_bytes(h, p->id, n * sizeof(uint32_t));
    if (p->rods) {
        h = bdl_hash_bytes(h, p->orient, n * sizeof(bdl_quat));
        h = bdl_hash_bytes(h, p->ang_mom, n * sizeof(bdl_vec3));
    }
    if (w->neighbor.history)
        h = bdl_hash_bytes(h, w->neighbor.history,
                           (size_t)w->neighbor.pair_count * sizeof(bdl_vec3));
    if (w->neighbor.spring_work)
        h = bdl_hash_bytes(h, w->neighbor.spring_work,
                           (size_t)w->neighbor.pair_count * sizeof(double));
    h = bdl_hash_bytes(h, &w->time, sizeof w->time);
    h = bdl_hash_bytes(h, &w->step, sizeof w->step);
    if (w->gas) {
        size_t cells = (size_t)w->gas->grid.size;
        for (int a = 0; a < 3; ++a)
            h = bdl_hash_bytes(h, w->gas->u[a], cells * sizeof(double));
        h = bdl_hash_bytes(h, w->gas->p, cells * sizeof(double));
    }
    if (w->solids) {
        const size_t cells = (size_t)w->solids->grid.size * sizeof(double);
        for (int m = 0; m < w->solids->count; ++m) {
            const bdl_solids_phase *ph = &w->solids->phase[m];
            h = bdl_hash_bytes(h, ph->eps, cells);
            h = bdl_hash_bytes(h, ph->theta, cells);
            for (int a = 0; a < 3; ++a)
                h = bdl_hash_bytes(h, ph->v[a], cells);
        }
    }
    return h;
}

static int any_friction(const bdl_world *w)
{
    int ns = w->scene.species_count;
    for (int k = 0; k < ns * ns; ++k)
        if (w->pair_params[k].friction > 0.0)
            return 1;
    for (int k = 0; k < w->scene.wall_count * ns; ++k)
        if (w->wall_params[k].friction > 0.0)
            return 1;
    return 0;
}

static int any_rolling(const bdl_world *w)
{
    if (w->scene.rolling == BDL_ROLLING_NONE)
        return 0;
    int ns = w->scene.species_count;
    for (int k = 0; k < ns * ns; ++k)
        if (w->pair_params[k].rolling_friction > 0.0)
            return 1;
    for (int k = 0; k < w->scene.wall_count * ns; ++k)
        if (w->wall_params[k].rolling_friction > 0.0)
            return 1;
    return 0;
}

/// "scenes/x.ini:12: [create NAME]": the section a particle came from (by id order of
/// creation), for messages.
static void creator_of(const bdl_world *w, uint32_t id, const long *first_id, char *out, size_t len)
{
    int c = -1;
    for (int k = 0; k < w->scene.create_count; ++k)
        if ((long)id >= first_id[k])
            c = k;
    snprintf(out, len, "%s:%d: [create %s]", w->scene.path, c >= 0 ? w->scene.line.creates[c] : 0,
             c >= 0 ? w->scene.creates[c].name : "?");
}

/// Initial particle i outside the domain (on a non-periodic axis): the sentence, or 0.
static int outside_domain(const bdl_world *w, long i, char *what, size_t len)
{
    const bdl_scene *s = &w->scene;
    const bdl_vec3 x = w->particles.pos[i];
    for (int a = 0; a < 3; ++a) {
        double c = bdl_v3_comp(x, a);
        if (!s->periodic[a] &&
            (c < bdl_v3_comp(s->domain_min, a) || c > bdl_v3_comp(s->domain_max, a))) {
            snprintf(what, len,
                     "particle %u at (%g, %g, %g) m lies outside the domain [%g, %g] x [%g, %g] x "
                     "[%g, %g] m",
                     w->particles.id[i], x.x, x.y, x.z, s->domain_min.x, s->domain_max.x,
                     s->domain_min.y, s->domain_max.y, s->domain_min.z, s->domain_max.z);
            return 1;
        }
    }
    return 0;
}

/// Initial particle i overlapping a listed partner beyond [guards] initial_overlap: the
/// sentence, or 0.
static int overlaps_particle(const bdl_world *w, long i, char *what, size_t len)
{
    const bdl_particles *p = &w->particles;
    const bdl_neighbor *nb = &w->neighbor;
    const double allowed = w->scene.guards.initial_overlap;
    for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k) {
        int32_t j = nb->partner[k];
        double s, t; // the centres' (or with rods the shafts') distance, coincident ones included
        double dist = sqrt(bdl_segments_closest(bdl_neighbor_delta(nb, p->pos[i], p->pos[j]),
                                                bdl_particle_half_axis(p, i),
                                                bdl_particle_half_axis(p, j), &s, &t));
        double overlap = p->radius[i] + p->radius[j] - dist;
        double rmin = fmin(p->radius[i], p->radius[j]);
        if (overlap > allowed * rmin + 1e-12 * rmin) {
            snprintf(what, len,
                     "initial particles %u and %u overlap by %.3g%% of the smaller radius "
                     "(allowed: [guards] initial_overlap = %g); move them apart or use a random or "
                     "lattice fill",
                     p->id[i], p->id[j], 100.0 * overlap / rmin, allowed);
            return 1;
        }
    }
    return 0;
}

/// Initial particle i overlapping a wall beyond [guards] initial_overlap: the sentence, or 0.
static int overlaps_wall(const bdl_world *w, long i, char *what, size_t len)
{
    const bdl_particles *p = &w->particles;
    const bdl_neighbor *nb = &w->neighbor;
    for (int32_t k = nb->wall_start[i]; k < nb->wall_start[i + 1]; ++k) {
        bdl_world_contact c;
        if (bdl_world_wall_contact(w, i, k, &c) &&
            c.overlap > (w->scene.guards.initial_overlap + 1e-12) * p->radius[i]) {
            snprintf(what, len, "initial particle %u overlaps wall '%s' by %.3g%% of its radius",
                     p->id[i], w->scene.walls[bdl_wall_of(&w->walls, c.prim)].name,
                     100.0 * c.overlap / p->radius[i]);
            return 1;
        }
    }
    return 0;
}

static bdl_result check_initial(bdl_world *w, const long *first_id, bdl_scene_error *err)
{
    char what[768];
    const int parcels = w->parcels != NULL; // parcels may overlap, and meet no walls
    for (long i = 0; i < w->particles.count; ++i)
        if (outside_domain(w, i, what, sizeof what) ||
            (!parcels && (overlaps_particle(w, i, what, sizeof what) ||
                          overlaps_wall(w, i, what, sizeof what)))) {
            char where[BDL_PATH_LEN + 64];
            creator_of(w, w->particles.id[i], first_id, where, sizeof where);
            snprintf(err->message, sizeof err->message, "%s: %s", where, what);
            return BDL_ERR_SCENE;
        }
    return BDL_OK;
}

/// The contact parameters of every species pair and species-wall pair, and which contact
/// models the scene needs at all (friction keeps tangential history, rolling its own torque).
static void build_contacts(bdl_world *w)
{
    const bdl_scene *scene = &w->scene;
    bdl_material species[BDL_MAX_SPECIES], walls[BDL_MAX_WALLS];
    for (int k = 0; k < scene->species_count; ++k)
        species[k] = scene->species[k].material;
    for (int k = 0; k < scene->wall_count; ++k)
        walls[k] = scene->walls[k].material;
    const bdl_contact_table_def table = {.law = scene->law,
                                         .damping = scene->damping,
                                         .species_count = scene->species_count,
                                         .species = species,
                                         .pair_count = scene->pair_count,
                                         .pairs = scene->pairs,
                                         .wall_count = scene->wall_count,
                                         .walls = walls};
    bdl_contact_table_build(&table, w->pair_params, w->wall_params);
    w->hertz = scene->law == BDL_LAW_HERTZ;
    w->friction = any_friction(w);
    w->rolling = any_rolling(w);
    for (int k = 0; k < scene->species_count; ++k)
        w->background_damping[k] = scene->species[k].background_damping;
}

double bdl_world_contact_reach(const bdl_scene *scene, double *skin)
{
    double d_max = max_diameter(scene), extent = d_max;
    for (int k = 0; k < scene->species_count; ++k)
        extent = fmax(extent, bdl_species_max_extent(&scene->species[k]));
    *skin = scene->skin * d_max;
    return extent + *skin;
}

/// Triangle walls that repeat along periodic axes: their period is the domain's length there, and
/// their triangles must reach `reach` beyond its faces (else a particle near a face would miss the
/// triangles across it).
static bdl_result wrap_walls(bdl_world *w, double reach, bdl_scene_error *err)
{
    const bdl_scene *s = &w->scene;
    bdl_walls *walls = &w->walls;
    for (int k = 0; k < s->wall_count; ++k)
        for (int a = 0; a < 3; ++a) {
            if (!s->walls[k].periodic[a])
                continue;
            const double lo = bdl_v3_comp(s->domain_min, a), hi = bdl_v3_comp(s->domain_max, a);
            double min = INFINITY, max = -INFINITY;
            for (long t = 0; t < walls->tri_count; ++t) {
                const bdl_wall_tri *tri = &walls->tri[t];
                if (tri->wall != k)
                    continue;
                const double c[3] = {bdl_v3_comp(tri->a, a), bdl_v3_comp(tri->b, a),
                                     bdl_v3_comp(tri->c, a)};
                for (int v = 0; v < 3; ++v) {
                    min = fmin(min, c[v]);
                    max = fmax(max, c[v]);
                }
            }
            if (!(min <= lo - reach && max >= hi + reach)) {
                snprintf(err->message, sizeof err->message,
                         "%s:%d: [wall %s] periodic: its triangles span [%g, %g] m along %c; a "
                         "repeating wall must reach %g m beyond the domain's faces there: [%g, %g]",
                         s->path, s->line.walls[k], s->walls[k].name, min, max, "xyz"[a], reach,
                         lo - reach, hi + reach);
                return BDL_ERR_SCENE;
            }
            bdl_v3_set_comp(&walls->wrap_origin[k], a, lo);
            bdl_v3_set_comp(&walls->wrap_length[k], a, hi - lo);
        }
    return BDL_OK;
}

/// The walls at rest, with live scales of one, and the container whose frame the run is in.
static bdl_result build_walls(bdl_world *w, bdl_scene_error *err)
{
    const bdl_scene *scene = &w->scene;
    for (int k = 0; k < BDL_MAX_WALLS; ++k)
        w->live.amplitude_scale[k] = w->live.frequency_scale[k] = 1.0;
    w->live.inlet_scale = 1.0;
    double skin;
    char why[600];
    bdl_result r =
        bdl_walls_build(scene->walls, scene->wall_count, bdl_world_contact_reach(scene, &skin),
                        &w->walls, why, sizeof why);
    if (r != BDL_OK)
        snprintf(err->message, sizeof err->message, "%s: [wall] %s", scene->path, why);
    else
        r = wrap_walls(w, bdl_world_contact_reach(scene, &skin), err);
    w->container = -1;
    for (int k = 0; k < scene->wall_count; ++k)
        if (scene->walls[k].motion == BDL_MOTION_VIBRATE &&
            scene->walls[k].frame == BDL_FRAME_CONTAINER)
            w->container = k;
    return r;
}

/// The particles of every creator that makes them at the start; `first_id` receives the id of
/// each creator's first particle, and `expected` how many particles the run will hold at most.
static bdl_result create_particles(bdl_world *w, long *first_id, long *expected,
                                   bdl_scene_error *err)
{
    const bdl_scene *scene = &w->scene;
    w->particles.fluid = scene->gas.enabled; // before the arrays exist
    w->particles.parcels = scene->parcels.enabled;
    for (int k = 0; k < scene->species_count; ++k)
        w->particles.rods |= scene->species[k].shape == BDL_SHAPE_ROD;
    // Reserve what the creators will make, so storage carries no growth slack.
    *expected = bdl_create_estimate_total(scene->creates, scene->create_count, scene->species);
    long reserve = *expected < 64 ? 64 : (*expected > 10000000 ? 10000000 : *expected);
    if (bdl_particles_reserve(&w->particles, reserve) != BDL_OK)
        return BDL_ERR_NOMEM;
    bdl_create_context ctx = create_context(w);
    for (int c = 0; c < scene->create_count; ++c) {
        first_id[c] = w->particles.next_id;
        char why[768];
        bdl_result r = BDL_OK;
        if (scene->creates[c].region_shape == BDL_REGION_MESH)
            r = bdl_create_region_mesh(&scene->creates[c], &w->region_mesh[c], why, sizeof why);
        ctx.region = &w->region_mesh[c];
        if (r == BDL_OK)
            r = bdl_create_initial(&scene->creates[c], &ctx, &w->particles, why, sizeof why);
        if (r == BDL_ERR_SCENE)
            snprintf(err->message, sizeof err->message, "%s:%d: [create %s]: %s", scene->path,
                     scene->line.creates[c], scene->creates[c].name, why);
        if (r != BDL_OK)
            return r;
    }
    if (*expected < w->particles.count)
        *expected = w->particles.count;
    return BDL_OK;
}

/// The cell grid and Verlet lists, sized for `expected` particles of the largest diameter.
static bdl_result build_neighbor(bdl_world *w, long expected, bdl_scene_error *err)
{
    const bdl_scene *scene = &w->scene;
    double skin, reach = bdl_world_contact_reach(scene, &skin), extent = reach - skin;
    bdl_result r = bdl_neighbor_init(&w->neighbor, scene->domain_min, scene->domain_max,
                                     scene->periodic, reach, skin, expected, w->friction, w->hertz,
                                     w->rolling, w->particles.rods);
    if (r == BDL_ERR_SCENE)
        snprintf(err->message, sizeof err->message,
                 "%s: [domain] periodic axes must be at least 3 x (largest particle + skin) = %g "
                 "m long",
                 scene->path, 3.0 * (extent + skin));
    return r;
}

/// The time step: as given, or a fraction of the smallest contact time.
static bdl_result choose_time_step(bdl_world *w, bdl_scene_error *err)
{
    const bdl_scene *scene = &w->scene;
    w->contact_time = bdl_world_min_contact_time(w, bdl_world_reference_speed(w), NULL, 0);
    if (!(w->contact_time > 0.0) || !isfinite(w->contact_time)) {
        snprintf(err->message, sizeof err->message,
                 "%s: the contact time is %g s, so no time step can be derived; check the species' "
                 "stiffness, youngs_modulus and restitution",
                 scene->path, w->contact_time);
        return BDL_ERR_SCENE;
    }
    w->dt = scene->dt > 0.0 ? scene->dt : scene->dt_fraction * w->contact_time;
    w->contact_time_dt_ratio = w->dt / w->contact_time;
    return BDL_OK;
}

/// The particles' contact solver (lists, the time step from the contact time), the gas, and the
/// forces of the initial state.
/// Lees–Edwards: the particles start on the shear profile u_x = shear_rate (z - middle) on top
/// of their own velocities, and the images in place for time 0.
static void start_shear(bdl_world *w)
{
    const bdl_scene *s = &w->scene;
    if (s->shear_rate == 0.0)
        return;
    const double middle = 0.5 * (s->domain_min.z + s->domain_max.z);
    bdl_particles *p = &w->particles;
    for (long i = 0; i < p->count; ++i)
        p->vel[i].x += s->shear_rate * (p->pos[i].z - middle);
    bdl_neighbor_set_shear(&w->neighbor, s->shear_rate, w->time);
}

static bdl_result build_contact_solver(bdl_world *w, long expected, bdl_scene_error *err)
{
    bdl_result r = build_neighbor(w, expected, err);
    if (r == BDL_OK)
        start_shear(w);
    if (r == BDL_OK)
        r = choose_time_step(w, err);
    if (r == BDL_OK) // the particles' own speeds may have shortened the step
        r = bdl_budget_check_steps(w, w->dt, err);
    w->budget.dt = w->dt;
    w->budget.steps = w->scene.end_time / w->dt;
    if (r == BDL_OK && w->scene.gas.enabled)
        r = bdl_world_gas_init(w, err);
    // The first neighbour build sorts the particles for locality; forces are consistent with it.
    if (r == BDL_OK)
        r = bdl_world_compute_forces(w);
    return r;
}

static bdl_result create(const bdl_scene *scene, bdl_world **out, bdl_scene_error *err, int divide)
{
    *out = NULL;
    bdl_world *w = calloc(1, sizeof *w);
    if (!w)
        return BDL_ERR_NOMEM;
    w->scene = *scene;
    w->parallel_min = BDL_PARALLEL_MIN;
    bdl_rng_seed(&w->rng, scene->seed);
    build_contacts(w);
    bdl_result r = build_walls(w, err);
    // What the scene will need, before any of it is allocated.
    bdl_budget_estimate(w, &w->budget);
    long first_id[BDL_MAX_CREATES], expected = 0;
    if (r == BDL_OK)
        r = bdl_budget_check(w, &w->budget, err);
    if (r == BDL_OK)
        r = create_particles(w, first_id, &expected, err);
    if (r == BDL_OK && scene->parcels.enabled) // no contacts: the gas's pace
        r = bdl_world_parcels_init(w, err);
    else if (r == BDL_OK && scene->solids.enabled) // no particles at all
        r = bdl_world_solids_init(w, err);
    else if (r == BDL_OK)
        r = build_contact_solver(w, expected, err);
    for (int f = 0; f < 6 && !scene->parcels.enabled && !scene->solids.enabled; ++f)
        w->outflow[f] |= !scene->periodic[f / 2] && scene->outside == BDL_OUTSIDE_REMOVE;
    if (r == BDL_OK)
        r = check_initial(w, first_id, err);
    if (r == BDL_OK && divide && bdl_comm_size() > 1)
        r = bdl_world_dist_init(w, err);
    if (r != BDL_OK) {
        bdl_world_destroy(w);
        return r;
    }
    *out = w;
    return BDL_OK;
}

bdl_result bdl_world_create(const bdl_scene *scene, bdl_world **out, bdl_scene_error *err)
{
    return create(scene, out, err, 1);
}

bdl_result bdl_world_create_whole(const bdl_scene *scene, bdl_world **out, bdl_scene_error *err)
{
    return create(scene, out, err, 0);
}

void bdl_world_destroy(bdl_world *w)
{
    if (!w)
        return;
    bdl_world_parcels_free(w);
    bdl_world_solids_free(w);
    bdl_world_gas_free(w);
    bdl_dist_destroy(w->dist);
    bdl_particles_free(&w->particles);
    bdl_neighbor_free(&w->neighbor);
    bdl_walls_free(&w->walls);
    for (int c = 0; c < BDL_MAX_CREATES; ++c)
        bdl_mesh_free(&w->region_mesh[c]);
    bdl_force_work_free(&w->force_work);
    free(w->coordination);
    free(w->drop);
    free(w);
}
