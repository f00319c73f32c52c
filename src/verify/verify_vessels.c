// bedlam — verification of granular vessels: a silo's discharge against Beverloo, a rotating drum's
// angle of repose, a silo's bottom pressure against Janssen (verify.h).
#define _POSIX_C_SOURCE 200809L // mkdtemp
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "core/log.h"
#include "verify/verify.h"

#define SIDES 96

/// The floor: an annulus from the orifice's radius out to 40 mm at z = 0, as an OBJ file.
static int write_floor(const char *path, double orifice)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return 0;
    for (int ring = 0; ring < 2; ++ring)
        for (int k = 0; k < SIDES; ++k) {
            const double r = ring ? 0.040 : 0.5 * orifice, a = 2.0 * BDL_PI * k / SIDES;
            fprintf(f, "v %.17g %.17g 0\n", r * cos(a), r * sin(a));
        }
    for (int k = 0; k < SIDES; ++k) {
        const int a = 1 + k, b = 1 + (k + 1) % SIDES, c = b + SIDES, d = a + SIDES;
        fprintf(f, "f %d %d %d\nf %d %d %d\n", a, b, c, a, c, d);
    }
    return fclose(f) == 0;
}

/// Bulk density of the settled bed: the beads whose centres lie in r < 25 mm, 10 < z < 40 mm.
static double bulk_density(const bdl_world *w)
{
    const bdl_particles *p = &w->particles;
    double mass = 0.0;
    for (long i = 0; i < p->count; ++i) {
        const bdl_vec3 x = p->pos[i];
        if (x.x * x.x + x.y * x.y < 0.025 * 0.025 && x.z > 0.010 && x.z < 0.040)
            mass += 1.0 / p->inv_mass[i];
    }
    return mass / (BDL_PI * 0.025 * 0.025 * 0.030);
}

static bdl_world *silo_world(const char *floor, long count, double t_end)
{
    return bdl_verify_world(
        "[run]\nend_time = %g\ndt_fraction = 0.05\ngravity = 0 0 -9.81\nseed = 3\n"
        "[domain]\nmin = -0.04 -0.04 -0.03\nmax = 0.04 0.04 0.14\n[contact]\nlaw = linear\n"
        "[species glass]\ndiameter = 0.003\ndensity = 2500\nstiffness = 2000\n"
        "restitution = 0.5\nfriction = 0.5\n"
        "[wall silo]\ntype = cylinder\npoint = 0 0 0\naxis = 0 0 1\nradius = 0.036\n"
        "[wall floor]\ntype = mesh\nfile = %s\n"
        "[wall plug]\ntype = plane\npoint = 0 0 -0.001\nnormal = 0 0 1\nopen_time = 0.5\n"
        "[create bed]\ntype = random\nspecies = glass\ncount = %ld\n"
        "region_min = -0.036 -0.036 0.0015\nregion_max = 0.036 0.036 0.13\n",
        t_end, floor, count);
}

/// Least-squares slope of y against t.
static double slope(const double *t, const double *y, int n)
{
    double st = 0.0, sy = 0.0, stt = 0.0, sty = 0.0;
    for (int k = 0; k < n; ++k) {
        st += t[k];
        sy += y[k];
        stt += t[k] * t[k];
        sty += t[k] * y[k];
    }
    return (n * sty - st * sy) / (n * stt - st * st);
}

/// Runs the discharge, sampling the mass out every 10 ms from t_open + 0.2 s.
static bdl_result discharge(bdl_world *w, double t_end, bdl_verify_silo *out)
{
    enum { MAX = 512 };
    double t[MAX], m[MAX], next = 0.7;
    int n = 0;
    bdl_result r = BDL_OK;
    while (r == BDL_OK && w->time < t_end - 0.5 * w->dt) {
        if (out->bulk_density == 0.0 && w->time >= 0.5 - 0.5 * w->dt)
            out->bulk_density = bulk_density(w);
        r = bdl_world_step(w);
        ++out->steps;
        if (r == BDL_OK && w->time >= next - 0.5 * w->dt && n < MAX) {
            t[n] = w->time;
            m[n++] = w->removed_mass;
            next += 0.01;
        }
    }
    if (r != BDL_OK)
        bdl_error("%s", w->failure);
    out->rate = n >= 2 ? slope(t, m, n) : NAN;
    return r;
}

