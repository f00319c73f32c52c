// bedlam — DEM verification cases: one sphere on a plane, two spheres, a static column.
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "dem/material.h"
#include "output/diagnostics.h"
#include "verify/verify.h"

bdl_world *bdl_verify_world_text(const char *text)
{
    bdl_scene *scene = calloc(1, sizeof *scene); // large: keep it off the stack
    bdl_scene_error err;
    err.message[0] = '\0';
    bdl_world *w = NULL;
    if (!scene) {
        fprintf(stderr, "verify: out of memory\n");
        return NULL;
    }
    if (bdl_scene_load_string(text, "verify-scene", NULL, 0, scene, &err) != BDL_OK ||
        bdl_world_create(scene, &w, &err) != BDL_OK || !w) {
        fprintf(stderr, "verify: %s\n--- scene ---\n%s\n-------------\n", err.message, text);
        w = NULL;
    }
    free(scene);
    return w;
}

bdl_world *bdl_verify_world_v(const char *format, va_list ap)
{
    char text[16384];
    int n = vsnprintf(text, sizeof text, format, ap);
    if (n < 0 || n >= (int)sizeof text) {
        fprintf(stderr, "verify: scene text too long (%d characters)\n", n);
        return NULL;
    }
    return bdl_verify_world_text(text);
}

bdl_world *bdl_verify_world(const char *format, ...)
{
    va_list ap;
    va_start(ap, format);
    bdl_world *w = bdl_verify_world_v(format, ap);
    va_end(ap);
    return w;
}

long bdl_verify_find_particle(const bdl_world *w, uint32_t id)
{
    for (long i = 0; i < w->particles.count; ++i)
        if (w->particles.id[i] == id)
            return i;
    return -1;
}

double bdl_verify_order(double n1, double e1, double n2, double e2)
{
    return log(e1 / e2) / log(n2 / n1);
}

double bdl_verify_difference_order(double n1, double e1, double n2, double e2, double n3, double e3)
{
    double a = e1 - e2, b = e2 - e3;
    if (!(a * b > 0.0) || fabs(log(n3 / n2) / log(n2 / n1) - 1.0) > 1e-9)
        return NAN;
    return log(a / b) / log(n2 / n1);
}

// ---- restitution of a sphere bouncing on a plane ----

static const double bounce_d = 0.01;       // m
static const double bounce_rho = 2500.0;   // kg/m^3
static const double bounce_k = 2.0e6;      // N/m (linear): overlap ~1 % of r at 2 m/s
static const double bounce_youngs = 1.0e9; // Pa (Hertz): overlap ~2 % of r at 2 m/s
static const double bounce_nu = 0.3;

double bdl_verify_bounce_contact_time(int hertz, double e, double v)
{
    double m = bounce_rho * BDL_PI / 6.0 * bounce_d * bounce_d * bounce_d, r = 0.5 * bounce_d;
    if (!hertz) {
        double l = log(e);
        double zeta = -l / sqrt(BDL_PI * BDL_PI + l * l);
        return BDL_PI / (sqrt(bounce_k / m) * sqrt(1.0 - zeta * zeta));
    }
    double es = bounce_youngs / (2.0 * (1.0 - bounce_nu * bounce_nu));
    return 2.87 * pow(m * m / (r * es * es * v), 0.2);
}

bdl_world *bdl_verify_bounce_world(int hertz, const char *damping, double e, double v, double z0,
                                   double dt, double g)
{
    const double r = 0.5 * bounce_d;
    return bdl_verify_world(
        "[run]\nend_time = 10\ndt = %.17g\ngravity = 0 0 %.17g\n"
        "[domain]\nmin = -0.02 -0.02 -0.01\nmax = 0.02 0.02 0.5\n"
        "[contact]\nlaw = %s\ndamping = %s\n"
        "[species ball]\ndiameter = %.17g\ndensity = %.17g\n%s = %.17g\npoisson_ratio = %.17g\n"
        "restitution = %.17g\nfriction = 0\n"
        "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"
        "[create ball]\ntype = lattice\ncount = 1\nvelocity = 0 0 %.17g\n"
        "region_min = %.17g %.17g %.17g\nregion_max = %.17g %.17g %.17g\n",
        dt, -g, bdl_normal_law_names[hertz ? BDL_LAW_HERTZ : BDL_LAW_LINEAR], damping, bounce_d,
        bounce_rho, hertz ? "youngs_modulus" : "stiffness", hertz ? bounce_youngs : bounce_k,
        bounce_nu, e, -v, -r, -r, z0 - r, r + bounce_d, r + bounce_d, z0 + 2.0 * r);
}

