// bedlam — capsules for the synthetic camera: the nearest hit of a ray, the volume inside boxes.
//
// Ray. The capsule is the union of the cylinder |(y - x) - ((y - x).u) u| <= r clipped to the
// shaft |(y - x).u| <= h and the two end balls |y - (x +- e)| <= r. A ray's first point in a union
// of convex sets is the earliest of its first points in each. It enters the clipped cylinder
// through the side (the infinite cylinder's entry, when that lies on the shaft) or through an end
// disc, and an end disc lies inside that end's ball: so the side entry and the balls' entries
// decide, the nearest of them wins.
//
// Volume. With s the position along the axis, V_box = \int A_box(s) ds, A_box(s) the area of the
// cross-section (a disc of radius rho(s): r on the shaft, sqrt(r^2 - (|s| - h)^2) on the caps)
// inside the box. On the caps s = +-(h + r sin(theta)), so that rho = r cos(theta) and
// ds = r cos(theta) dtheta: no square root at the tips. A_box is analytic in s except where the
// disc's edge touches a face of the box (a kink like d^(3/2); nearly a step when the face is
// across the axis), where an edge of the box crosses the disc's edge, and where the section
// passes a corner of the box inside the capsule. The integral is split at all of these for the
// boxes the capsule reaches, and each piece is integrated by 8-point Gauss-Legendre. A disc's
// area inside a box is exact: the box's section, a convex polygon, clipped from a square around
// the disc, intersected with the circle edge by edge. The boxes of a grid share the nodes, and
// their polygons tile each section, so the volumes over boxes covering a capsule add up to its
// volume to rounding.
#include "dia/capsule.h"

#include <math.h>
#include <stdlib.h>

int bdl_dia_ray_capsule(bdl_vec3 o, bdl_vec3 d, bdl_vec3 x, bdl_vec3 e, double r, double *t,
                        bdl_vec3 *normal)
{
    const double h = bdl_v3_len(e);
    const bdl_vec3 u = bdl_v3_scale(e, 1.0 / h), oc = bdl_v3_sub(o, x);
    const double du = bdl_v3_dot(d, u), ou = bdl_v3_dot(oc, u);
    double best = INFINITY;
    bdl_vec3 centre = x; // the point of the axis nearest the hit: the normal points away from it
    // Side: the parts across the axis, |oc_perp + t d_perp| = r.
    const bdl_vec3 dp = bdl_v3_madd(d, u, -du), op = bdl_v3_madd(oc, u, -ou);
    const double a = bdl_v3_dot(dp, dp), b = bdl_v3_dot(op, dp), c = bdl_v3_dot(op, op) - r * r;
    const double disc = b * b - a * c;
    if (a > 0.0 && disc >= 0.0) { // a = 0: the ray runs along the axis and meets only the ends
        double ts = (-b - sqrt(disc)) / a, s = ou + ts * du;
        if (fabs(s) <= h) {
            best = ts;
            centre = bdl_v3_madd(x, u, s);
        }
    }
    for (int side = -1; side <= 1; side += 2) {
        const bdl_vec3 end = bdl_v3_madd(x, e, side), oe = bdl_v3_sub(o, end);
        double be = bdl_v3_dot(oe, d), de = be * be - (bdl_v3_dot(oe, oe) - r * r);
        if (de < 0.0)
            continue;
        double te = -be - sqrt(de);
        if (te < best) {
            best = te;
            centre = end;
        }
    }
    if (!(best > 0.0) || best == INFINITY)
        return 0;
    *t = best;
    *normal = bdl_v3_scale(bdl_v3_sub(bdl_v3_madd(o, d, best), centre), 1.0 / r);
    return 1;
}

double bdl_dia_capsule_volume(double r, double h)
{
    return BDL_PI * r * r * (2.0 * h + 4.0 / 3.0 * r);
}

// ---- volume inside boxes ----

/// The capsule in components, with two unit vectors p, q across the axis (the section's plane
/// coordinates) and across[a] = |(p_a, q_a)|: a section's half-extent along axis a per unit radius.
typedef struct capsule {
    double x[3], u[3], p[3], q[3], across[3];
    double h, r;
} capsule;