bdl_result bdl_verify_silo_discharge(double orifice, long count, double t_end, bdl_verify_silo *out)
{
    *out = (bdl_verify_silo){.orifice = orifice, .rate = NAN};
    char folder[] = "/tmp/bedlam-silo-XXXXXX", floor[64];
    if (!mkdtemp(folder))
        return BDL_ERR_IO;
    snprintf(floor, sizeof floor, "%s/floor.obj", folder);
    bdl_world *w = write_floor(floor, orifice) ? silo_world(floor, count, t_end) : NULL;
    unlink(floor);
    rmdir(folder);
    if (!w)
        return BDL_ERR_SCENE;
    const long start = w->particles.count;
    double mass0 = 0.0, mass1 = 0.0;
    for (long i = 0; i < start; ++i)
        mass0 += 1.0 / w->particles.inv_mass[i];
    bdl_result r = discharge(w, t_end, out);
    out->out = w->removed;
    out->left = w->particles.count;
    for (long i = 0; i < w->particles.count; ++i)
        mass1 += 1.0 / w->particles.inv_mass[i];
    out->mass_imbalance = fabs(mass1 + w->removed_mass - mass0) / mass0;
    const double d = 0.003, c = 0.58, k = 1.5;
    out->rate_beverloo = c * out->bulk_density * sqrt(9.81) * pow(orifice - k * d, 2.5);
    bdl_world_destroy(w);
    if (r == BDL_OK && (out->out + out->left != start || !isfinite(out->rate)))
        r = BDL_ERR_NO_RESULT;
    return r;
}

// ------------------------------------------------------------------------------------- drum --

/// The free surface's angle: a line fitted to the highest centre in each 6 mm bin of x over
/// |x| < 25 mm [degrees]; NAN when a bin is empty.
static double surface_angle(const bdl_world *w)
{
    enum { BINS = 8 };
    double top[BINS], x[BINS];
    for (int b = 0; b < BINS; ++b) {
        top[b] = -INFINITY;
        x[b] = -0.024 + 0.006 * (b + 0.5);
    }
    const bdl_particles *p = &w->particles;
    for (long i = 0; i < p->count; ++i) {
        const int b = (int)floor((p->pos[i].x + 0.024) / 0.006);
        if (b >= 0 && b < BINS && p->pos[i].z > top[b])
            top[b] = p->pos[i].z;
    }
    for (int b = 0; b < BINS; ++b)
        if (!isfinite(top[b]))
            return NAN;
    return atan(fabs(slope(x, top, BINS))) * 180.0 / BDL_PI;
}

/// Mean of v_t / (omega R) at the contact points of the beads within 0.1 d of the drum's wall in
/// its bottom quarter (within 45 degrees of straight down: always under the bed), v_t the
/// tangential velocity of the bead's surface where it meets the wall (its centre's velocity
/// plus its spin times the lever arm): 1 when it sticks to the wall.
static double carried_ratio(const bdl_world *w, double omega, double radius)
{
    const bdl_particles *p = &w->particles;
    double sum = 0.0;
    long n = 0;
    for (long i = 0; i < p->count; ++i) {
        const bdl_vec3 x = p->pos[i];
        const double rho = hypot(x.x, x.z);
        if (x.z > -fabs(x.x) || radius - rho - p->radius[i] > 0.1 * 2.0 * p->radius[i])
            continue;
        const bdl_vec3 out = bdl_v3(x.x / rho, 0.0, x.z / rho); // towards the wall
        const bdl_vec3 v =
            bdl_v3_add(p->vel[i], bdl_v3_cross(p->omega[i], bdl_v3_scale(out, p->radius[i])));
        // Turning about +y at omega: the wall at (x, z) moves along (z, -x) / rho.
        sum += (v.x * out.z - v.z * out.x) / (omega * radius);
        ++n;
    }
    return n ? sum / n : NAN;
}

