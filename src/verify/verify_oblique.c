// bedlam — oblique impact of an elastic sphere on a plane: the tangential spring against its
// continuum limit and against the theory of Maw, Barber & Fawcett (1976).
//
// A steel sphere (d = 10 mm, 7800 kg/m^3, E = 200 GPa, nu = 0.3, e = 1, Hertz-Mindlin) meets a
// plane of the same steel at v_n = 1 m/s with the tangential velocity v_t of its contact point
// and no spin, gravity off. After it leaves, the contact point moves at v_t2 = v_x - r w_y. In
// the reduced variables of Maw et al.,
//
//   psi = kappa v_t / (mu v_n1),   kappa = 2 (1 - nu)/(2 - nu)   (k_t/k_n at the same overlap),
//   chi = (1 - nu)/(2 - nu) (1 + m r^2/I)                       (1.4412 for a solid sphere),
//
// rigid-body Coulomb friction in gross sliding gives psi2 = psi1 - 4 chi (e = 1).
//
// Three answers to compare a run with:
//  - the continuum limit of bedlam's own law (what the runs converge to as dt -> 0): the
//    equations of motion of the sphere with the same force law, lever arm r - delta/2 and
//    spring, by RK4 at 2e5 steps per contact, in two regimes whose law is smooth: full stick
//    (F_t = -8 G* sqrt(R delta) u, du/dt = v_t) and gross sliding (F_t = -mu F_n sign v_t);
//  - rigid-body Coulomb friction (gross sliding, the lever arm r);
//  - the theory of Maw, Barber & Fawcett: Hertz normal contact, the Cattaneo-Mindlin tangential
//    compliance with Coulomb friction at every point, new contact laid down free of tangential
//    traction, traction released where the contact recedes, normal and tangential problems
//    uncoupled (similar materials). bedlam computes it with the method of dimensionality
//    reduction (Popov & Hess 2015), exact for these assumptions: a row of independent springs,
//    normal stiffness E* dx and tangential 4 G* dx per unit length, on the profile
//    g(x) = x^2/R, each stuck while its force is below mu times its normal force.
#include <math.h>
#include <stdlib.h>

#include "output/diagnostics.h"
#include "verify/verify.h"

static const double ob_d = 0.01, ob_rho = 7800.0, ob_youngs = 2.0e11, ob_nu = 0.3;
static const double ob_vn = 1.0; // normal approach speed [m/s]

double bdl_verify_oblique_kappa(void) { return 2.0 * (1.0 - ob_nu) / (2.0 - ob_nu); }

double bdl_verify_oblique_chi(void) { return 0.5 * bdl_verify_oblique_kappa() * 3.5; }

double bdl_verify_oblique_contact_time(void) { return bdl_verify_hertz_time(0, ob_vn); }

double bdl_verify_oblique_speed(double psi1, double mu)
{
    return psi1 * mu * ob_vn / bdl_verify_oblique_kappa();
}

bdl_world *bdl_verify_oblique_world(double vt, double mu, double dt, double phi)
{
    const double r = 0.5 * ob_d, z0 = r + (3.0 + phi) * ob_vn * dt;
    return bdl_verify_world(
        "[run]\nend_time = 1\ndt = %.17g\ngravity = 0 0 0\n"
        "[domain]\nmin = -0.02 -0.02 -0.01\nmax = 0.06 0.02 0.05\n"
        "[contact]\nlaw = hertz\n"
        "[species steel]\ndiameter = %.17g\ndensity = %.17g\nyoungs_modulus = %.17g\n"
        "poisson_ratio = %.17g\nrestitution = 1\nfriction = %.17g\n"
        "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"
        "[create ball]\ntype = lattice\ncount = 1\nvelocity = %.17g 0 %.17g\n"
        "region_min = %.17g %.17g %.17g\nregion_max = %.17g %.17g %.17g\n",
        dt, ob_d, ob_rho, ob_youngs, ob_nu, mu, vt, -ob_vn, -r, -r, z0 - r, r + ob_d, r + ob_d,
        z0 + 2.0 * r);
}

bdl_verify_oblique bdl_verify_oblique_impact(double vt, double mu, double dt, double phi)
{
    const double r = 0.5 * ob_d;
    bdl_verify_oblique o = {.vt1 = vt, .vn1 = ob_vn, .vt2 = NAN, .vn2 = NAN, .steps = 0};
    bdl_world *w = bdl_verify_oblique_world(vt, mu, dt, phi);
    if (!w)
        return o;
    bdl_diagnostics d;
    bdl_diagnostics_compute(w, 0.0, &d);
    const double e0 = d.kinetic_energy + d.rotational_energy;
    const long max_steps = 10 + (long)(4.0 * bdl_verify_oblique_contact_time() / dt);
    int touched = 0;
    while (o.steps < max_steps && bdl_world_step(w) == BDL_OK) {
        ++o.steps;
        const bdl_vec3 x = w->particles.pos[0], v = w->particles.vel[0];
        bdl_diagnostics_compute(w, e0, &d);
        o.worst_balance = fmax(o.worst_balance, fabs(d.energy_balance) / e0);
        touched |= x.z < r;
        if (touched && x.z >= r && v.z > 0.0) { // left the plane: no force acts any more
            o.vn2 = v.z;
            o.vt2 = v.x - r * w->particles.omega[0].y;
            o.energy_error = d.energy_balance / e0;
            break;
        }
    }
    bdl_world_destroy(w);
    return o;
}

// ---- the continuum limit of bedlam's law ----