static capsule make_capsule(bdl_vec3 x, bdl_vec3 e, double r)
{
    capsule k = {{x.x, x.y, x.z}, {0.0, 0.0, 1.0}, {0}, {0}, {0}, bdl_v3_len(e), r};
    if (k.h > 0.0)
        k.u[0] = e.x / k.h, k.u[1] = e.y / k.h, k.u[2] = e.z / k.h;
    // p: the world axis most across u, made normal to it; q = u x p.
    int a = fabs(k.u[0]) <= fabs(k.u[1]) && fabs(k.u[0]) <= fabs(k.u[2]) ? 0
            : fabs(k.u[1]) <= fabs(k.u[2])                               ? 1
                                                                         : 2;
    double n = 0.0;
    for (int i = 0; i < 3; ++i) {
        k.p[i] = (i == a) - k.u[a] * k.u[i];
        n += k.p[i] * k.p[i];
    }
    for (int i = 0; i < 3; ++i)
        k.p[i] /= sqrt(n);
    for (int i = 0; i < 3; ++i) {
        int j = (i + 1) % 3, l = (i + 2) % 3;
        k.q[i] = k.u[j] * k.p[l] - k.u[l] * k.p[j];
    }
    for (int i = 0; i < 3; ++i)
        k.across[i] = hypot(k.p[i], k.q[i]);
    return k;
}

/// Half-plane n.w <= d of the section's plane: clips the convex polygon in (n vertices) into out.
static int clip(const double (*in)[2], int n, double nx, double ny, double d, double (*out)[2])
{
    int m = 0;
    for (int i = 0; i < n; ++i) {
        const double *a = in[i], *b = in[(i + 1) % n];
        double fa = nx * a[0] + ny * a[1] - d, fb = nx * b[0] + ny * b[1] - d;
        if (fa <= 0.0) {
            out[m][0] = a[0], out[m][1] = a[1];
            ++m;
        }
        if ((fa < 0.0 && fb > 0.0) || (fa > 0.0 && fb < 0.0)) {
            double f = fa / (fa - fb);
            out[m][0] = a[0] + f * (b[0] - a[0]), out[m][1] = a[1] + f * (b[1] - a[1]);
            ++m;
        }
    }
    return m;
}

/// Area of the circle of radius R about the origin swept from a to b (signed).
static double sector(const double a[2], const double b[2], double R)
{
    return 0.5 * R * R * atan2(a[0] * b[1] - a[1] * b[0], a[0] * b[0] + a[1] * b[1]);
}

/// Signed area of the triangle (origin, a, b) inside the circle of radius R about the origin: the
/// part of the edge inside the circle gives a triangle, the parts outside give sectors.
static double circle_triangle(const double a[2], const double b[2], double R)
{
    const double dx = b[0] - a[0], dy = b[1] - a[1];
    const double qa = dx * dx + dy * dy, qb = a[0] * dx + a[1] * dy;
    const double disc = qb * qb - qa * (a[0] * a[0] + a[1] * a[1] - R * R);
    if (!(qa > 0.0))
        return 0.0;
    if (disc <= 0.0)
        return sector(a, b, R);
    const double sq = sqrt(disc);
    double t0 = (-qb - sq) / qa, t1 = (-qb + sq) / qa;
    if (t1 <= 0.0 || t0 >= 1.0)
        return sector(a, b, R);
    t0 = fmax(t0, 0.0), t1 = fmin(t1, 1.0);
    const double p[2] = {a[0] + t0 * dx, a[1] + t0 * dy}, q[2] = {a[0] + t1 * dx, a[1] + t1 * dy};
    return sector(a, p, R) + 0.5 * (p[0] * q[1] - p[1] * q[0]) + sector(q, b, R);
}

