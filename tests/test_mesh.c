// Mesh walls (core/mesh.h, dem/walls.h): a sphere on a mesh feels what it would feel from the
// analytic surface it touches.
//
// 1. On a face, on an edge and at a vertex: the force equals that of a plane through the touched
//    point with the normal from it to the centre (that is the plane, line and point contact) to
//    1e-12 relative; on shared edges and vertices of a flat mesh and at the apex of a pyramid the
//    contact is counted once; a mesh is touched from either side.
// 2. Rolling: a sphere carried across a plate of 200 triangles (over faces, edges, diagonals and
//    vertices) feels the plane's force at every one of 2001 positions (1e-9 relative).
// 3. A bed settles in a box of 12 triangles (binary STL) as in the primitive box: bed heights
//    within one diameter.
// 4. A silo of 1500 beads discharging through a mesh orifice: every bead out counted, the mass
//    balance closed (the rate against Beverloo is `bedlam verify silo_beverloo`).
// 5. A turning mesh: a plate turned by an angle is touched as the turned plane (1e-12); a paddle
//    turning about an axis in its plane sweeps up a sphere at rest (found by the neighbour lists
//    through the sweep) and throws it off at (1 + e) times its surface speed at the contact.
// 6. Fills (random and pour) inside a closed mesh: volume exact, every bead wholly inside.
// 7. The reader: ASCII STL, binary STL and OBJ of the same square give the same mesh; bad files
//    (empty, truncated, a huge header, NaN, non-manifold, zero area) are refused with a reason.
#define _POSIX_C_SOURCE 200809L // mkdtemp, truncate
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "core/mesh.h"
#include "scene_util.h"

static char folder[] = "/tmp/bedlam-mesh-XXXXXX";
static const double radius = 0.002;

typedef struct tri {
    bdl_vec3 v[3];
} tri;

static void path_of(char *out, size_t n, const char *name)
{
    snprintf(out, n, "%s/%s", folder, name);
}

/// Opens NAME in the test's folder for writing (a failed check and NULL if it cannot).
static FILE *open_in(const char *name, const char *mode)
{
    char path[256];
    path_of(path, sizeof path, name);
    FILE *f = fopen(path, mode);
    CHECK(f != NULL);
    return f;
}