/// State of the sphere in contact: overlap delta, its rate, v_x, w_y, spring u.
typedef struct ob_state {
    double d, dd, vx, wy, u;
} ob_state;

typedef struct ob_law {
    double m, inertia, r, kh, kt, mu; ///< kh = (4/3) E* sqrt(R); kt = 8 G* sqrt(R)
    int sliding;
} ob_law;

static ob_state ob_rate(const ob_law *l, ob_state s)
{
    const double d = s.d > 0.0 ? s.d : 0.0, arm = l->r - 0.5 * s.d;
    const double fn = l->kh * d * sqrt(d), vt = s.vx - arm * s.wy;
    const double ft = l->sliding ? -l->mu * fn * (vt > 0.0 ? 1.0 : -1.0) : -l->kt * sqrt(d) * s.u;
    return (ob_state){s.dd, -fn / l->m, ft / l->m, -arm * ft / l->inertia, vt};
}

static ob_state ob_axpy(ob_state s, double h, ob_state k)
{
    return (ob_state){s.d + h * k.d, s.dd + h * k.dd, s.vx + h * k.vx, s.wy + h * k.wy,
                      s.u + h * k.u};
}

/// k1 + 2 k2 + 2 k3 + k4 (RK4's weights).
static ob_state ob_sum4(ob_state k1, ob_state k2, ob_state k3, ob_state k4)
{
    return (ob_state){k1.d + 2.0 * (k2.d + k3.d) + k4.d, k1.dd + 2.0 * (k2.dd + k3.dd) + k4.dd,
                      k1.vx + 2.0 * (k2.vx + k3.vx) + k4.vx, k1.wy + 2.0 * (k2.wy + k3.wy) + k4.wy,
                      k1.u + 2.0 * (k2.u + k3.u) + k4.u};
}

bdl_verify_oblique bdl_verify_oblique_reference(double vt, double mu, int sliding)
{
    const double r = 0.5 * ob_d, m = ob_rho * BDL_PI / 6.0 * ob_d * ob_d * ob_d;
    const double es = ob_youngs / (2.0 * (1.0 - ob_nu * ob_nu));
    const double gs = ob_youngs / (2.0 * (1.0 + ob_nu)) / (2.0 * (2.0 - ob_nu));
    const ob_law l = {m,  0.4 * m * r * r, r, (4.0 / 3.0) * es * sqrt(r), 8.0 * gs * sqrt(r),
                      mu, sliding};
    const double h = bdl_verify_oblique_contact_time() / 2e5;
    ob_state s = {0.0, ob_vn, vt, 0.0, 0.0};
    bdl_verify_oblique o = {.vt1 = vt, .vn1 = ob_vn};
    for (; o.steps < 400000 && !(o.steps > 0 && s.d <= 0.0); ++o.steps) {
        const ob_state k1 = ob_rate(&l, s), k2 = ob_rate(&l, ob_axpy(s, 0.5 * h, k1));
        const ob_state k3 = ob_rate(&l, ob_axpy(s, 0.5 * h, k2));
        const ob_state k4 = ob_rate(&l, ob_axpy(s, h, k3));
        s = ob_axpy(s, h / 6.0, ob_sum4(k1, k2, k3, k4));
    }
    o.vt2 = s.vx - r * s.wy;
    o.vn2 = -s.dd;
    const double e0 = 0.5 * m * (vt * vt + ob_vn * ob_vn);
    o.energy_error =
        (0.5 * m * (s.vx * s.vx + s.dd * s.dd) + 0.5 * l.inertia * s.wy * s.wy) / e0 - 1.0;
    return o;
}

// ---- the theory of Maw, Barber & Fawcett ----

double bdl_verify_mbf_psi2(double nu, double inertia_factor, double psi1, int springs)
{
    // Units: overlap delta* = (m v^2/k_h)^(2/5), time delta*/v, force k_h delta*^(3/2); the
    // contact radius is sqrt(x), the normal density 3/4 (so that F_n = x^(3/2)) and the
    // tangential 3/4 kappa (so that k_t = 3/2 kappa sqrt(x), Mindlin's 8 G* a). w = v_t/v_n = 1.
    const double kappa = 2.0 * (1.0 - nu) / (2.0 - nu), normal = 0.75, shear = 0.75 * kappa;
    const double mu = kappa / psi1, width = 1.2 / springs, h = 0.2 / springs;
    double *q = calloc((size_t)springs, sizeof *q); // the springs' tangential displacements
    if (!q)
        return NAN;
    double x = 0.0, xd = 1.0, vt = 1.0, ax = 0.0, at = 0.0;
    for (long k = 0; k < 100L * springs && !(k > 0 && x < 0.0); ++k) {
        xd += 0.5 * h * ax, vt += 0.5 * h * at; // velocity Verlet, as fine as the springs
        x += h * xd;
        double sum = 0.0;
        for (int i = 0; i < springs; ++i) {
            const double c = (i + 0.5) * width, limit = mu * normal * (x - c * c) / shear;
            const double qi = q[i] + h * vt;
            q[i] = limit <= 0.0 ? 0.0 : (qi > limit ? limit : (qi < -limit ? -limit : qi));
            sum += q[i]; // out of contact (limit <= 0) a spring holds nothing: released
        }
        ax = -(x > 0.0 ? x * sqrt(x) : 0.0);
        at = -inertia_factor * 2.0 * width * shear * sum;
        xd += 0.5 * h * ax, vt += 0.5 * h * at;
    }
    free(q);
    return kappa * vt / mu;
}