/// Area of the disc (centre c, radius rho, across the axis) inside the box lo..hi. A box is
/// half-open along an axis the sections lie across, so a section in a shared face counts once.
static double disc_box_area(const capsule *k, const double c[3], double rho, const double lo[3],
                            const double hi[3])
{
    double poly[2][16][2] = {{{-rho, -rho}, {rho, -rho}, {rho, rho}, {-rho, rho}}};
    int n = 4, cur = 0, clipped = 0;
    for (int a = 0; a < 3; ++a)
        for (int upper = 0; upper <= 1; ++upper) {
            // The face as a half-plane of the section: sign (p_a, q_a).w <= d.
            const double sign = upper ? 1.0 : -1.0, d = upper ? hi[a] - c[a] : c[a] - lo[a];
            const double bn = k->across[a];
            if (bn == 0.0) {
                if (upper ? d <= 0.0 : d < 0.0)
                    return 0.0;
                continue;
            }
            if (d >= rho * bn) // the face misses the disc
                continue;
            if (d <= -rho * bn)
                return 0.0;
            n = clip((const double(*)[2])poly[cur], n, sign * k->p[a], sign * k->q[a], d,
                     poly[1 - cur]);
            cur = 1 - cur;
            clipped = 1;
        }
    if (!clipped)
        return BDL_PI * rho * rho;
    double area = 0.0;
    for (int i = 0; i < n; ++i)
        area += circle_triangle(poly[cur][i], poly[cur][(i + 1) % n], rho);
    return area;
}

/// Number of the n increasing values p[] that are <= v (strict: < v).
static int count_below(const double *p, int n, double v, int strict)
{
    int lo = 0, hi = n;
    while (lo < hi) {
        int m = (lo + hi) / 2;
        if (strict ? p[m] < v : p[m] <= v)
            lo = m + 1;
        else
            hi = m;
    }
    return lo;
}

/// The cells along axis a that the interval lo..hi reaches: first..last (none when first > last).
static void cell_range(const bdl_dia_grid *g, int a, double lo, double hi, int *first, int *last)
{
    *first = count_below(g->plane[a] + 1, g->n[a], lo, 0);
    *last = count_below(g->plane[a], g->n[a], hi, 0) - 1;
}

/// One section (at s along the axis, radius rho, quadrature weight w): its area in each box.
static void add_section(const capsule *k, const bdl_dia_grid *g, double s, double rho, double w,
                        double *volume)
{
    double c[3];
    int first[3], last[3];
    for (int a = 0; a < 3; ++a) {
        c[a] = k->x[a] + s * k->u[a];
        const double ext = rho * k->across[a];
        cell_range(g, a, c[a] - ext, c[a] + ext, &first[a], &last[a]);
        if (first[a] > last[a])
            return;
    }
    for (int i2 = first[2]; i2 <= last[2]; ++i2)
        for (int i1 = first[1]; i1 <= last[1]; ++i1)
            for (int i0 = first[0]; i0 <= last[0]; ++i0) {
                const int i[3] = {i0, i1, i2};
                double lo[3], hi[3];
                for (int a = 0; a < 3; ++a)
                    lo[a] = g->plane[a][i[a]], hi[a] = g->plane[a][i[a] + 1];
                double area = disc_box_area(k, c, rho, lo, hi);
                if (area != 0.0)
                    volume[((size_t)i2 * g->n[1] + i1) * g->n[0] + i0] += w * area;
            }
}

// 8-point Gauss-Legendre nodes and weights on [-1, 1].
static const double gl8_x[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                0.7966664774136267,  0.9602898564975363};
static const double gl8_w[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                0.2223810344533745, 0.1012285362903763};

/// One smooth piece a..b of the parameter: s on the shaft (side 0), theta on the cap of that side.
static void add_piece(const capsule *k, const bdl_dia_grid *g, int side, double a, double b,
                      double *volume)
{
    if (!(b > a))
        return;
    const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    for (int i = 0; i < 8; ++i) {
        const double t = mid + half * gl8_x[i];
        double w = half * gl8_w[i], s = t, rho = k->r;
        if (side != 0) {
            rho = k->r * cos(t);
            s = side * (k->h + k->r * sin(t));
            w *= rho; // ds = r cos(theta) dtheta
        }
        add_section(k, g, s, rho, w, volume);
    }
}