static void write_text(const char *name, const char *text)
{
    FILE *f = open_in(name, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

static void write_stl_ascii(const char *name, const tri *t, int n)
{
    FILE *f = open_in(name, "w");
    if (!f)
        return;
    fprintf(f, "solid test\n");
    for (int k = 0; k < n; ++k) {
        fprintf(f, "  facet normal 0 0 0\n    outer loop\n");
        for (int c = 0; c < 3; ++c)
            fprintf(f, "      vertex %.17g %.17g %.17g\n", t[k].v[c].x, t[k].v[c].y, t[k].v[c].z);
        fprintf(f, "    endloop\n  endfacet\n");
    }
    fprintf(f, "endsolid test\n");
    fclose(f);
}

static void write_stl_binary(const char *name, const tri *t, int n, uint32_t claimed, long cut)
{
    FILE *f = open_in(name, "wb");
    if (!f)
        return;
    char header[80] = "binary test mesh";
    fwrite(header, 1, 80, f);
    fwrite(&claimed, 4, 1, f);
    for (int k = 0; k < n; ++k) {
        float rec[12] = {0};
        for (int c = 0; c < 3; ++c) {
            rec[3 + 3 * c] = (float)t[k].v[c].x;
            rec[4 + 3 * c] = (float)t[k].v[c].y;
            rec[5 + 3 * c] = (float)t[k].v[c].z;
        }
        uint16_t attr = 0;
        fwrite(rec, 4, 12, f);
        fwrite(&attr, 2, 1, f);
    }
    fclose(f);
    char path[256];
    path_of(path, sizeof path, name);
    if (cut > 0)
        CHECK(truncate(path, cut) == 0);
}

/// A square plate [-h, h]^2 at height z, split into m x m squares of two triangles each (a
/// corner shared by several squares is computed once, so that it welds).
static int plate(tri *out, int m, double h, double z)
{
    int n = 0;
    for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) {
            double x0 = -h + 2.0 * h * i / m, x1 = -h + 2.0 * h * (i + 1) / m;
            double y0 = -h + 2.0 * h * j / m, y1 = -h + 2.0 * h * (j + 1) / m;
            bdl_vec3 a = bdl_v3(x0, y0, z), b = bdl_v3(x1, y0, z), c = bdl_v3(x1, y1, z),
                     d = bdl_v3(x0, y1, z);
            out[n++] = (tri){{a, b, c}};
            out[n++] = (tri){{a, c, d}};
        }
    return n;
}

/// A world of one glass sphere at x (read from a CSV file) against the wall described by `wall`,
/// under `gravity`; it may start overlapping the wall by up to half its radius.
static bdl_world *one_sphere(const char *wall, bdl_vec3 x, const char *gravity)
{
    char csv[256], row[128];
    path_of(csv, sizeof csv, "one.csv");
    snprintf(row, sizeof row, "x,y,z\n%.17g,%.17g,%.17g\n", x.x, x.y, x.z);
    write_text("one.csv", row);
    return bdl_test_world(
        "[guards]\ninitial_overlap = 0.5\n[run]\nend_time = 1\ngravity = %s\n[domain]\n"
        "min = -0.05 -0.05 -0.05\nmax = 0.05 0.05 0.05\n[species glass]\ndiameter = %g\n"
        "density = 2500\nyoungs_modulus = 1e7\npoisson_ratio = 0.25\nrestitution = 0.7\n"
        "friction = 0.4\n[wall w]\n%s\n[create one]\ntype = file\nspecies = glass\nfile = %s\n",
        gravity, 2.0 * radius, wall, csv);
}

/// The force on one sphere at x (at rest, no gravity) from the wall described by `wall`.
static bdl_vec3 force_at(const char *wall, bdl_vec3 x)
{
    bdl_world *w = one_sphere(wall, x, "0 0 0");
    bdl_vec3 force = w->particles.load[0].force;
    bdl_world_destroy(w);
    return force;
}

/// The plane through q whose normal points from q to x.
static bdl_vec3 plane_force(bdl_vec3 q, bdl_vec3 x)
{
    bdl_vec3 n = bdl_v3_normalize(bdl_v3_sub(x, q));
    char wall[256];
    snprintf(wall, sizeof wall,
             "type = plane\npoint = %.17g %.17g %.17g\nnormal = %.17g %.17g %.17g", q.x, q.y, q.z,
             n.x, n.y, n.z);
    return force_at(wall, x);
}

static double rel_diff(bdl_vec3 a, bdl_vec3 b)
{
    return bdl_v3_len(bdl_v3_sub(a, b)) / bdl_v3_len(b);
}

static void check_feature(const char *mesh_wall, const char *what, bdl_vec3 q, bdl_vec3 x)
{
    bdl_vec3 fm = force_at(mesh_wall, x), fp = plane_force(q, x);
    double e = rel_diff(fm, fp);
    printf("| %s | %.4g %.4g %.4g | %.3e |\n", what, fp.x, fp.y, fp.z, e);
    CHECK_MSG(bdl_v3_len(fp) > 0.0 && e <= 1e-12, "%s: mesh force differs by %.3e", what, e);
}

static int box_triangles(tri *t);

/// The corners and edges of a box of 12 triangles push as the primitive box's faces do.
static void box_corner(void)
{
    tri t[12];
    write_stl_ascii("box_ascii.stl", t, box_triangles(t));
    char mesh[300];
    snprintf(mesh, sizeof mesh, "type = mesh\nfile = %s/box_ascii.stl", folder);
    const char *box = "type = box\nmin = 0 0 0\nmax = 0.02 0.02 0.06";
    const bdl_vec3 at[3] = {bdl_v3(0.0019, 0.0019, 0.0019), bdl_v3(0.0019, 0.011, 0.0019),
                            bdl_v3(0.013, 0.0185, 0.03)};
    const char *what[3] = {"box of 12 triangles, in a corner (3 faces)",
                           "box of 12 triangles, along an edge (2 faces)",
                           "box of 12 triangles, on a side"};
    for (int k = 0; k < 3; ++k) {
        bdl_vec3 fm = force_at(mesh, at[k]), fb = force_at(box, at[k]);
        double e = rel_diff(fm, fb);
        printf("| %s | %.4g %.4g %.4g | %.3e |\n", what[k], fb.x, fb.y, fb.z, e);
        CHECK_MSG(bdl_v3_len(fb) > 0.0 && e <= 1e-12, "%s: differs by %.3e", what[k], e);
    }
}

static void features(void)
{
    tri t[64];
    int n = plate(t, 4, 0.02, 0.0);
    write_stl_ascii("plate.stl", t, n);
    // A pyramid: apex (0, 0, 0.01) over the square [-0.005, 0.005]^2 at z = 0.
    bdl_vec3 apex = bdl_v3(0, 0, 0.01), c[4] = {bdl_v3(-0.005, -0.005, 0), bdl_v3(0.005, -0.005, 0),
                                                bdl_v3(0.005, 0.005, 0), bdl_v3(-0.005, 0.005, 0)};
    tri pyr[4];
    for (int k = 0; k < 4; ++k)
        pyr[k] = (tri){{c[k], c[(k + 1) % 4], apex}};
    write_stl_ascii("pyramid.stl", pyr, 4);
    char plate_wall[512], pyramid_wall[512];
    snprintf(plate_wall, sizeof plate_wall, "type = mesh\nfile = %s/plate.stl", folder);
    snprintf(pyramid_wall, sizeof pyramid_wall, "type = mesh\nfile = %s/pyramid.stl", folder);
    const double z = 0.0019, s = 0.01;
    printf("\nSphere (r = %g m) against a mesh and against the plane through the touched point\n\n"
           "| where | force of the plane (N) | relative difference |\n|---|---|---|\n",
           radius);
    check_feature(plate_wall, "face", bdl_v3(0.003, -0.004, 0), bdl_v3(0.003, -0.004, z));
    check_feature(plate_wall, "face, from below", bdl_v3(0.003, -0.004, 0),
                  bdl_v3(0.003, -0.004, -z));
    check_feature(plate_wall, "on an inner edge", bdl_v3(s, 0.003, 0), bdl_v3(s, 0.003, z));
    check_feature(plate_wall, "on a diagonal", bdl_v3(0.004, 0.004, 0), bdl_v3(0.004, 0.004, z));
    check_feature(plate_wall, "on an inner vertex (6 triangles)", bdl_v3(s, s, 0), bdl_v3(s, s, z));
    check_feature(plate_wall, "beyond the border edge", bdl_v3(0.02, 0.001, 0),
                  bdl_v3(0.021, 0.001, 0.0015));
    check_feature(plate_wall, "beyond the corner vertex", bdl_v3(0.02, 0.02, 0),
                  bdl_v3(0.021, 0.021, 0.0012));
    check_feature(pyramid_wall, "at a pyramid's apex (4 triangles)", apex,
                  bdl_v3_add(apex, bdl_v3(0.0002, 0.0001, 0.0018)));
    // Over the ridge between two faces of the pyramid: the edge from the corner to the apex.
    bdl_vec3 mid = bdl_v3_scale(bdl_v3_add(c[1], apex), 0.5);
    bdl_vec3 out = bdl_v3_normalize(bdl_v3(1, -1, 1)); // normal to that edge, between the faces
    check_feature(pyramid_wall, "on a pyramid's ridge (2 triangles)", mid,
                  bdl_v3_madd(mid, out, 0.0018));
    box_corner();
    // A disk with a hole (an orifice plate) of 64 sides: on its face it is the plane; over the
    // hole, nothing; beyond a corner of its rim's polygon, the point.
    const char *disk = "type = disk\npoint = 0 0 0\nnormal = 0 0 1\nradius = 0.03\n"
                       "hole_radius = 0.008\nsegments = 64";
    check_feature(disk, "disk of 64 sides, on its face", bdl_v3(0.015, 0.004, 0),
                  bdl_v3(0.015, 0.004, z));
    const bdl_vec3 corner = bdl_v3(0.0, 0.03, 0.0); // a vertex of the rim
    check_feature(disk, "disk, beyond a corner of its rim", corner,
                  bdl_v3_add(corner, bdl_v3(0.0, 0.001, 0.0015)));
    const bdl_vec3 none = force_at(disk, bdl_v3(0.0, 0.0, z));
    printf("| disk, over the middle of its hole | (no contact) | %.3e N |\n", bdl_v3_len(none));
    CHECK(bdl_v3_len(none) == 0.0);
}

/// A sphere carried across 200 triangles at a fixed overlap feels the plane's force throughout.
static void rolling(void)
{
    tri t[256];
    int n = plate(t, 10, 0.02, 0.0);
    write_stl_ascii("fine.stl", t, n);
    char mesh[300];
    snprintf(mesh, sizeof mesh, "type = mesh\nfile = %s/fine.stl", folder);
    const bdl_vec3 start = bdl_v3(-0.015, -0.0035, 0.0019);
    bdl_world *wm = one_sphere(mesh, start, "0 0 0");
    bdl_world *wp = one_sphere("type = plane\npoint = 0 0 0\nnormal = 0 0 1", start, "0 0 0");
    double worst = 0.0;
    for (int k = 0; k <= 2000; ++k) {
        double x = -0.015 + 0.03 * k / 2000.0;
        bdl_vec3 pos = bdl_v3(x, 0.25 * x, 0.0019); // crosses edges, diagonals and a vertex
        if (k == 1000)
            pos = bdl_v3(0.0, 0.0, 0.0019); // the vertex at the centre
        wm->particles.pos[0] = wp->particles.pos[0] = pos;
        CHECK(bdl_world_compute_forces(wm) == BDL_OK && bdl_world_compute_forces(wp) == BDL_OK);
        double e = rel_diff(wm->particles.load[0].force, wp->particles.load[0].force);
        if (e > 1e-9)
            printf("  at (%.6f, %.6f): mesh %.6g plane %.6g\n", pos.x, pos.y,
                   wm->particles.load[0].force.z, wp->particles.load[0].force.z);
        worst = fmax(worst, e);
    }
    printf("\nRolling across 200 triangles, 2001 positions: largest relative force difference "
           "from the plane %.3e\n",
           worst);
    CHECK_MSG(worst <= 1e-9, "the force jumps by %.3e at an edge", worst);
    bdl_world_destroy(wm);
    bdl_world_destroy(wp);
}

/// A sphere pressed onto the plate by gravity and dragged over 12 mm of it (edges and diagonals)
/// (its velocity set every step, below and above the friction's limit): the force it feels, the
/// tangential spring included, is the plane's at every step, so the spring passes from triangle to
/// triangle.
static void dragging(void)
{
    char mesh[300];
    snprintf(mesh, sizeof mesh, "type = mesh\nfile = %s/fine.stl", folder);
    const bdl_vec3 start = bdl_v3(-0.006, -0.0035, 0.002);
    bdl_world *wm = one_sphere(mesh, start, "0 0 -9.81");
    bdl_world *wp = one_sphere("type = plane\npoint = 0 0 0\nnormal = 0 0 1", start, "0 0 -9.81");
    double worst = 0.0, ft = 0.0;
    long steps = 0;
    while (wm->particles.pos[0].x < 0.006 && steps < 400000) {
        const double speed = steps < 5000 ? 0.002 : 0.05; // sticking, then sliding
        bdl_world *w[2] = {wm, wp};
        for (int k = 0; k < 2; ++k) {
            w[k]->particles.vel[0] = bdl_v3(speed, 0.25 * speed, w[k]->particles.vel[0].z);
            w[k]->particles.omega[0] = bdl_v3_zero();
            CHECK(bdl_world_step(w[k]) == BDL_OK);
        }
        const bdl_vec3 a = wm->particles.load[0].force, b = wp->particles.load[0].force;
        worst = fmax(worst, bdl_v3_len(bdl_v3_sub(a, b)) / fmax(bdl_v3_len(b), 1e-30));
        ft = fmax(ft, hypot(b.x, b.y));
        ++steps;
    }
    printf("\nDragged 12 mm over the plate (%ld steps, tangential force up to %.3g N): largest "
           "relative force difference from the plane %.3e\n",
           steps, ft, worst);
    CHECK(ft > 0.0);
    CHECK_MSG(worst <= 1e-9, "the tangential spring does not pass between triangles: %.3e", worst);
    bdl_world_destroy(wm);
    bdl_world_destroy(wp);
}

/// Plate of 32 triangles in z = 0 turning about x: at angles through a whole turn, points above
/// and below it see the turned plane.
static void turned_plate(void)
{
    tri t[32];
    write_stl_ascii("turn.stl", t, plate(t, 4, 0.02, 0.0));
    char mesh[400];
    snprintf(mesh, sizeof mesh,
             "type = mesh\nfile = %s/turn.stl\nmotion = rotate\nrotation_axis = 1 0 0\n"
             "rotation_center = 0 0 0\nangular_velocity = 1",
             folder);
    bdl_world *w = one_sphere(mesh, bdl_v3(0.0, 0.0, 0.04), "0 0 0");
    double worst = 0.0;
    const double angles[] = {0.3, 1.1, 2.5, 4.0, -0.7};
    const double heights[] = {0.0015, -0.0015, 0.003};
    for (int a = 0; a < 5; ++a) {
        w->walls.angle[0] = angles[a];
        bdl_walls_update(&w->walls, w->time);
        const bdl_quat q = bdl_q_axis_angle(bdl_v3(1.0, 0.0, 0.0), angles[a]);
        for (int k = 0; k < 3; ++k)
            for (int s = 0; s < 7; ++s) {
                const double u = -0.017 + 0.0053 * s, v = 0.013 - 0.0041 * s;
                const bdl_vec3 x = bdl_q_rotate(q, bdl_v3(u, v, heights[k]));
                const bdl_vec3 n0 = bdl_q_rotate(q, bdl_v3(0.0, 0.0, heights[k] > 0 ? 1.0 : -1.0));
                const int32_t *near = NULL;
                const int m = bdl_walls_near(&w->walls, 0, x, &near);
                double gap = INFINITY;
                bdl_vec3 n = bdl_v3_zero();
                for (int i = 0; i < m; ++i) {
                    bdl_vec3 ni;
                    const double g = bdl_wall_tri_gap(&w->walls, near[i], x, radius, &ni);
                    if (g < gap) {
                        gap = g;
                        n = ni;
                    }
                }
                CHECK(m > 0);
                worst = fmax(worst, fabs(gap - (fabs(heights[k]) - radius)) / radius);
                worst = fmax(worst, bdl_v3_len(bdl_v3_sub(n, n0)));
            }
    }
    printf("\nPlate turned by 5 angles: largest difference from the turned plane %.3e\n", worst);
    CHECK_MSG(worst <= 1e-12, "a turned mesh is not the turned plane: %.3e", worst);
    bdl_world_destroy(w);
}

/// A paddle (the rectangle x in [4, 40] mm, z in [-10, 10] mm of the plane y = 0, 16 triangles)
/// turning at 20 rad/s about z meets a frictionless sphere at rest half a radian ahead of it,
/// 25 mm from the axis: the sphere leaves at (1 + e) times the paddle's speed at the contact,
/// omega sqrt(r^2 - R^2), along the paddle's normal.
static void paddle(void)
{
    tri t[16];
    int n = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 2; ++j) {
            const double x0 = 0.004 + 0.009 * i, x1 = x0 + 0.009, z0 = -0.01 + 0.01 * j,
                         z1 = z0 + 0.01;
            const bdl_vec3 a = bdl_v3(x0, 0, z0), b = bdl_v3(x1, 0, z0), c = bdl_v3(x1, 0, z1),
                           d = bdl_v3(x0, 0, z1);
            t[n++] = (tri){{a, b, c}};
            t[n++] = (tri){{a, c, d}};
        }
    write_stl_ascii("paddle.stl", t, n);
    char mesh[400];
    snprintf(mesh, sizeof mesh,
             "type = mesh\nfile = %s/paddle.stl\nmotion = rotate\nrotation_axis = 0 0 1\n"
             "rotation_center = 0 0 0\nangular_velocity = 20\nfriction = 0",
             folder);
    const double r0 = 0.025, phi = 0.5, omega = 20.0, e = 0.7;
    bdl_world *w = one_sphere(mesh, bdl_v3(r0 * cos(phi), r0 * sin(phi), 0.0), "0 0 0");
    int touched = 0;
    long steps = 0;
    while (steps < 200000 && !(touched && bdl_v3_len(w->particles.load[0].force) == 0.0)) {
        CHECK(bdl_world_step(w) == BDL_OK);
        touched |= bdl_v3_len(w->particles.load[0].force) > 0.0;
        ++steps;
    }
    const double expected = (1.0 + e) * omega * sqrt(r0 * r0 - radius * radius);
    const double speed = bdl_v3_len(w->particles.vel[0]);
    printf("Paddle at %g rad/s: sphere thrown at %.5f m/s after %ld steps (turned %.4f rad), "
           "(1 + e) omega r_c = %.5f m/s: %+.2e\n",
           omega, speed, steps, w->walls.angle[0], expected, speed / expected - 1.0);
    CHECK_MSG(touched, "the turning paddle never met the sphere (lists not rebuilt on its sweep)");
    CHECK_MSG(fabs(speed / expected - 1.0) < 0.01, "thrown at %.5f m/s, expected %.5f", speed,
              expected);
    bdl_world_destroy(w);
}