double bdl_verify_restitution(int hertz, const char *damping, double e, double v, double dt,
                              double phi, long *steps)
{
    const double r = 0.5 * bounce_d, z0 = r + (3.0 + phi) * v * dt;
    bdl_world *w = bdl_verify_bounce_world(hertz, damping, e, v, z0, dt, 0.0);
    if (!w)
        return -1.0;
    const double tc = bdl_verify_bounce_contact_time(hertz, e, v);
    const long max_steps = 10 + (long)(4.0 * tc / dt);
    int touched = 0;
    double result = -1.0;
    long s = 0;
    while (s < max_steps && bdl_world_step(w) == BDL_OK) {
        ++s;
        double z = w->particles.pos[0].z, vz = w->particles.vel[0].z;
        if (z < r)
            touched = 1;
        if (touched && z >= r && vz > 0.0) { // left the wall: no force acts any more
            result = vz / v;
            break;
        }
    }
    if (steps)
        *steps += s;
    bdl_world_destroy(w);
    return result;
}

double bdl_verify_restitution_worst(int hertz, double e, double v, double dt, long *steps)
{
    enum { phases = 8 };
    double worst = 0.0;
    for (int k = 0; k < phases; ++k) {
        double em = bdl_verify_restitution(hertz, bdl_damping_mode_names[BDL_DAMPING_EXACT], e, v,
                                           dt, (k + 0.5) / phases, steps);
        worst = fmax(worst, em < 0.0 ? INFINITY : fabs(em - e) / e);
    }
    return worst;
}

// ---- Hertz contact duration ----

static const double steel_d = 0.01, steel_rho = 7800.0, steel_youngs = 2.0e11, steel_nu = 0.3;

double bdl_verify_hertz_time(int pair, double v)
{
    double r = 0.5 * steel_d, m = steel_rho * BDL_PI / 6.0 * steel_d * steel_d * steel_d;
    double m_eff = pair ? 0.5 * m : m, r_eff = pair ? 0.5 * r : r;
    double es = steel_youngs / (2.0 * (1.0 - steel_nu * steel_nu));
    // 2 (15/16)^(2/5) (2/5) B(2/5, 1/2) = 2.86827, usually rounded to 2.87 (0.06 % larger).
    return 2.8682656991953315 * pow(m_eff * m_eff / (r_eff * es * es * v), 0.2);
}

