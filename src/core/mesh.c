#include "core/mesh.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "core/file.h"

/// Triangles as read, before welding: three corners each.
typedef struct soup {
    bdl_vec3 *corner; ///< 3 per triangle
    long count, capacity;
} soup;

static int fail(char *why, size_t len, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(why, len, fmt, ap);
    va_end(ap);
    return 0;
}

static int soup_add(soup *s, const bdl_vec3 c[3], char *why, size_t len)
{
    if (s->count >= BDL_MESH_MAX_TRIANGLES)
        return fail(why, len, "holds more than %ld triangles", BDL_MESH_MAX_TRIANGLES);
    if (s->count == s->capacity) {
        long cap = s->capacity ? 2 * s->capacity : 1024;
        bdl_vec3 *grown = realloc(s->corner, (size_t)cap * 3 * sizeof *grown);
        if (!grown)
            return fail(why, len, "needs more memory than there is (%ld triangles)", cap);
        s->corner = grown;
        s->capacity = cap;
    }
    memcpy(s->corner + 3 * s->count++, c, 3 * sizeof *c);
    return 1;
}

/// Parses three finite numbers from `text`; returns the rest of the text or NULL.
static const char *parse_point(const char *text, bdl_vec3 *v)
{
    double c[3];
    for (int k = 0; k < 3; ++k) {
        char *end;
        errno = 0;
        c[k] = strtod(text, &end);
        if (end == text || !isfinite(c[k]))
            return NULL;
        text = end;
    }
    *v = bdl_v3(c[0], c[1], c[2]);
    return text;
}

/// The next line of `text` (at *pos) into `line` without its end; 0 at the end of the text.
static int next_line(const char *text, size_t size, size_t *pos, char *line, size_t cap)
{
    if (*pos >= size)
        return 0;
    size_t n = 0;
    while (*pos < size && text[*pos] != '\n') {
        if (n + 1 < cap)
            line[n++] = text[*pos];
        ++*pos;
    }
    ++*pos;
    line[n] = '\0';
    return 1;
}

/// The first word of a line and where the rest starts.
static const char *first_word(const char *line, char *word, size_t cap)
{
    while (isspace((unsigned char)*line))
        ++line;
    size_t n = 0;
    while (*line && !isspace((unsigned char)*line)) {
        if (n + 1 < cap)
            word[n++] = *line;
        ++line;
    }
    word[n] = '\0';
    return line;
}

static int only_space(const char *s)
{
    while (isspace((unsigned char)*s))
        ++s;
    return *s == '\0';
}

static int read_stl_ascii(const char *text, size_t size, soup *s, char *why, size_t len)
{
    char line[512], word[32];
    size_t pos = 0;
    long number = 0;
    int corners = -1; // -1: outside a facet
    bdl_vec3 c[3];
    while (next_line(text, size, &pos, line, sizeof line)) {
        ++number;
        const char *rest = first_word(line, word, sizeof word);
        if (!word[0] || !strcmp(word, "solid") || !strcmp(word, "endsolid") ||
            !strcmp(word, "outer") || !strcmp(word, "endloop"))
            continue;
        if (!strcmp(word, "facet")) {
            if (corners >= 0)
                return fail(why, len, "line %ld: 'facet' before the previous 'endfacet'", number);
            corners = 0;
        } else if (!strcmp(word, "vertex")) {
            if (corners < 0 || corners == 3)
                return fail(why, len, "line %ld: 'vertex' outside a facet or a fourth one", number);
            rest = parse_point(rest, &c[corners]);
            if (!rest || !only_space(rest))
                return fail(why, len, "line %ld: 'vertex' needs three finite numbers", number);
            ++corners;
        } else if (!strcmp(word, "endfacet")) {
            if (corners != 3)
                return fail(why, len, "line %ld: a facet with %d vertices (3 needed)", number,
                            corners < 0 ? 0 : corners);
            if (!soup_add(s, c, why, len))
                return 0;
            corners = -1;
        } else {
            return fail(why, len, "line %ld: '%s' is not a word of an ASCII STL file", number,
                        word);
        }
    }
    if (corners >= 0)
        return fail(why, len, "ends inside a facet (truncated)");
    return 1;
}