/// The 12 triangles of the box [0, 0.02] x [0, 0.02] x [0, 0.06].
static int box_triangles(tri *t)
{
    const double L[3] = {0.02, 0.02, 0.06};
    int n = 0;
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            int u = (axis + 1) % 3, v = (axis + 2) % 3;
            bdl_vec3 q[4];
            for (int k = 0; k < 4; ++k) {
                double c[3];
                c[axis] = side * L[axis];
                c[u] = (k == 1 || k == 2) * L[u];
                c[v] = (k >= 2) * L[v];
                q[k] = bdl_v3(c[0], c[1], c[2]);
            }
            t[n++] = (tri){{q[0], q[1], q[2]}};
            t[n++] = (tri){{q[0], q[2], q[3]}};
        }
    return n;
}

static double settled_height(const char *wall)
{
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 1\n[domain]\nmin = -0.001 -0.001 -0.001\nmax = 0.021 0.021 0.061\n"
        "[contact]\nlaw = linear\n[species glass]\ndiameter = 0.003\ndensity = 2500\n"
        "stiffness = 500\nrestitution = 0.3\nfriction = 0.3\n[wall w]\n%s\n"
        "[create bed]\ntype = random\nspecies = glass\ncount = 120\nregion_min = 0.0015 0.0015 "
        "0.0015\nregion_max = 0.0185 0.0185 0.0585\n",
        wall);
    while (w->time < 0.6)
        CHECK(bdl_world_step(w) == BDL_OK);
    double top = 0.0, mean = 0.0;
    const bdl_particles *p = &w->particles;
    for (long i = 0; i < p->count; ++i) {
        top = fmax(top, p->pos[i].z);
        mean += p->pos[i].z / (double)p->count;
    }
    printf("| %s | %ld | %.5f | %.5f |\n", strstr(wall, "mesh") ? "12 triangles" : "box", p->count,
           mean, top);
    CHECK(p->count == 120);
    bdl_world_destroy(w);
    return mean;
}