double bdl_verify_hertz_duration(int pair, double v, double dt, double *rebound, long *steps)
{
    const double r = 0.5 * steel_d, d = steel_d;
    const double gap0 = 3.3 * v * dt; // contact starts 0.3 of a step into the 4th step
    bdl_world *w;
    if (!pair) {
        double z0 = r + gap0;
        w = bdl_verify_world(
            "[run]\nend_time = 1\ndt = %.17g\ngravity = 0 0 0\n"
            "[domain]\nmin = -0.02 -0.02 -0.01\nmax = 0.02 0.02 0.05\n"
            "[contact]\nlaw = hertz\n"
            "[species steel]\ndiameter = %.17g\ndensity = %.17g\nyoungs_modulus = %.17g\n"
            "poisson_ratio = %.17g\nrestitution = 1\n"
            "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"
            "[create ball]\ntype = lattice\ncount = 1\nvelocity = 0 0 %.17g\n"
            "region_min = %.17g %.17g %.17g\nregion_max = %.17g %.17g %.17g\n",
            dt, d, steel_rho, steel_youngs, steel_nu, -v, -r, -r, z0 - r, r + d, r + d,
            z0 + 2.0 * r);
    } else {
        double x0 = r + 0.5 * gap0; // centres at -x0 and +x0
        w = bdl_verify_world(
            "[run]\nend_time = 1\ndt = %.17g\ngravity = 0 0 0\n"
            "[domain]\nmin = -0.05 -0.02 -0.02\nmax = 0.05 0.02 0.02\n"
            "[contact]\nlaw = hertz\n"
            "[species steel]\ndiameter = %.17g\ndensity = %.17g\nyoungs_modulus = %.17g\n"
            "poisson_ratio = %.17g\nrestitution = 1\n"
            "[create left]\ntype = lattice\ncount = 1\nvelocity = %.17g 0 0\n"
            "region_min = %.17g %.17g %.17g\nregion_max = %.17g %.17g %.17g\n"
            "[create right]\ntype = lattice\ncount = 1\nvelocity = %.17g 0 0\n"
            "region_min = %.17g %.17g %.17g\nregion_max = %.17g %.17g %.17g\n",
            dt, d, steel_rho, steel_youngs, steel_nu, 0.5 * v, -x0 - r, -r, -r, -x0 + 2.0 * r,
            r + d, r + d, -0.5 * v, x0 - r, -r, -r, x0 + 2.0 * r, r + d, r + d);
    }
    if (!w)
        return -1.0;
    double prev_gap = gap0, t_start = -1.0, t_end = -1.0, t_prev = 0.0;
    const long max_steps = 10 + (long)(3.0 * bdl_verify_hertz_time(pair, v) / dt);
    long s = 0;
    while (s < max_steps && t_end < 0.0 && bdl_world_step(w) == BDL_OK) {
        ++s;
        const bdl_particles *p = &w->particles;
        double gap;
        if (!pair) {
            gap = p->pos[0].z - r;
            *rebound = p->vel[0].z / v;
        } else {
            long a = bdl_verify_find_particle(w, 0), b = bdl_verify_find_particle(w, 1);
            gap = bdl_v3_len(bdl_v3_sub(p->pos[b], p->pos[a])) - 2.0 * r;
            *rebound = (p->vel[b].x - p->vel[a].x) / v;
        }
        // Start and end by linear interpolation of the gap between the bracketing steps.
        if (t_start < 0.0 && gap < 0.0)
            t_start = t_prev + dt * prev_gap / (prev_gap - gap);
        else if (t_start >= 0.0 && gap >= 0.0)
            t_end = t_prev + dt * prev_gap / (prev_gap - gap);
        prev_gap = gap;
        t_prev = w->time;
    }
    if (steps)
        *steps += s;
    bdl_world_destroy(w);
    return t_start >= 0.0 && t_end >= 0.0 ? t_end - t_start : -1.0;
}

// ---- sliding to rolling ----