/// Positions along the axis where a section's area in a box is not smooth, each kept only on the
/// piece whose surface (the cylinder, or the ball of one end) produced it.
typedef struct events {
    double *s;
    int n, cap;
    double h, r;
} events;

static void on_shaft(events *ev, double s)
{
    if (fabs(s) < ev->h && ev->n < ev->cap)
        ev->s[ev->n++] = s;
}

static void on_cap(events *ev, int side, double s)
{
    const double beyond = side * s - ev->h;
    if (beyond > 0.0 && beyond < ev->r && ev->n < ev->cap)
        ev->s[ev->n++] = s;
}

/// The plane x_a = plane touches the sections' edges: on the shaft where the disc's extent along
/// a reaches it; on a cap at the ends along the axis of the circle it cuts from the ball.
static void face_events(const capsule *k, int a, double plane, events *ev)
{
    const double ua = k->u[a], b = k->across[a], d0 = plane - k->x[a];
    if (ua != 0.0) {
        on_shaft(ev, (d0 - k->r * b) / ua);
        on_shaft(ev, (d0 + k->r * b) / ua);
    }
    for (int side = -1; side <= 1; side += 2) {
        const double d = d0 - side * k->h * ua; // from the end's centre to the plane
        if (fabs(d) >= k->r)
            continue;
        const double rho = sqrt(k->r * k->r - d * d);
        on_cap(ev, side, side * k->h + d * ua - rho * b);
        on_cap(ev, side, side * k->h + d * ua + rho * b);
    }
}

/// The line through p0 along axis c (an edge of the boxes) crosses the surface: the cylinder
/// |w_perp + t (e_c)_perp| = r on the shaft, the end balls on the caps.
static void edge_events(const capsule *k, int c, const double p0[3], events *ev)
{
    double w[3], wu = 0.0, ww = 0.0;
    for (int a = 0; a < 3; ++a) {
        w[a] = p0[a] - k->x[a];
        wu += w[a] * k->u[a];
        ww += w[a] * w[a];
    }
    const double uc = k->u[c], r2 = k->r * k->r;
    const double qa = 1.0 - uc * uc, qb = w[c] - uc * wu, disc = qb * qb - qa * (ww - wu * wu - r2);
    if (qa > 0.0 && disc > 0.0) { // qa = 0: the edge runs along the axis, at a fixed distance
        const double sq = sqrt(disc);
        on_shaft(ev, wu + uc * (-qb - sq) / qa);
        on_shaft(ev, wu + uc * (-qb + sq) / qa);
    }
    for (int side = -1; side <= 1; side += 2) {
        const double sh = side * k->h; // w1 = w - sh u: from the end's centre
        const double b = w[c] - sh * uc, de = b * b - (ww - 2.0 * sh * wu + sh * sh - r2);
        if (de <= 0.0)
            continue;
        const double sq = sqrt(de);
        on_cap(ev, side, wu + uc * (-b - sq));
        on_cap(ev, side, wu + uc * (-b + sq));
    }
}

/// A corner of the boxes inside the capsule: the section through it changes shape there.
static void corner_event(const capsule *k, const double v[3], events *ev)
{
    double w[3], s = 0.0, ww = 0.0;
    for (int a = 0; a < 3; ++a) {
        w[a] = v[a] - k->x[a];
        s += w[a] * k->u[a];
        ww += w[a] * w[a];
    }
    const double sc = fmax(-k->h, fmin(k->h, s)); // nearest point of the segment
    if (ww - 2.0 * s * sc + sc * sc >= k->r * k->r)
        return;
    if (fabs(s) < k->h)
        on_shaft(ev, s);
    else
        on_cap(ev, s > 0.0 ? 1 : -1, s);
}

/// The planes of the grid strictly inside the capsule's extent along each axis.
typedef struct planes {
    const double *v[3];
    int m[3];
} planes;