static void box_bed(void)
{
    tri t[12];
    write_stl_binary("box.stl", t, box_triangles(t), 12, 0);
    char mesh[300];
    snprintf(mesh, sizeof mesh, "type = mesh\nfile = %s/box.stl", folder);
    printf("\nA bed of 120 beads (d = 3 mm) settled for 0.6 s\n\n| walls | particles | mean "
           "height (m) | top (m) |\n|---|---|---|---|\n");
    double hm = settled_height(mesh);
    double hb = settled_height("type = box\nmin = 0 0 0\nmax = 0.02 0.02 0.06");
    CHECK_MSG(fabs(hm - hb) < 0.003, "mean heights %.5f and %.5f differ by more than a diameter",
              hm, hb);
}

/// A small silo empties through its mesh orifice: every bead that falls out is counted, and the
/// beads and the mass in and out add up to the start.
static void discharge(void)
{
    bdl_verify_silo s;
    bdl_result r = bdl_verify_silo_discharge(0.018, 1500, 0.75, &s);
    printf("\nSilo of 1500 beads, orifice 18 mm opened at 0.5 s, to 0.75 s: %ld out, %ld left, "
           "mass balance %.1e, rate %.4f kg/s\n",
           s.out, s.left, s.mass_imbalance, s.rate);
    CHECK(r == BDL_OK);
    CHECK(s.out > 100 && s.out + s.left == 1500);
    CHECK(s.mass_imbalance < 1e-12);
}