bdl_verify_slide bdl_verify_slide_roll(int hertz, double mu, double v0, double dt)
{
    const double d = 0.01, rho = 2500.0, g = 9.81, r = 0.5 * d;
    const double ts = 2.0 * v0 / (7.0 * mu * g);
    bdl_verify_slide res = {-1.0, 0, 0.0, 0.0, 0.0, 0};
    // Linear: k_n = 1e5 N/m, t_c ~ 5e-4 s; Hertz: E = 1e8 Pa, resting contact period ~ 2e-3 s.
    // e = 0.2 (zeta = 0.73, exact damping).
    bdl_world *w = bdl_verify_world(
        "[run]\nend_time = 10\ndt = %.17g\ngravity = 0 0 %.17g\n"
        "[domain]\nmin = -0.02 -0.02 -0.01\nmax = 1.5 0.02 0.05\n"
        "[contact]\nlaw = %s\n"
        "[species ball]\ndiameter = %.17g\ndensity = %.17g\n%s\nrestitution = "
        "0.2\nfriction = %.17g\ntangential_damping_ratio = 0.5\n"
        "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"
        "[create ball]\ntype = lattice\ncount = 1\nvelocity = %.17g 0 0\n"
        "region_min = %.17g %.17g 0\nregion_max = %.17g %.17g %.17g\n",
        dt, -g, bdl_normal_law_names[hertz ? BDL_LAW_HERTZ : BDL_LAW_LINEAR], d, rho,
        hertz ? "youngs_modulus = 1e8\npoisson_ratio = 0.3" : "stiffness = 1e5", mu, v0, -r, -r,
        r + d, r + d, 3.0 * d);
    if (!w)
        return res;
    // Least-squares sums of the slip s(t) over the sliding window 0.2 v0 < s < 0.8 v0.
    double n = 0, st = 0, ss = 0, stt = 0, sts = 0;
    const long steps = (long)(2.0 * ts / dt) + 1;
    for (long k = 0; k < steps && bdl_world_step(w) == BDL_OK; ++k) {
        ++res.steps;
        const bdl_particles *p = &w->particles;
        double arm = 0.5 * (r + p->pos[0].z); // the solver's lever arm r - delta/2
        double s = p->vel[0].x - arm * p->omega[0].y;
        double t = w->time;
        if (s > 0.2 * v0 && s < 0.8 * v0) {
            n += 1, st += t, ss += s, stt += t * t, sts += t * s;
        }
        // Wall force on the sphere: its x component is tangential (the normal is z).
        const bdl_neighbor *nb = &w->neighbor;
        bdl_vec3 fw = bdl_v3_zero();
        for (int32_t c = nb->wall_start[0]; c < nb->wall_start[1]; ++c)
            fw = bdl_v3_add(fw, nb->wall_force[c]);
        if (s > 0.05 * v0 && fw.x > 0.0) {
            ++res.forward;
            res.max_forward = fmax(res.max_forward, fw.z > 0.0 ? fw.x / (mu * fw.z) : INFINITY);
        }
        res.v_roll = p->vel[0].x;
        res.slip_end = fabs(s);
    }
    double slope = (n * sts - st * ss) / (n * stt - st * st);
    res.t_fit = -(ss - slope * st) / n / slope;
    bdl_world_destroy(w);
    return res;
}

// ---- elastic head-on collision ----

double bdl_verify_collision_contact_time(int hertz, double v)
{
    const double r = 0.005, m_eff = 0.5 * 2500.0 * BDL_PI / 6.0 * 1e-6;
    if (hertz) {
        double es = 1e9 / (2.0 * (1.0 - 0.09));
        return 2.87 * pow(m_eff * m_eff / (0.5 * r * es * es * v), 0.2);
    }
    return BDL_PI / sqrt(1e6 / m_eff);
}

double bdl_verify_collision_energy(int hertz, double v, double dt, double phi, long *steps)
{
    const double r = 0.005, gap0 = (3.0 + phi) * v * dt, x0 = r + 0.5 * gap0;
    bdl_world *w = bdl_verify_world(
        "[run]\nend_time = 1\ndt = %.17g\ngravity = 0 0 0\n"
        "[domain]\nmin = -0.05 -0.02 -0.02\nmax = 0.05 0.02 0.02\n"
        "[contact]\nlaw = %s\n"
        "[species s]\ndiameter = 0.01\ndensity = 2500\n%s\nrestitution = 1\nfriction = 0\n"
        "[create left]\ntype = lattice\ncount = 1\nvelocity = %.17g 0 0\n"
        "region_min = %.17g -0.005 -0.005\nregion_max = %.17g 0.01 0.01\n"
        "[create right]\ntype = lattice\ncount = 1\nvelocity = %.17g 0 0\n"
        "region_min = %.17g -0.005 -0.005\nregion_max = %.17g 0.01 0.01\n",
        dt, bdl_normal_law_names[hertz ? BDL_LAW_HERTZ : BDL_LAW_LINEAR],
        hertz ? "youngs_modulus = 1e9\npoisson_ratio = 0.3" : "stiffness = 1e6", 0.5 * v, -x0 - r,
        -x0 + 2.0 * r, -0.5 * v, x0 - r, x0 + 2.0 * r);
    if (!w)
        return INFINITY;
    bdl_diagnostics d;
    bdl_diagnostics_compute(w, 0.0, &d);
    const double e0 = d.kinetic_energy;
    int touched = 0;
    long s = 0;
    while (s < 100000 && bdl_world_step(w) == BDL_OK) {
        ++s;
        const bdl_particles *p = &w->particles;
        if (bdl_v3_len(bdl_v3_sub(p->pos[0], p->pos[1])) < 2.0 * r)
            touched = 1;
        else if (touched)
            break;
    }
    if (steps)
        *steps += s;
    bdl_diagnostics_compute(w, 0.0, &d);
    bdl_world_destroy(w);
    return touched ? fabs(d.kinetic_energy - e0) / e0 : INFINITY;
}