static int read_stl_binary(const unsigned char *data, size_t size, soup *s, char *why, size_t len)
{
    if (size == 0)
        return fail(why, len, "is empty");
    if (size < 84)
        return fail(why, len, "is %zu bytes, too short for a binary STL (84-byte header)", size);
    uint32_t n = (uint32_t)data[80] | (uint32_t)data[81] << 8 | (uint32_t)data[82] << 16 |
                 (uint32_t)data[83] << 24;
    if ((long)n > BDL_MESH_MAX_TRIANGLES)
        return fail(why, len, "has a header that claims %lu triangles; at most %ld are read",
                    (unsigned long)n, BDL_MESH_MAX_TRIANGLES);
    size_t need = 84 + 50 * (size_t)n;
    if (size < need)
        return fail(why, len,
                    "is truncated: its header claims %lu triangles (%zu bytes), the file has %zu",
                    (unsigned long)n, need, size);
    for (uint32_t t = 0; t < n; ++t) {
        const unsigned char *rec = data + 84 + 50 * (size_t)t + 12; // past the normal
        bdl_vec3 c[3];
        for (int k = 0; k < 3; ++k) {
            float f[3];
            memcpy(f, rec + 12 * k, sizeof f); // little-endian IEEE floats, as on every host
            c[k] = bdl_v3(f[0], f[1], f[2]);
            if (!bdl_v3_isfinite(c[k]))
                return fail(why, len, "triangle %lu has a coordinate that is not finite",
                            (unsigned long)t + 1);
        }
        if (!soup_add(s, c, why, len))
            return 0;
    }
    return 1;
}

/// An OBJ face index ("7", "7/1", "7//3", "-1") as a 0-based vertex index, or -1.
static long obj_index(const char *token, long vertices)
{
    char *end;
    long k = strtol(token, &end, 10);
    if (end == token || (*end && *end != '/'))
        return -1;
    k = k < 0 ? vertices + k : k - 1;
    return k >= 0 && k < vertices ? k : -1;
}

/// One "f" line, fanned into triangles.
static int obj_face(const char *rest, const bdl_vec3 *v, long nv, long number, soup *s, char *why,
                    size_t len)
{
    char token[64];
    long first = -1, prev = -1, corners = 0;
    for (;;) {
        rest = first_word(rest, token, sizeof token);
        if (!token[0])
            break;
        long k = obj_index(token, nv);
        if (k < 0)
            return fail(why, len, "line %ld: face index '%s' names no vertex (%ld so far)", number,
                        token, nv);
        if (corners == 0)
            first = k;
        else if (corners >= 2) {
            const bdl_vec3 c[3] = {v[first], v[prev], v[k]};
            if (!soup_add(s, c, why, len))
                return 0;
        }
        prev = k;
        ++corners;
    }
    if (corners < 3)
        return fail(why, len, "line %ld: a face needs at least three vertices", number);
    return 1;
}

static int read_obj(const char *text, size_t size, soup *s, char *why, size_t len)
{
    char line[4096], word[32];
    size_t pos = 0;
    long number = 0, nv = 0, cap = 0;
    bdl_vec3 *v = NULL;
    int ok = 1;
    while (ok && next_line(text, size, &pos, line, sizeof line)) {
        ++number;
        const char *rest = first_word(line, word, sizeof word);
        if (!strcmp(word, "v")) {
            if (nv == cap) {
                cap = cap ? 2 * cap : 1024;
                bdl_vec3 *grown = realloc(v, (size_t)cap * sizeof *v);
                if (!grown) {
                    ok = fail(why, len, "needs more memory than there is");
                    break;
                }
                v = grown;
            }
            if (!parse_point(rest, &v[nv++]))
                ok = fail(why, len, "line %ld: 'v' needs three finite numbers", number);
        } else if (!strcmp(word, "f")) {
            ok = obj_face(rest, v, nv, number, s, why, len);
        }
    }
    free(v);
    return ok;
}

// ---------------------------------------------------------------------------------- welding --

static const bdl_vec3 *sort_base;

static int compare_corner(const void *a, const void *b)
{
    const bdl_vec3 *p = &sort_base[*(const int32_t *)a], *q = &sort_base[*(const int32_t *)b];
    if (p->x != q->x)
        return p->x < q->x ? -1 : 1;
    if (p->y != q->y)
        return p->y < q->y ? -1 : 1;
    if (p->z != q->z)
        return p->z < q->z ? -1 : 1;
    return *(const int32_t *)a < *(const int32_t *)b ? -1 : 1;
}