/// A random fill in a cylindrical region: every bead inside the cylinder inscribed in the box,
/// and the region's volume fraction taken of the cylinder.
static void cylinder_region(void)
{
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 1\n[domain]\nmin = -0.03 -0.03 0\nmax = 0.03 0.03 0.1\n"
        "[contact]\nlaw = linear\n[species glass]\ndiameter = 0.003\ndensity = 2500\n"
        "stiffness = 2000\nrestitution = 0.5\n"
        "[create bed]\ntype = random\nspecies = glass\nvolume_fraction = 0.2\n"
        "region_shape = cylinder\nregion_axis = z\nregion_min = -0.02 -0.025 0.01\n"
        "region_max = 0.02 0.025 0.05\n");
    const bdl_particles *p = &w->particles;
    double worst = 0.0;
    for (long i = 0; i < p->count; ++i)
        worst = fmax(worst, hypot(p->pos[i].x, p->pos[i].y) + p->radius[i]);
    const double expected = 0.2 * BDL_PI * 0.02 * 0.02 * 0.04 / (BDL_PI / 6.0 * 27e-9);
    printf("\nRandom fill of a cylindrical region (radius 20 mm): %ld beads (%.0f asked), the "
           "farthest reaching %.5f m from the axis\n",
           p->count, expected, worst);
    CHECK(worst <= 0.02 + 1e-15);
    CHECK(labs(p->count - lrint(expected)) <= 1);
    bdl_world_destroy(w);
}