bdl_result bdl_verify_drum_repose(double friction, double omega, bdl_verify_drum *out)
{
    *out = (bdl_verify_drum){.friction = friction, .omega = omega, .angle = NAN};
    const double radius = 0.05;
    bdl_world *w = bdl_verify_world(
        "[run]\nend_time = 2.5\ndt_fraction = 0.05\ngravity = 0 0 -9.81\nseed = 5\n"
        "[domain]\nmin = -0.052 0 -0.052\nmax = 0.052 0.02 0.052\nperiodic = y\n"
        "[contact]\nlaw = linear\n[species glass]\ndiameter = 0.003\ndensity = 2500\n"
        "stiffness = 2000\nrestitution = 0.5\nfriction = %.17g\n"
        "[wall drum]\ntype = cylinder\npoint = 0 0 0\naxis = 0 1 0\nradius = %g\n"
        "friction = 1.0\nmotion = rotate\nrotation_axis = 0 1 0\nrotation_center = 0 0 0\n"
        "angular_velocity = %.17g\nstart = 0.3\n"
        "[create bed]\ntype = random\nspecies = glass\ncount = 2600\n"
        "region_min = -0.05 0 -0.05\nregion_max = 0.05 0.02 0.035\n",
        friction, radius, omega);
    if (!w)
        return BDL_ERR_SCENE;
    double next = 1.2, sum = 0.0, sum2 = 0.0, carried = 0.0;
    bdl_result r = BDL_OK;
    while (r == BDL_OK && w->time < 2.5 - 0.5 * w->dt) {
        r = bdl_world_step(w);
        ++out->steps;
        if (r != BDL_OK || w->time < next - 0.5 * w->dt)
            continue;
        next += 0.1;
        const double a = surface_angle(w);
        sum += a;
        sum2 += a * a;
        carried += carried_ratio(w, omega, radius);
        ++out->samples;
    }
    if (r != BDL_OK)
        bdl_error("%s", w->failure);
    bdl_world_destroy(w);
    if (out->samples > 0) {
        out->angle = sum / out->samples;
        out->angle_sd = sqrt(fmax(0.0, sum2 / out->samples - out->angle * out->angle));
        out->carried = carried / out->samples;
    }
    return r == BDL_OK && !isfinite(out->angle) ? BDL_ERR_NO_RESULT : r;
}

// ---------------------------------------------------------------------------------- janssen --

#define JANSSEN_RADIUS 0.02
#define JANSSEN_SLABS  4

double bdl_verify_janssen_mass(double bulk_density, double radius, double mu_wall, double k,
                               double height)
{
    const double lambda = radius / (2.0 * mu_wall * k);
    return bulk_density * BDL_PI * radius * radius * lambda * (1.0 - exp(-height / lambda));
}

/// Sums over the wall contacts of the particles: the floor's vertical force, and per slab of
/// [z0, z1) the cylinder's radial and vertical force on the particles whose centres lie in it,
/// and the weight and the cylinder's vertical force on those above each slab's middle.
typedef struct janssen_sums {
    double floor;
    double radial[JANSSEN_SLABS], shear[JANSSEN_SLABS];
    double weight_above[JANSSEN_SLABS], lift_above[JANSSEN_SLABS];
} janssen_sums;

static void janssen_sample(const bdl_world *w, double z0, double z1, janssen_sums *s)
{
    const bdl_particles *p = &w->particles;
    const bdl_neighbor *nb = &w->neighbor;
    const double dz = (z1 - z0) / JANSSEN_SLABS, g = 9.81;
    for (long i = 0; i < p->count; ++i) {
        const bdl_vec3 x = p->pos[i];
        const double rho = hypot(x.x, x.y);
        const int slab = (int)floor((x.z - z0) / dz);
        double lift = 0.0, radial = 0.0;
        for (int32_t k = nb->wall_start[i]; k < nb->wall_start[i + 1]; ++k) {
            if (!nb->wall_touching[k])
                continue;
            const bdl_vec3 f = nb->wall_force[k];
            if (bdl_wall_of(&w->walls, nb->wall_prim[k]) == 1) { // the floor
                s->floor += f.z;
                continue;
            }
            lift += f.z;
            radial -= rho > 0.0 ? (f.x * x.x + f.y * x.y) / rho : 0.0; // pushing inwards
        }
        if (slab >= 0 && slab < JANSSEN_SLABS) {
            s->radial[slab] += radial;
            s->shear[slab] += lift;
        }
        for (int b = 0; b < JANSSEN_SLABS; ++b)
            if (x.z > z0 + (b + 0.5) * dz) {
                s->weight_above[b] += g / p->inv_mass[i];
                s->lift_above[b] += lift;
            }
    }
}