static int compare_edge(const void *a, const void *b)
{
    const int64_t *p = a, *q = b;
    if (p[0] != q[0])
        return p[0] < q[0] ? -1 : 1;
    return p[1] < q[1] ? -1 : p[1] > q[1];
}

/// Vertices of equal coordinates become one; vertex ids follow the coordinates' order.
static int weld_vertices(const soup *s, bdl_mesh *m, char *why, size_t len)
{
    long n = 3 * s->count;
    int32_t *order = malloc((size_t)n * sizeof *order);
    m->vertex = malloc((size_t)n * sizeof *m->vertex);
    m->tri = malloc((size_t)s->count * sizeof *m->tri);
    if (!order || !m->vertex || !m->tri) {
        free(order);
        return fail(why, len, "needs more memory than there is");
    }
    for (long k = 0; k < n; ++k)
        order[k] = (int32_t)k;
    sort_base = s->corner; // qsort has no context argument; the reader is single-threaded
    qsort(order, (size_t)n, sizeof *order, compare_corner);
    m->vertex_count = 0;
    for (long k = 0; k < n; ++k) {
        const bdl_vec3 c = s->corner[order[k]];
        const bdl_vec3 *last = m->vertex_count ? &m->vertex[m->vertex_count - 1] : NULL;
        if (!last || c.x != last->x || c.y != last->y || c.z != last->z)
            m->vertex[m->vertex_count++] = c;
        m->tri[order[k] / 3][order[k] % 3] = (int32_t)(m->vertex_count - 1);
    }
    free(order);
    m->tri_count = s->count;
    return 1;
}

/// Rejects triangles of zero area (two corners welded into one, or three in a line).
static int check_areas(const bdl_mesh *m, char *why, size_t len)
{
    for (long t = 0; t < m->tri_count; ++t) {
        bdl_vec3 a = m->vertex[m->tri[t][0]], b = m->vertex[m->tri[t][1]],
                 c = m->vertex[m->tri[t][2]];
        if (bdl_v3_len2(bdl_v3_cross(bdl_v3_sub(b, a), bdl_v3_sub(c, a))) == 0.0)
            return fail(why, len,
                        "triangle %ld has zero area (corners (%g, %g, %g), (%g, %g, %g), "
                        "(%g, %g, %g))",
                        t + 1, a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z);
    }
    return 1;
}

/// Gives every edge an id shared by the triangles on its two sides; more than two is refused.
static int weld_edges(bdl_mesh *m, char *why, size_t len)
{
    long n = 3 * m->tri_count;
    int64_t(*key)[2] = malloc((size_t)n * sizeof *key);
    m->tri_edge = malloc((size_t)m->tri_count * sizeof *m->tri_edge);
    m->edge = malloc((size_t)n * sizeof *m->edge);
    if (!key || !m->tri_edge || !m->edge) {
        free(key);
        return fail(why, len, "needs more memory than there is");
    }
    for (long k = 0; k < n; ++k) {
        int32_t a = m->tri[k / 3][k % 3], b = m->tri[k / 3][(k + 1) % 3];
        key[k][0] = (int64_t)(a < b ? a : b) << 32 | (int64_t)(a < b ? b : a);
        key[k][1] = k;
    }
    qsort(key, (size_t)n, sizeof *key, compare_edge);
    m->edge_count = 0;
    int ok = 1;
    for (long k = 0, shared = 0; k < n && ok; ++k) {
        if (k == 0 || key[k][0] != key[k - 1][0]) {
            m->edge[m->edge_count][0] = (int32_t)(key[k][0] >> 32);
            m->edge[m->edge_count][1] = (int32_t)(key[k][0] & 0xffffffff);
            ++m->edge_count;
            shared = 0;
        }
        if (++shared > 2) {
            bdl_vec3 a = m->vertex[m->edge[m->edge_count - 1][0]],
                     b = m->vertex[m->edge[m->edge_count - 1][1]];
            ok = fail(why, len,
                      "is not a manifold: the edge from (%g, %g, %g) to (%g, %g, %g) "
                      "is shared by more than two triangles",
                      a.x, a.y, a.z, b.x, b.y, b.z);
        }
        m->tri_edge[key[k][1] / 3][key[k][1] % 3] = (int32_t)(m->edge_count - 1);
    }
    free(key);
    return ok;
}