/// Random fill and pour in the inside of a closed mesh, an octahedron |x| + |y| + |z| <= a
/// (8 triangles, all turning inwards: the way they turn does not matter, only that they agree):
/// its volume 4/3 a^3 exactly, the count a volume fraction asks for, every bead wholly inside.
static void mesh_region(void)
{
    const double a = 0.02;
    const bdl_vec3 v[6] = {{a, 0, 0}, {-a, 0, 0}, {0, a, 0}, {0, -a, 0}, {0, 0, a}, {0, 0, -a}};
    tri t[8];
    for (int k = 0; k < 8; ++k) {
        const bdl_vec3 x = v[k & 1], y = v[2 + (k >> 1 & 1)], z = v[4 + (k >> 2 & 1)];
        const int odd = ((k & 1) + (k >> 1 & 1) + (k >> 2 & 1)) & 1;
        t[k] = odd ? (tri){{x, y, z}} : (tri){{x, z, y}};
    }
    write_stl_ascii("octahedron.stl", t, 8);
    const char *const ways[2] = {"type = random\nvolume_fraction = 0.2",
                                 "type = pour\ncount = 150\nrate = 30000"};
    for (int k = 0; k < 2; ++k) {
        bdl_world *w = bdl_test_world(
            "[run]\nend_time = 1\ngravity = 0 0 0\n[domain]\nmin = -0.03 -0.03 -0.03\n"
            "max = 0.03 0.03 0.05\n[contact]\nlaw = linear\n[species glass]\ndiameter = 0.003\n"
            "density = 2500\nstiffness = 2000\nrestitution = 0.5\n[create bed]\n%s\n"
            "species = glass\nregion_shape = mesh\nregion_file = %s/octahedron.stl\n"
            "region_translate = 0 0 0.01\nregion_min = -0.025 -0.025 -0.015\n"
            "region_max = 0.025 0.025 0.035\n",
            ways[k], folder);
        if (!w)
            continue;
        while (k == 1 && w->time < 0.012)
            CHECK(bdl_world_step(w) == BDL_OK);
        const bdl_particles *p = &w->particles;
        double worst = -INFINITY; // largest reach of a bead beyond the faces
        for (long i = 0; i < p->count; ++i) {
            const double l1 = fabs(p->pos[i].x) + fabs(p->pos[i].y) + fabs(p->pos[i].z - 0.01);
            worst = fmax(worst, (l1 - a) / sqrt(3.0) + p->radius[i]);
        }
        const double volume = w->scene.creates[0].region_volume;
        const double expected = 0.2 * 4.0 / 3.0 * a * a * a / (BDL_PI / 6.0 * 27e-9);
        printf("%s in an octahedron (volume %.6e m^3, exact %.6e): %ld beads (%s %.0f); the "
               "farthest reaches %.2e m beyond a face\n",
               k ? "Pour" : "Random fill", volume, 4.0 / 3.0 * a * a * a, p->count,
               k ? "poured by 0.012 s of" : "asked", k ? 150.0 : expected, worst);
        CHECK(fabs(volume / (4.0 / 3.0 * a * a * a) - 1.0) < 1e-14);
        CHECK(worst <= 1e-15);
        CHECK(k ? p->count == 150 : labs(p->count - lrint(expected)) <= 1);
        bdl_world_destroy(w);
    }
}