static void collect_events(const capsule *k, const planes *pl, events *ev)
{
    for (int a = 0; a < 3; ++a)
        for (int j = 0; j < pl->m[a]; ++j)
            face_events(k, a, pl->v[a][j], ev);
    for (int c = 0; c < 3; ++c) { // edges along c, where the planes of the other two axes meet
        const int a = (c + 1) % 3, b = (c + 2) % 3;
        for (int i = 0; i < pl->m[a]; ++i)
            for (int j = 0; j < pl->m[b]; ++j) {
                double p0[3] = {0};
                p0[a] = pl->v[a][i], p0[b] = pl->v[b][j];
                edge_events(k, c, p0, ev);
            }
    }
    for (int i = 0; i < pl->m[0]; ++i)
        for (int j = 0; j < pl->m[1]; ++j)
            for (int l = 0; l < pl->m[2]; ++l) {
                const double v[3] = {pl->v[0][i], pl->v[1][j], pl->v[2][l]};
                corner_event(k, v, ev);
            }
}

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/// The shaft from -h to h, then each cap from theta = 0 (the shaft's end) to pi/2 (the tip),
/// split at the events (sorted).
static void integrate(const capsule *k, const bdl_dia_grid *g, const double *s, int n,
                      double *volume)
{
    double prev = -k->h;
    for (int i = 0; i < n; ++i)
        if (fabs(s[i]) < k->h) {
            add_piece(k, g, 0, prev, s[i], volume);
            prev = s[i];
        }
    add_piece(k, g, 0, prev, k->h, volume);
    for (int side = -1; side <= 1; side += 2) {
        prev = 0.0;
        for (int i = 0; i < n; ++i) {
            const double beyond = (side * s[side > 0 ? i : n - 1 - i] - k->h) / k->r;
            if (!(beyond > 0.0 && beyond < 1.0))
                continue;
            const double theta = asin(beyond);
            add_piece(k, g, side, prev, theta, volume);
            prev = theta;
        }
        add_piece(k, g, side, prev, 0.5 * BDL_PI, volume);
    }
}

int bdl_dia_capsule_grid_volume(bdl_vec3 x, bdl_vec3 e, double r, const bdl_dia_grid *g,
                                double *volume)
{
    const capsule k = make_capsule(x, e, r);
    const double ext[3] = {fabs(e.x) + r, fabs(e.y) + r, fabs(e.z) + r};
    planes pl;
    for (int a = 0; a < 3; ++a) {
        int first, last;
        cell_range(g, a, k.x[a] - ext[a], k.x[a] + ext[a], &first, &last);
        if (first > last)
            return 1; // outside the grid
        int j0 = count_below(g->plane[a], g->n[a] + 1, k.x[a] - ext[a], 0);
        int j1 = count_below(g->plane[a], g->n[a] + 1, k.x[a] + ext[a], 1);
        pl.v[a] = g->plane[a] + j0;
        pl.m[a] = j1 > j0 ? j1 - j0 : 0;
    }
    const int *m = pl.m;
    events ev = {NULL, 0, 0, k.h, k.r};
    ev.cap = 6 * (m[0] + m[1] + m[2]) + 6 * (m[0] * m[1] + m[1] * m[2] + m[2] * m[0]) +
             m[0] * m[1] * m[2];
    if (ev.cap > 0 && !(ev.s = malloc((size_t)ev.cap * sizeof(double))))
        return 0;
    collect_events(&k, &pl, &ev);
    if (ev.n > 1)
        qsort(ev.s, (size_t)ev.n, sizeof(double), compare_double);
    integrate(&k, g, ev.s, ev.n, volume);
    free(ev.s);
    return 1;
}

double bdl_dia_capsule_box_volume(bdl_vec3 x, bdl_vec3 e, double r, bdl_vec3 lo, bdl_vec3 hi)
{
    const double px[2] = {lo.x, hi.x}, py[2] = {lo.y, hi.y}, pz[2] = {lo.z, hi.z};
    const bdl_dia_grid g = {{1, 1, 1}, {px, py, pz}};
    double v = 0.0;
    return bdl_dia_capsule_grid_volume(x, e, r, &g, &v) ? v : NAN;
}