static int has_extension(const char *path, const char *ext)
{
    size_t n = strlen(path), e = strlen(ext);
    return n > e && strcasecmp(path + n - e, ext) == 0;
}

/// Whether the text is an ASCII STL: starts with "solid" and holds no NUL byte.
static int looks_ascii(const char *text, size_t size)
{
    const char *p = text;
    while ((size_t)(p - text) < size && isspace((unsigned char)*p))
        ++p;
    return (size_t)(p - text) + 5 <= size && !strncmp(p, "solid", 5) && !memchr(text, 0, size);
}

/// Welds and checks a soup (freed here) into m.
static bdl_result finish(soup *s, bdl_mesh *m, char *why, size_t why_len)
{
    int ok = s->count > 0 || fail(why, why_len, "holds no triangle");
    ok = ok && weld_vertices(s, m, why, why_len) && check_areas(m, why, why_len) &&
         weld_edges(m, why, why_len);
    free(s->corner);
    if (!ok)
        bdl_mesh_free(m);
    return ok ? BDL_OK : BDL_ERR_SCENE;
}

bdl_result bdl_mesh_read(const char *path, bdl_mesh *m, char *why, size_t why_len)
{
    memset(m, 0, sizeof *m);
    if (bdl_check_regular_file(path, NULL, why, why_len) != BDL_OK)
        return BDL_ERR_IO;
    size_t size = 0;
    char *text = bdl_read_file(path, &size);
    if (!text) {
        snprintf(why, why_len, "cannot be read: %s", strerror(errno));
        return BDL_ERR_IO;
    }
    soup s = {0};
    int ok = has_extension(path, ".obj") ? read_obj(text, size, &s, why, why_len)
             : looks_ascii(text, size)
                 ? read_stl_ascii(text, size, &s, why, why_len)
                 : read_stl_binary((const unsigned char *)text, size, &s, why, why_len);
    free(text);
    if (!ok) {
        free(s.corner);
        return BDL_ERR_SCENE;
    }
    return finish(&s, m, why, why_len);
}

/// Two unit vectors across the unit axis a.
static void across(bdl_vec3 a, bdl_vec3 *u, bdl_vec3 *v)
{
    const bdl_vec3 t = fabs(a.x) < 0.9 ? bdl_v3(1, 0, 0) : bdl_v3(0, 1, 0);
    *u = bdl_v3_normalize(bdl_v3_cross(a, t));
    *v = bdl_v3_cross(a, *u);
}

/// Point k of a ring of `segments` points of radius r around c in the plane of u, v.
static bdl_vec3 ring_point(bdl_vec3 c, bdl_vec3 u, bdl_vec3 v, double r, int k, int segments)
{
    const double phi = 2.0 * BDL_PI * (double)(k % segments) / (double)segments;
    // Each point from its own angle, so that a corner shared by two triangles has the same bits.
    return bdl_v3_add(c, bdl_v3_add(bdl_v3_scale(u, r * cos(phi)), bdl_v3_scale(v, r * sin(phi))));
}

/// The band between two rings (radius r0 around c0, r1 around c1; a ring of radius 0 is its
/// centre, a fan), `segments` quadrilaterals of two triangles.
static int band(soup *s, bdl_vec3 c0, double r0, bdl_vec3 c1, double r1, bdl_vec3 axis,
                int segments, char *why, size_t len)
{
    bdl_vec3 u, v;
    across(axis, &u, &v);
    for (int k = 0; k < segments; ++k) {
        const bdl_vec3 a = ring_point(c0, u, v, r0, k, segments),
                       b = ring_point(c0, u, v, r0, k + 1, segments),
                       c = ring_point(c1, u, v, r1, k + 1, segments),
                       d = ring_point(c1, u, v, r1, k, segments);
        const bdl_vec3 t1[3] = {a, b, c}, t2[3] = {a, c, d};
        // A ring of radius 0 is a point: its side of the quadrilateral has no area.
        if ((r0 > 0.0 && !soup_add(s, t1, why, len)) || (r1 > 0.0 && !soup_add(s, t2, why, len)))
            return 0;
    }
    return 1;
}