/// A box with a floor and soft glass beads, for the pours below.
#define POUR_BOX                                                                                   \
    "[run]\nend_time = 1\n[domain]\nmin = -0.03 -0.03 0\nmax = 0.03 0.03 0.1\n"                    \
    "[contact]\nlaw = linear\n[species glass]\ndiameter = 0.003\ndensity = 2500\n"                 \
    "stiffness = 2000\nrestitution = 0.5\n[wall floor]\ntype = plane\npoint = 0 0 0\n"             \
    "normal = 0 0 1\n"

/// A pour with a time window stops at stop_time, short of its count.
static void pour_window(void)
{
    bdl_world *w = bdl_test_world(
        POUR_BOX "[create rain]\ntype = pour\nspecies = glass\ncount = 1000\n"
                 "rate = 10000\nstart_time = 0.005\nstop_time = 0.02\nregion_shape = cylinder\n"
                 "region_min = -0.025 -0.025 0.05\nregion_max = 0.025 0.025 0.09\n");
    while (w->time < 0.04)
        CHECK(bdl_world_step(w) == BDL_OK);
    printf("\nPour of 1000 at 10 000/s from 0.005 to 0.02 s: %ld particles at 0.04 s\n",
           w->particles.count);
    CHECK(w->particles.count > 100 && w->particles.count <= 151);
    bdl_world_destroy(w);
    // The same pour onto a sink in the middle of the box: what falls in is removed and counted.
    w = bdl_test_world(POUR_BOX
                       "[create rain]\ntype = pour\n"
                       "species = glass\ncount = 300\nrate = 20000\nregion_min = -0.025 -0.025 "
                       "0.05\nregion_max = 0.025 0.025 0.09\n[sink hole]\nmin = -0.01 -0.01 0\n"
                       "max = 0.01 0.01 0.02\n");
    while (w->time < 0.15)
        CHECK(bdl_world_step(w) == BDL_OK);
    printf("A sink 20 mm square under a pour of 300: %ld removed, %ld left\n", w->removed,
           w->particles.count);
    CHECK(w->removed > 20 && w->removed + w->particles.count == 300);
    bdl_world_destroy(w);
}