/// Bulk density of the settled bed in its core: centres within 2 d of the axis' distance from
/// the wall kept out, heights between a quarter and three quarters of the bed.
static double janssen_density(const bdl_world *w, double height)
{
    const bdl_particles *p = &w->particles;
    const double rc = JANSSEN_RADIUS - 0.006, z0 = 0.25 * height, z1 = 0.75 * height;
    double mass = 0.0;
    for (long i = 0; i < p->count; ++i) {
        const bdl_vec3 x = p->pos[i];
        if (x.x * x.x + x.y * x.y < rc * rc && x.z >= z0 && x.z < z1)
            mass += 1.0 / p->inv_mass[i];
    }
    return mass / (BDL_PI * rc * rc * (z1 - z0));
}

/// K and the mobilised friction from the slabs' sums (NAN for a bed under 8 diameters).
static void janssen_ratio(const janssen_sums *s, double height, bdl_verify_janssen *out)
{
    if (height < 8.0 * 0.003)
        return;
    const double r = JANSSEN_RADIUS, dz = 0.5 * height / JANSSEN_SLABS;
    double k = 0.0, mob = 0.0;
    for (int b = 0; b < JANSSEN_SLABS; ++b) {
        const double sigma_h = s->radial[b] / (2.0 * BDL_PI * r * dz);
        const double sigma_v = (s->weight_above[b] - s->lift_above[b]) / (BDL_PI * r * r);
        k += sigma_h / sigma_v / JANSSEN_SLABS;
        mob += fabs(s->shear[b]) / s->radial[b] / JANSSEN_SLABS;
    }
    out->k = k;
    out->mobilised = mob;
}

bdl_result bdl_verify_janssen_silo(long count, bdl_verify_janssen *out)
{
    *out = (bdl_verify_janssen){.count = count, .k = NAN, .mobilised = NAN};
    const double r = JANSSEN_RADIUS, area = BDL_PI * r * r;
    // A region twice the settled height (random insertion reaches about half of close packing).
    const double top = 0.0015 + 2.0 * count * BDL_PI / 6.0 * 27e-9 / (0.6 * area);
    bdl_world *w = bdl_verify_world(
        "[run]\nend_time = 1.0\ndt_fraction = 0.05\ngravity = 0 0 -9.81\nseed = 11\n"
        "[domain]\nmin = -0.021 -0.021 -0.002\nmax = 0.021 0.021 %.6g\n[contact]\nlaw = linear\n"
        "[species glass]\ndiameter = 0.003\ndensity = 2500\nstiffness = 2000\n"
        "restitution = 0.5\nfriction = 0.5\n"
        "[wall silo]\ntype = cylinder\npoint = 0 0 0\naxis = 0 0 1\nradius = %g\n"
        "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\nmotion = move\n"
        "velocity = 0 0 -0.005\nstart = 0.6\nstop = 1.0\n"
        "[create bed]\ntype = random\nspecies = glass\ncount = %ld\n"
        "region_min = -0.02 -0.02 0.0015\nregion_max = 0.02 0.02 %.6g\n",
        top + 0.01, r, count, top);
    if (!w)
        return BDL_ERR_SCENE;
    janssen_sums sums = {0};
    int samples = 0;
    bdl_result r_step = BDL_OK;
    double next = 0.9, mass = 0.0;
    for (long i = 0; i < w->particles.count; ++i)
        mass += 1.0 / w->particles.inv_mass[i];
    out->fill_mass = mass;
    out->height = mass / (1500.0 * area); // a first guess, for the slabs (rho_b replaces it)
    while (r_step == BDL_OK && w->time < 1.0 - 0.5 * w->dt) {
        r_step = bdl_world_step(w);
        ++out->steps;
        if (r_step != BDL_OK || w->time < next - 0.5 * w->dt)
            continue;
        next += 0.01;
        if (samples == 0) { // the bed has settled: its density, height and slabs
            out->bulk_density = janssen_density(w, out->height);
            out->height = mass / (out->bulk_density * area);
        }
        janssen_sample(w, 0.25 * out->height, 0.75 * out->height, &sums);
        ++samples;
    }
    if (r_step != BDL_OK)
        bdl_error("%s", w->failure);
    bdl_world_destroy(w);
    if (samples == 0)
        return r_step != BDL_OK ? r_step : BDL_ERR_NO_RESULT;
    out->floor_mass = sums.floor / samples / 9.81;
    janssen_ratio(&sums, out->height, out);
    return r_step;
}