// ---- static column ----

static int by_height(const void *a, const void *b)
{
    double za = ((const bdl_vec3 *)a)->z, zb = ((const bdl_vec3 *)b)->z;
    return (za > zb) - (za < zb);
}

bdl_verify_column bdl_verify_static_column(int hertz, double dt_fraction)
{
    enum { N = BDL_VERIFY_COLUMN };
    const double d = 0.01, rho = 2500.0, g = 9.81, k_n = 1.0e4, youngs = 1.0e8, nu = 0.3;
    const double r = 0.5 * d, m = rho * BDL_PI / 6.0 * d * d * d;
    bdl_verify_column c = {{0}, {0}, 0.0, INFINITY, 1e-12 * N * m * g * r, 0.0, 0.0, 0};
    // The lattice stacks the spheres 1.0001 d apart from z = r: they drop by 1e-4 d and settle.
    bdl_world *w = bdl_verify_world(
        "[run]\nend_time = 10\ndt_fraction = %.17g\ngravity = 0 0 %.17g\n"
        "[domain]\nmin = -0.02 -0.02 -0.01\nmax = 0.02 0.02 0.1\n"
        "[contact]\nlaw = %s\n"
        "[species ball]\ndiameter = %.17g\ndensity = %.17g\n%s = %.17g\npoisson_ratio = %.17g\n"
        "restitution = 0.3\nfriction = 0\nbackground_damping = 20\n"
        "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"
        "[create column]\ntype = lattice\ncount = %d\n"
        "region_min = %.17g %.17g 0\nregion_max = %.17g %.17g %.17g\n",
        dt_fraction, -g, bdl_normal_law_names[hertz ? BDL_LAW_HERTZ : BDL_LAW_LINEAR], d, rho,
        hertz ? "youngs_modulus" : "stiffness", hertz ? youngs : k_n, nu, N, -r, -r, r + d, r + d,
        5.5 * d);
    if (!w || w->particles.count != N) {
        if (w)
            bdl_world_destroy(w);
        return c;
    }
    while (w->time < 5.0 && bdl_world_step(w) == BDL_OK) {
        if (++c.steps % 100)
            continue;
        c.kinetic = 0.0;
        for (long i = 0; i < w->particles.count; ++i)
            c.kinetic += 0.5 * bdl_v3_len2(w->particles.vel[i]) / w->particles.inv_mass[i];
        if (c.kinetic < c.kinetic_limit && w->time > 0.2)
            break;
    }
    bdl_vec3 x[N];
    for (int i = 0; i < N; ++i)
        x[i] = w->particles.pos[i];
    qsort(x, N, sizeof x[0], by_height); // x[0] is the bottom sphere
    const double es = youngs / (2.0 * (1.0 - nu * nu));
    for (int k = 0; k < N; ++k) {
        // Contact k carries the N - k spheres above it, including sphere k itself.
        double f = (N - k) * m * g;
        c.overlap[k] = k == 0 ? r - x[0].z : 2.0 * r - (x[k].z - x[k - 1].z);
        c.theory[k] =
            hertz ? pow(f / ((4.0 / 3.0) * es * sqrt(k == 0 ? r : 0.5 * r)), 2.0 / 3.0) : f / k_n;
        c.lateral = fmax(c.lateral, fmax(fabs(x[k].x - x[0].x), fabs(x[k].y - x[0].y)));
    }
    c.time = w->time;
    c.dt_ratio = w->contact_time_dt_ratio;
    bdl_world_destroy(w);
    return c;
}