static void expect_refused(const char *name, const char *reason)
{
    char path[256], why[400];
    path_of(path, sizeof path, name);
    bdl_mesh m;
    bdl_result r = bdl_mesh_read(path, &m, why, sizeof why);
    printf("| %s | %s |\n", name, r == BDL_OK ? "(read)" : why);
    CHECK_MSG(r != BDL_OK && strstr(why, reason), "%s: expected '%s', got '%s'", name, reason,
              r == BDL_OK ? "success" : why);
}

static void reader(void)
{
    tri sq[2] = {{{bdl_v3(0, 0, 0), bdl_v3(1, 0, 0), bdl_v3(1, 1, 0)}},
                 {{bdl_v3(0, 0, 0), bdl_v3(1, 1, 0), bdl_v3(0, 1, 0)}}};
    write_stl_ascii("square.stl", sq, 2);
    write_stl_binary("square_bin.stl", sq, 2, 2, 0);
    write_text("square.obj", "# a square\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
    const char *names[3] = {"square.stl", "square_bin.stl", "square.obj"};
    for (int k = 0; k < 3; ++k) {
        char path[256], why[400];
        path_of(path, sizeof path, names[k]);
        bdl_mesh m;
        CHECK_MSG(bdl_mesh_read(path, &m, why, sizeof why) == BDL_OK, "%s: %s", names[k], why);
        CHECK(m.tri_count == 2 && m.vertex_count == 4 && m.edge_count == 5);
        bdl_mesh_free(&m);
    }
    write_text("empty.stl", "");
    write_stl_binary("truncated.stl", sq, 2, 2, 84 + 50 + 20);
    write_stl_binary("huge.stl", sq, 2, 100000000u, 0);
    write_text("nan.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex nan 0 0\n"
                          "vertex 0 1 0\nendloop\nendfacet\nendsolid x\n");
    tri fin[3] = {{{bdl_v3(0, 0, 0), bdl_v3(1, 0, 0), bdl_v3(0, 1, 0)}},
                  {{bdl_v3(0, 0, 0), bdl_v3(1, 0, 0), bdl_v3(0, -1, 0)}},
                  {{bdl_v3(0, 0, 0), bdl_v3(1, 0, 0), bdl_v3(0, 0, 1)}}};
    write_stl_ascii("fin.stl", fin, 3);
    tri flat[1] = {{{bdl_v3(0, 0, 0), bdl_v3(1, 0, 0), bdl_v3(2, 0, 0)}}};
    write_stl_ascii("flat.stl", flat, 1);
    write_text("bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n");
    printf("\nRefused meshes\n\n| file | reason |\n|---|---|\n");
    expect_refused("empty.stl", "is empty");
    expect_refused("truncated.stl", "truncated");
    expect_refused("huge.stl", "100000000 triangles");
    expect_refused("nan.stl", "line 5");
    expect_refused("fin.stl", "not a manifold");
    expect_refused("flat.stl", "zero area");
    expect_refused("bad.obj", "line 3");
}

int main(void)
{
    if (!mkdtemp(folder)) {
        perror("mkdtemp");
        return 1;
    }
    reader();
    cylinder_region();
    mesh_region();
    pour_window();
    features();
    rolling();
    dragging();
    turned_plate();
    paddle();
    box_bed();
    discharge();
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", folder);
    if (system(cmd) != 0)
        fprintf(stderr, "could not remove %s\n", folder);
    return bdl_test_summary("test_mesh");
}