bdl_result bdl_mesh_disk(bdl_mesh *m, bdl_vec3 centre, bdl_vec3 normal, double radius,
                         double hole_radius, int segments, char *why, size_t why_len)
{
    memset(m, 0, sizeof *m);
    soup s = {0};
    const bdl_vec3 n = bdl_v3_normalize(normal);
    if (!band(&s, centre, hole_radius, centre, radius, n, segments, why, why_len)) {
        free(s.corner);
        return BDL_ERR_SCENE;
    }
    return finish(&s, m, why, why_len);
}

bdl_result bdl_mesh_frustum(bdl_mesh *m, bdl_vec3 base, bdl_vec3 axis, double radius,
                            double radius_top, double height, int segments, char *why,
                            size_t why_len)
{
    memset(m, 0, sizeof *m);
    soup s = {0};
    const bdl_vec3 a = bdl_v3_normalize(axis), top = bdl_v3_madd(base, a, height);
    if (!band(&s, base, radius, top, radius_top, a, segments, why, why_len)) {
        free(s.corner);
        return BDL_ERR_SCENE;
    }
    return finish(&s, m, why, why_len);
}

void bdl_mesh_transform(bdl_mesh *m, double scale, bdl_vec3 angles_deg, bdl_vec3 translate)
{
    const double deg = BDL_PI / 180.0;
    const double cx = cos(angles_deg.x * deg), sx = sin(angles_deg.x * deg);
    const double cy = cos(angles_deg.y * deg), sy = sin(angles_deg.y * deg);
    const double cz = cos(angles_deg.z * deg), sz = sin(angles_deg.z * deg);
    for (long k = 0; k < m->vertex_count; ++k) {
        bdl_vec3 v = bdl_v3_scale(m->vertex[k], scale);
        v = bdl_v3(v.x, cx * v.y - sx * v.z, sx * v.y + cx * v.z);
        v = bdl_v3(cy * v.x + sy * v.z, v.y, -sy * v.x + cy * v.z);
        v = bdl_v3(cz * v.x - sz * v.y, sz * v.x + cz * v.y, v.z);
        m->vertex[k] = bdl_v3_add(v, translate);
    }
}

/// Within this fraction of an edge's length of its end, or of a face's height of its border, a
/// nearest point is taken to lie on the end or the border, so that round-off cannot put a centre
/// over a shared vertex or edge on different parts of the triangles around it. (The distance
/// moves by the square of the shift, far below round-off; the normal by 1e-10 of the ratio of
/// edge length to distance at most.)
#define SNAP 1e-10

/// An edge's nearest point at parameter s from its first vertex k to vertex (k + 1) % 3.
static bdl_vec3 on_edge(const bdl_vec3 *v, int k, double s)
{
    if (s <= SNAP || s >= 1.0 - SNAP)
        return v[s <= SNAP ? k : (k + 1) % 3];
    return bdl_v3_madd(v[k], bdl_v3_sub(v[(k + 1) % 3], v[k]), s);
}

bdl_vec3 bdl_triangle_nearest(bdl_vec3 a, bdl_vec3 b, bdl_vec3 c, bdl_vec3 p, int *face)
{
    *face = 0;
    const bdl_vec3 v[3] = {a, b, c};
    const bdl_vec3 ab = bdl_v3_sub(b, a), ac = bdl_v3_sub(c, a);
    const bdl_vec3 ap = bdl_v3_sub(p, a), bp = bdl_v3_sub(p, b), cp = bdl_v3_sub(p, c);
    const double d1 = bdl_v3_dot(ab, ap), d2 = bdl_v3_dot(ac, ap);
    const double d3 = bdl_v3_dot(ab, bp), d4 = bdl_v3_dot(ac, bp);
    const double d5 = bdl_v3_dot(ab, cp), d6 = bdl_v3_dot(ac, cp);
    if (d1 <= 0.0 && d2 <= 0.0)
        return on_edge(v, 0, 0.0);
    if (d3 >= 0.0 && d4 <= d3)
        return on_edge(v, 1, 0.0);
    if (d6 >= 0.0 && d5 <= d6)
        return on_edge(v, 2, 0.0);
    const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
        return on_edge(v, 0, d1 / (d1 - d3));
    if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)
        return on_edge(v, 1, (d4 - d3) / ((d4 - d3) + (d5 - d6)));
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
        return on_edge(v, 2, 1.0 - d2 / (d2 - d6));
    // Inside: barycentric weights va, vb, vc (of a, b, c) over their sum.
    const double sum = va + vb + vc, wa = va / sum, wb = vb / sum, wc = vc / sum;
    if (wa <= SNAP) // on edge b-c
        return on_edge(v, 1, wc / (wb + wc));
    if (wb <= SNAP) // on edge c-a
        return on_edge(v, 2, wa / (wa + wc));
    if (wc <= SNAP) // on edge a-b
        return on_edge(v, 0, wb / (wa + wb));
    *face = 1;
    return p; // the face: the distance is the plane's (below)
}

long bdl_mesh_unclosed_edge(const bdl_mesh *m, int *border)
{
    // Per edge: the triangles on it, and whether the first runs it from edge[0] to edge[1].
    uint8_t *sides = calloc((size_t)(m->edge_count > 0 ? m->edge_count : 1), 2);
    if (!sides)
        return -2;
    long bad = -1;
    for (long t = 0; t < m->tri_count && bad < 0; ++t)
        for (int k = 0; k < 3; ++k) {
            const int32_t e = m->tri_edge[t][k];
            const uint8_t forward = m->tri[t][k] == m->edge[e][0];
            if (sides[2 * e]++ == 0)
                sides[2 * e + 1] = forward;
            else if (sides[2 * e + 1] == forward)
                bad = e; // both triangles run the edge the same way
        }
    *border = 0;
    for (long e = 0; e < m->edge_count && bad < 0; ++e)
        if (sides[2 * e] == 1) {
            bad = e;
            *border = 1;
        }
    free(sides);
    return bad;
}

/// The corners of triangle t.
static void corners(const bdl_mesh *m, long t, bdl_vec3 *a, bdl_vec3 *b, bdl_vec3 *c)
{
    *a = m->vertex[m->tri[t][0]];
    *b = m->vertex[m->tri[t][1]];
    *c = m->vertex[m->tri[t][2]];
}

double bdl_mesh_volume(const bdl_mesh *m)
{
    double v = 0.0;
    for (long t = 0; t < m->tri_count; ++t) {
        bdl_vec3 a, b, c;
        corners(m, t, &a, &b, &c);
        v += bdl_v3_dot(a, bdl_v3_cross(b, c));
    }
    return v / 6.0;
}

double bdl_mesh_winding(const bdl_mesh *m, bdl_vec3 x)
{
    double sum = 0.0;
    for (long t = 0; t < m->tri_count; ++t) {
        bdl_vec3 a, b, c;
        corners(m, t, &a, &b, &c);
        a = bdl_v3_sub(a, x);
        b = bdl_v3_sub(b, x);
        c = bdl_v3_sub(c, x);
        const double la = bdl_v3_len(a), lb = bdl_v3_len(b), lc = bdl_v3_len(c);
        const double num = bdl_v3_dot(a, bdl_v3_cross(b, c));
        const double den =
            la * lb * lc + bdl_v3_dot(a, b) * lc + bdl_v3_dot(a, c) * lb + bdl_v3_dot(b, c) * la;
        sum += 2.0 * atan2(num, den); // the solid angle the triangle subtends at x
    }
    return sum / (4.0 * 3.14159265358979323846);
}

double bdl_mesh_distance(const bdl_mesh *m, bdl_vec3 x)
{
    double d2 = INFINITY;
    for (long t = 0; t < m->tri_count; ++t) {
        bdl_vec3 a, b, c;
        corners(m, t, &a, &b, &c);
        int face;
        bdl_vec3 q = bdl_triangle_nearest(a, b, c, x, &face);
        if (face) { // the plane's distance
            const bdl_vec3 n = bdl_v3_cross(bdl_v3_sub(b, a), bdl_v3_sub(c, a));
            const double h = bdl_v3_dot(bdl_v3_sub(x, a), n);
            d2 = fmin(d2, h * h / bdl_v3_len2(n));
        } else {
            d2 = fmin(d2, bdl_v3_len2(bdl_v3_sub(x, q)));
        }
    }
    return sqrt(d2);
}

void bdl_mesh_free(bdl_mesh *m)
{
    free(m->vertex);
    free(m->tri);
    free(m->tri_edge);
    free(m->edge);
    memset(m, 0, sizeof *m);
}
