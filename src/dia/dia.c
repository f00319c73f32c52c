// bedlam — synthetic camera images: projection, CPU ray casting of spheres and capsules,
// post-processing, ground truth.
#include "dia/dia.h"

#include <float.h>
#include <math.h>
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/rng.h"
#include "core/file.h"
#include "core/memory.h"
#include "dia/capsule.h"

/// Half the shaft length of particle i: 0 for a sphere.
static double half_length(const bdl_dia_scene *s, long i)
{
    return s->axis && s->half_length ? s->half_length[i] : 0.0;
}

bdl_result bdl_dia_camera_init(bdl_dia_camera *c, const bdl_dia_def *def)
{
    c->def = *def;
    bdl_vec3 f = bdl_v3_sub(def->target, def->position);
    double len = bdl_v3_len(f);
    if (!(len > 0.0))
        return BDL_ERR_SCENE;
    c->forward = bdl_v3_scale(f, 1.0 / len);
    bdl_vec3 r = bdl_v3_cross(c->forward, def->up); // image right = forward x up
    double rl = bdl_v3_len(r);
    if (!(rl > 1e-9 * bdl_v3_len(def->up)))
        return BDL_ERR_SCENE;
    c->right = bdl_v3_scale(r, 1.0 / rl);
    c->down = bdl_v3_cross(c->forward, c->right); // right-handed: right x down = forward
    return BDL_OK;
}

double bdl_dia_scale(const bdl_dia_camera *c, double depth)
{
    const bdl_dia_def *d = &c->def;
    return d->projection == BDL_DIA_ORTHOGRAPHIC ? d->pixel_size
                                                 : d->pixel_size * depth / d->focal_length;
}

void bdl_dia_project(const bdl_dia_camera *c, bdl_vec3 x, double *u, double *v, double *depth)
{
    const bdl_dia_def *d = &c->def;
    bdl_vec3 r = bdl_v3_sub(x, d->position);
    double a = bdl_v3_dot(r, c->right), b = bdl_v3_dot(r, c->down), z = bdl_v3_dot(r, c->forward);
    double s = bdl_dia_scale(c, z);
    *u = 0.5 * d->width + a / s;
    *v = 0.5 * d->height + b / s;
    *depth = z;
}

bdl_vec3 bdl_dia_unproject(const bdl_dia_camera *c, double u, double v, double depth)
{
    const bdl_dia_def *d = &c->def;
    double s = bdl_dia_scale(c, depth);
    bdl_vec3 x = bdl_v3_madd(d->position, c->forward, depth);
    x = bdl_v3_madd(x, c->right, (u - 0.5 * d->width) * s);
    return bdl_v3_madd(x, c->down, (v - 0.5 * d->height) * s);
}

double bdl_dia_outline_area(const bdl_dia_camera *c, const bdl_dia_scene *s, long i, int samples)
{
    double u, v, depth;
    bdl_dia_project(c, s->pos[i], &u, &v, &depth);
    const double scale = bdl_dia_scale(c, depth);
    const double rp = s->radius[i] / scale * samples;
    double area = BDL_PI * rp * rp;
    const double h = half_length(s, i);
    if (h > 0.0) {
        // The shaft seen across the line of sight adds a rectangle 2 r by 2 h |u x sight|.
        bdl_vec3 sight = c->def.projection == BDL_DIA_ORTHOGRAPHIC
                             ? c->forward
                             : bdl_v3_normalize(bdl_v3_sub(s->pos[i], c->def.position));
        area += 4.0 * rp * (h / scale * samples) * bdl_v3_len(bdl_v3_cross(s->axis[i], sight));
    }
    return area;
}

void bdl_dia_image_free(bdl_dia_image *im)
{
    free(im->value);
    free(im->hit);
    free(im->depth);
    free(im->final);
    memset(im, 0, sizeof *im);
}

/// The ray through sample point (u, v) of the image: origin and unit direction.
static void sample_ray(const bdl_dia_camera *c, double u, double v, bdl_vec3 *o, bdl_vec3 *dir)
{
    const bdl_dia_def *d = &c->def;
    if (d->projection == BDL_DIA_ORTHOGRAPHIC) {
        *o = bdl_dia_unproject(c, u, v, 0.0);
        *dir = c->forward;
    } else {
        *o = d->position;
        *dir = bdl_v3_normalize(bdl_v3_sub(bdl_dia_unproject(c, u, v, d->focal_length), *o));
    }
}

/// Grey level of a particle's surface point p (normal n) under the camera's lights.
static double shade(const bdl_dia_camera *c, bdl_vec3 p, bdl_vec3 n)
{
    const bdl_dia_def *d = &c->def;
    if (d->lighting == BDL_DIA_BACK_LIT)
        return d->dark;
    double fade = 1.0;
    if (d->fade_length > 0.0) {
        double behind = bdl_v3_dot(bdl_v3_sub(p, d->position), c->forward) - d->fade_start;
        fade = behind > 0.0 ? exp(-behind / d->fade_length) : 1.0;
    }
    double g = d->ambient;
    for (int k = 0; k < d->light_count; ++k) {
        bdl_vec3 l = bdl_v3_normalize(bdl_v3_sub(d->light_position[k], p));
        double lambert = bdl_v3_dot(n, l);
        if (lambert > 0.0)
            g += d->light_intensity[k] * lambert;
    }
    return d->dark + (d->bright - d->dark) * fade * (g < 1.0 ? g : 1.0);
}

/// Where a particle's image can be: within rp pixels of the segment from (u0, v0) to (u1, v1)
/// (for a sphere a point), or anywhere (a capsule reaching behind a pinhole camera).
typedef struct outline {
    double u0, v0, u1, v1, rp;
    int anywhere;
} outline;

/// Pixel position of a sphere's centre and a bound on its image's radius (exact orthographic,
/// conservative for perspective). 0 when the camera is inside or behind the sphere.
static int sphere_image(const bdl_dia_camera *c, bdl_vec3 x, double r, double *u, double *v,
                        double *rp)
{
    double z;
    bdl_dia_project(c, x, u, v, &z);
    if (c->def.projection == BDL_DIA_ORTHOGRAPHIC) {
        *rp = r / c->def.pixel_size;
    } else {
        if (z <= r) // the camera is inside or behind the sphere
            return 0;
        // The silhouette is an ellipse within the cone of half-angle asin(r/dist) around the
        // centre's direction; bound it by the tangent of that angle at the nearest depth.
        double dist = bdl_v3_len(bdl_v3_sub(x, c->def.position));
        double tan_a = r / sqrt(dist * dist - r * r);
        *rp = (dist * tan_a + r) / bdl_dia_scale(c, z - r) + 1.0;
    }
    return 1;
}

/// Particle i's outline; 0 when the camera cannot see it.
static int particle_outline(const bdl_dia_camera *c, const bdl_dia_scene *s, long i, outline *o)
{
    const double h = half_length(s, i), r = s->radius[i];
    o->anywhere = 0;
    if (h == 0.0) {
        if (!sphere_image(c, s->pos[i], r, &o->u0, &o->v0, &o->rp))
            return 0;
        o->u1 = o->u0, o->v1 = o->v0;
        return 1;
    }
    // A capsule is the convex hull of its end balls, and both projections map the hull of points
    // in front of the camera to the hull of their images: within the larger ball's image radius
    // of the segment between the ends' images.
    const bdl_vec3 e = bdl_v3_scale(s->axis[i], h);
    double ra, rb;
    if (sphere_image(c, bdl_v3_sub(s->pos[i], e), r, &o->u0, &o->v0, &ra) &&
        sphere_image(c, bdl_v3_add(s->pos[i], e), r, &o->u1, &o->v1, &rb))
        o->rp = fmax(ra, rb);
    else
        o->anywhere = 1;
    return 1;
}

/// Pixel bounding box of an outline (one pixel wider), within the image; 0 when it has none.
static int outline_box(const bdl_dia_camera *c, const outline *o, int box[4])
{
    double ext[4] = {0.0, c->def.width, 0.0, c->def.height};
    if (!o->anywhere) {
        ext[0] = fmin(o->u0, o->u1) - o->rp - 1.0, ext[1] = fmax(o->u0, o->u1) + o->rp + 1.0;
        ext[2] = fmin(o->v0, o->v1) - o->rp - 1.0, ext[3] = fmax(o->v0, o->v1) + o->rp + 1.0;
    }
    box[0] = (int)floor(ext[0]), box[1] = (int)ceil(ext[1]);
    box[2] = (int)floor(ext[2]), box[3] = (int)ceil(ext[3]);
    if (box[0] < 0)
        box[0] = 0;
    if (box[2] < 0)
        box[2] = 0;
    if (box[1] > c->def.width)
        box[1] = c->def.width;
    if (box[3] > c->def.height)
        box[3] = c->def.height;
    return box[0] < box[1] && box[2] < box[3];
}

/// The sample columns [*x0, *x1) of sample row py that an outline can reach (one pixel wider):
/// the part of its segment within reach of the row, widened by the reach. A long rod across the
/// image fills a small part of its box; this keeps the rays it casts near its outline.
static void outline_row(const outline *o, int ns, int py, int *x0, int *x1)
{
    if (o->anywhere)
        return;
    const double v = (py + 0.5) / ns, reach = o->rp + 1.0, dv = o->v1 - o->v0;
    double ta = 0.0, tb = 1.0; // the segment's parameters within reach of the row
    if (dv != 0.0) {
        double t0 = (v - reach - o->v0) / dv, t1 = (v + reach - o->v0) / dv;
        ta = fmax(ta, fmin(t0, t1)), tb = fmin(tb, fmax(t0, t1));
    } else if (fabs(v - o->v0) > reach) {
        ta = 1.0, tb = 0.0;
    }
    if (ta > tb) {
        *x1 = *x0;
        return;
    }
    const double ua = o->u0 + ta * (o->u1 - o->u0), ub = o->u0 + tb * (o->u1 - o->u0);
    // Sample px sits at u = (px + 0.5) / ns.
    const double a = ceil((fmin(ua, ub) - reach) * ns - 0.5);
    const double b = floor((fmax(ua, ub) + reach) * ns - 0.5) + 1.0;
    if (a > *x0)
        *x0 = a < *x1 ? (int)a : *x1;
    if (b < *x1)
        *x1 = b > *x0 ? (int)b : *x0;
}

/// Separable Gaussian blur of a w x h image in place.
static void blur(double *img, int w, int h, double sigma)
{
    int rad = (int)ceil(3.0 * sigma);
    double *k = malloc((size_t)(2 * rad + 1) * sizeof(double));
    double *tmp = malloc((size_t)w * (size_t)h * sizeof(double));
    if (!k || !tmp) {
        free(k);
        free(tmp);
        return;
    }
    double sum = 0.0;
    for (int i = -rad; i <= rad; ++i)
        sum += k[i + rad] = exp(-0.5 * i * i / (sigma * sigma));
    for (int i = 0; i <= 2 * rad; ++i)
        k[i] /= sum;
    // Edges: the nearest pixel is repeated.
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double s = 0.0;
            for (int i = -rad; i <= rad; ++i) {
                int xx = x + i < 0 ? 0 : x + i >= w ? w - 1 : x + i;
                s += k[i + rad] * img[(size_t)y * w + xx];
            }
            tmp[(size_t)y * w + x] = s;
        }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double s = 0.0;
            for (int i = -rad; i <= rad; ++i) {
                int yy = y + i < 0 ? 0 : y + i >= h ? h - 1 : y + i;
                s += k[i + rad] * tmp[(size_t)yy * w + x];
            }
            img[(size_t)y * w + x] = s;
        }
    free(k);
    free(tmp);
}

/// The image's buffers, every sample empty (no hit, infinitely far).
static bdl_result allocate_image(const bdl_dia_def *d, int ns, bdl_dia_image *im)
{
    size_t npx, nsm, bytes;
    memset(im, 0, sizeof *im);
    if (!bdl_size_mul((size_t)d->width, (size_t)d->height, &npx) ||
        !bdl_size_mul3(npx, (size_t)ns, (size_t)ns, &nsm) ||
        !bdl_size_mul(nsm, sizeof(int32_t), &bytes) || !bdl_size_mul(npx, sizeof(double), &bytes))
        return BDL_ERR_NOMEM;
    im->width = d->width, im->height = d->height, im->samples = ns;
    im->value = malloc(npx * sizeof(float));
    im->final = malloc(npx * sizeof(double));
    im->hit = malloc(nsm * sizeof(int32_t));
    im->depth = malloc(nsm * sizeof(float));
    if (!im->value || !im->final || !im->hit || !im->depth) {
        bdl_dia_image_free(im);
        return BDL_ERR_NOMEM;
    }
    for (size_t k = 0; k < nsm; ++k) {
        im->hit[k] = -1;
        im->depth[k] = FLT_MAX;
    }
    return BDL_OK;
}

/// Keeps the hit at distance t along the ray of sample k when it is nearer than the one held.
static void record_hit(const bdl_dia_camera *c, bdl_dia_image *im, size_t k, bdl_vec3 o,
                       bdl_vec3 dir, double t, long i)
{
    // Depth along the optical axis of the hit point.
    double depth = bdl_v3_dot(bdl_v3_sub(bdl_v3_madd(o, dir, t), c->def.position), c->forward);
    if (t > 0.0 && depth < im->depth[k]) {
        im->depth[k] = (float)depth;
        im->hit[k] = (int32_t)i;
    }
}

/// Sphere i writes the samples of its pixel box where it is the nearest hit so far.
static void cast_sphere(const bdl_dia_camera *c, const bdl_dia_scene *s, long i, const int box[4],
                        bdl_dia_image *im)
{
    const int ns = im->samples, sw = c->def.width * ns;
    const bdl_vec3 x = s->pos[i];
    const double r = s->radius[i];
    for (int py = box[2] * ns; py < box[3] * ns; ++py)
        for (int px = box[0] * ns; px < box[1] * ns; ++px) {
            bdl_vec3 o, dir;
            sample_ray(c, (px + 0.5) / ns, (py + 0.5) / ns, &o, &dir);
            bdl_vec3 oc = bdl_v3_sub(o, x);
            double b = bdl_v3_dot(oc, dir), q = bdl_v3_dot(oc, oc) - r * r;
            double disc = b * b - q;
            if (disc < 0.0)
                continue;
            double t = -b - sqrt(disc); // nearest intersection along the ray
            record_hit(c, im, (size_t)py * (size_t)sw + (size_t)px, o, dir, t, i);
        }
}

/// The same for capsule i (half shaft length h), row by row within its outline.
static void cast_capsule(const bdl_dia_camera *c, const bdl_dia_scene *s, long i, double h,
                         const outline *ol, const int box[4], bdl_dia_image *im)
{
    const int ns = im->samples, sw = c->def.width * ns;
    const bdl_vec3 e = bdl_v3_scale(s->axis[i], h);
    for (int py = box[2] * ns; py < box[3] * ns; ++py) {
        int x0 = box[0] * ns, x1 = box[1] * ns;
        outline_row(ol, ns, py, &x0, &x1);
        for (int px = x0; px < x1; ++px) {
            bdl_vec3 o, dir, n;
            double t;
            sample_ray(c, (px + 0.5) / ns, (py + 0.5) / ns, &o, &dir);
            if (bdl_dia_ray_capsule(o, dir, s->pos[i], e, s->radius[i], &t, &n))
                record_hit(c, im, (size_t)py * (size_t)sw + (size_t)px, o, dir, t, i);
        }
    }
}

static void cast_rays(const bdl_dia_camera *c, const bdl_dia_scene *s, bdl_dia_image *im)
{
    for (long i = 0; i < s->count; ++i) {
        outline o;
        int box[4];
        if (!particle_outline(c, s, i, &o) || !outline_box(c, &o, box))
            continue;
        const double h = half_length(s, i);
        if (h > 0.0)
            cast_capsule(c, s, i, h, &o, box, im);
        else
            cast_sphere(c, s, i, box, im);
    }
}

/// The light a sample at (px, py) receives: the background, or the shaded particle it hits.
static double sample_light(const bdl_dia_camera *c, const bdl_dia_scene *s, const bdl_dia_image *im,
                           int px, int py)
{
    const bdl_dia_def *d = &c->def;
    const int ns = im->samples;
    const int32_t hit = im->hit[(size_t)py * (size_t)(d->width * ns) + (size_t)px];
    if (hit < 0)
        return d->lighting == BDL_DIA_BACK_LIT ? d->bright : d->dark;
    bdl_vec3 o, dir;
    sample_ray(c, (px + 0.5) / ns, (py + 0.5) / ns, &o, &dir);
    const double h = half_length(s, hit);
    if (h > 0.0) {
        double t;
        bdl_vec3 n;
        // The ray that hit the capsule when cast hits it again; the background stands in for a
        // miss that cannot happen.
        if (!bdl_dia_ray_capsule(o, dir, s->pos[hit], bdl_v3_scale(s->axis[hit], h), s->radius[hit],
                                 &t, &n))
            return d->lighting == BDL_DIA_BACK_LIT ? d->bright : d->dark;
        return shade(c, bdl_v3_madd(o, dir, t), n);
    }
    bdl_vec3 oc = bdl_v3_sub(o, s->pos[hit]);
    double b = bdl_v3_dot(oc, dir);
    double disc = b * b - bdl_v3_dot(oc, oc) + s->radius[hit] * s->radius[hit];
    double t = -b - sqrt(disc > 0.0 ? disc : 0.0);
    bdl_vec3 p = bdl_v3_madd(o, dir, t);
    bdl_vec3 n = bdl_v3_scale(bdl_v3_sub(p, s->pos[hit]), 1.0 / s->radius[hit]);
    return shade(c, p, n);
}

/// Optics and sensor: defocus, gamma, noise (seeded per frame), clipped to [0, 1].
static void expose(const bdl_dia_def *d, long frame, bdl_dia_image *im)
{
    const size_t npx = (size_t)d->width * (size_t)d->height;
    for (size_t k = 0; k < npx; ++k)
        im->final[k] = im->value[k];
    if (d->blur > 0.0)
        blur(im->final, d->width, d->height, d->blur);
    bdl_rng rng;
    bdl_rng_seed(&rng, d->seed ^ (0x9E3779B97F4A7C15ull * (uint64_t)(frame + 1)));
    const double inv_gamma = d->gamma > 0.0 ? 1.0 / d->gamma : 1.0;
    for (size_t k = 0; k < npx; ++k) {
        double g = im->final[k];
        g = g > 0.0 ? pow(g, inv_gamma) : 0.0;
        if (d->noise > 0.0)
            g += d->noise * bdl_rng_normal(&rng);
        im->final[k] = g < 0.0 ? 0.0 : g > 1.0 ? 1.0 : g;
    }
}

bdl_result bdl_dia_render(const bdl_dia_camera *c, const bdl_dia_scene *s, long frame,
                          bdl_dia_image *im)
{
    const bdl_dia_def *d = &c->def;
    const int ns = d->samples > 0 ? d->samples : 1;
    bdl_result r = allocate_image(d, ns, im);
    if (r != BDL_OK)
        return r;
    cast_rays(c, s, im);
    // Shading: each pixel is the mean of its samples.
    for (int y = 0; y < d->height; ++y)
        for (int x = 0; x < d->width; ++x) {
            double sum = 0.0;
            for (int sy = 0; sy < ns; ++sy)
                for (int sx = 0; sx < ns; ++sx)
                    sum += sample_light(c, s, im, x * ns + sx, y * ns + sy);
            im->value[(size_t)y * d->width + x] = (float)(sum / (ns * ns));
        }
    expose(d, frame, im);
    return BDL_OK;
}

bdl_result bdl_dia_write_png(const bdl_dia_image *im, int bits, const char *path)
{
    bdl_atomic_file af;
    bdl_result r = bdl_atomic_open(&af, path);
    if (r != BDL_OK)
        return r;
    const int w = im->width, h = im->height, bytes = bits == 16 ? 2 : 1;
    uint8_t *row = malloc((size_t)w * (size_t)bytes);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, NULL, NULL, NULL);
    png_infop info = png ? png_create_info_struct(png) : NULL;
    if (!row || !png || !info || setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        free(row);
        bdl_atomic_abort(&af);
        return BDL_ERR_IO;
    }
    png_init_io(png, af.file);
    png_set_compression_level(png, 1);
    png_set_IHDR(png, info, (png_uint_32)w, (png_uint_32)h, bytes * 8, PNG_COLOR_TYPE_GRAY,
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    const double full = bits == 16 ? 65535.0 : 255.0;
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            long q = lrint(im->final[(size_t)y * w + x] * full);
            if (bytes == 2) { // PNG stores 16-bit samples big-endian
                row[2 * x] = (uint8_t)(q >> 8);
                row[2 * x + 1] = (uint8_t)(q & 0xff);
            } else {
                row[x] = (uint8_t)q;
            }
        }
        png_write_row(png, row);
    }
    png_write_end(png, info);
    png_destroy_write_struct(&png, &info);
    free(row);
    return bdl_atomic_commit(&af);
}

// ---- ground truth ----

// 16-point Gauss-Legendre nodes and weights on [-1, 1] (positive half).
static const double gl_x[8] = {0.0950125098376374, 0.2816035507792589, 0.4580167776572274,
                               0.6178762444026438, 0.7554044083550030, 0.8656312023878318,
                               0.9445750230732326, 0.9894009349916499};
static const double gl_w[8] = {0.1894506104550685, 0.1826034150449236, 0.1691565193950025,
                               0.1495959888165767, 0.1246289712555339, 0.0951585116824928,
                               0.0622535239386479, 0.0271524594117541};

/// Clips the angle range of x = c + r sin(theta) to x in [lo, hi]: theta in [t0, t1].
static int angle_range(double c, double r, double lo, double hi, double *t0, double *t1)
{
    double a = (lo - c) / r, b = (hi - c) / r;
    if (a >= 1.0 || b <= -1.0 || a >= b)
        return 0;
    *t0 = asin(a < -1.0 ? -1.0 : a);
    *t1 = asin(b > 1.0 ? 1.0 : b);
    return *t1 > *t0;
}

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/// Breakpoints of [t0, t1]: the ends and the angles where r cos(t) = d for the distances d > 0
/// given (where a clipping in the next variable starts), sorted. Returns how many (2..6).
static int breakpoints(double t0, double t1, double r, const double *d, int nd, double *out)
{
    int n = 0;
    out[n++] = t0;
    out[n++] = t1;
    for (int k = 0; k < nd; ++k) {
        if (!(d[k] > 0.0 && d[k] < r))
            continue;
        double t = acos(d[k] / r);
        if (t > t0 && t < t1)
            out[n++] = t;
        if (-t > t0 && -t < t1)
            out[n++] = -t;
    }
    qsort(out, (size_t)n, sizeof(double), compare_double);
    return n;
}

/// 16-point Gauss-Legendre on [a, b]: node k and its weight.
static double gl_node(double a, double b, int k, double *w)
{
    double m = 0.5 * (a + b), h = 0.5 * (b - a);
    *w = h * gl_w[k < 8 ? 7 - k : k - 8];
    return m + h * (k < 8 ? -gl_x[7 - k] : gl_x[k - 8]);
}

/// Length of the chord [c - half, c + half] inside [lo, hi].
static double clipped(double c, double half, double lo, double hi)
{
    double a = fmax(c - half, lo), b = fmin(c + half, hi);
    return b > a ? b - a : 0.0;
}

double bdl_dia_sphere_box_volume(bdl_vec3 x, double r, bdl_vec3 lo, bdl_vec3 hi)
{
    // V = int dx int dz chord(x, z) with x = x0 + r sin(p), z = z0 + rho sin(q), rho = r cos(p):
    // the square roots at the sphere's edges become cosines. The integrands have kinks where a
    // clipping starts (a face of the box touches the section's edge); the ranges are split
    // there, so each piece is smooth for Gauss-Legendre.
    double p0, p1;
    if (!angle_range(x.x, r, lo.x, hi.x, &p0, &p1))
        return 0.0;
    const double dz[2] = {fabs(lo.z - x.z), fabs(hi.z - x.z)};
    const double dy[2] = {fabs(lo.y - x.y), fabs(hi.y - x.y)};
    double pb[8];
    // Outer kinks: the z faces reach the section's edge (rho = dz); the y faces reach the
    // chord's middle ring only through the inner split, whose own kink is where rho = dy.
    const double douter[4] = {dz[0], dz[1], dy[0], dy[1]};
    int np = breakpoints(p0, p1, r, douter, 4, pb);
    double volume = 0.0;
    for (int seg = 0; seg + 1 < np; ++seg)
        for (int a = 0; a < 16; ++a) {
            double wa, pa = gl_node(pb[seg], pb[seg + 1], a, &wa);
            double rho = r * cos(pa); // also dx/dp
            double q0, q1;
            if (!(rho > 0.0) || !angle_range(x.z, rho, lo.z, hi.z, &q0, &q1))
                continue;
            double qb[8];
            int nq = breakpoints(q0, q1, rho, dy, 2, qb);
            double inner = 0.0;
            for (int sq = 0; sq + 1 < nq; ++sq)
                for (int b = 0; b < 16; ++b) {
                    double wb, q = gl_node(qb[sq], qb[sq + 1], b, &wb);
                    double half = rho * cos(q); // half chord along y; also dz/dq
                    inner += wb * clipped(x.y, half, lo.y, hi.y) * half;
                }
            volume += wa * inner * rho;
        }
    return volume;
}

/// Visible area and velocity per cell: every sample belongs to the cell its centre falls in;
/// velocities become image-plane velocities at the scale of the bed's mid depth.
static bdl_result visible_truth(const bdl_dia_camera *c, const bdl_dia_scene *s,
                                const bdl_dia_image *im, const bdl_dia_truth_def *t,
                                bdl_dia_cell_truth *cells)
{
    const int ns = im->samples, sw = im->width * ns, sh = im->height * ns;
    const int nx = t->cells[0], ny = t->cells[1];
    double *weight = calloc((size_t)nx * ny, sizeof(double));
    long *seen = calloc((size_t)s->count, sizeof(long));
    if (!weight || !seen) {
        free(weight);
        free(seen);
        return BDL_ERR_NOMEM;
    }
    for (int py = 0; py < sh; ++py) {
        int cy = (int)((long)py * ny / sh);
        for (int px = 0; px < sw; ++px) {
            int cx = (int)((long)px * nx / sw);
            bdl_dia_cell_truth *ct = &cells[cy * nx + cx];
            int32_t hit = im->hit[(size_t)py * sw + px];
            weight[cy * nx + cx] += 1.0;
            if (hit < 0)
                continue;
            ct->area_fraction += 1.0;
            ct->velocity = bdl_v3_add(ct->velocity, s->vel[hit]);
            if (seen[hit] != 1 + cy * nx + cx) { // counts a particle once per cell
                seen[hit] = 1 + cy * nx + cx;
                ct->visible_particles++;
            }
        }
    }
    const double scale = bdl_dia_scale(c, 0.5 * (t->front + t->back));
    for (int k = 0; k < nx * ny; ++k) {
        bdl_dia_cell_truth *ct = &cells[k];
        if (ct->area_fraction > 0.0)
            ct->velocity = bdl_v3_scale(ct->velocity, 1.0 / ct->area_fraction);
        ct->area_fraction /= weight[k];
        ct->du = bdl_v3_dot(ct->velocity, c->right) / scale;
        ct->dv = bdl_v3_dot(ct->velocity, c->down) / scale;
    }
    free(weight);
    free(seen);
    return BDL_OK;
}

/// The truth cells' boxes in camera coordinates (x across, y along the view, z down, from the
/// camera position): the cell's footprint at the bed's mid depth (exact for orthographic views),
/// from the front to the back depth or to the end of the first layer.
typedef struct cell_boxes {
    int nx, ny;
    double cw, ch; ///< cell width and height [m]
    double a0, b0; ///< the image's left and top edges [m]
} cell_boxes;

static cell_boxes make_cell_boxes(const bdl_dia_camera *c, const bdl_dia_image *im,
                                  const bdl_dia_truth_def *t)
{
    const double scale = bdl_dia_scale(c, 0.5 * (t->front + t->back));
    return (cell_boxes){t->cells[0],
                        t->cells[1],
                        scale * im->width / t->cells[0],
                        scale * im->height / t->cells[1],
                        -0.5 * im->width * scale,
                        -0.5 * im->height * scale};
}

/// A world vector in camera coordinates (x across, y depth, z down).
static bdl_vec3 camera_coordinates(const bdl_dia_camera *c, bdl_vec3 v)
{
    return (bdl_vec3){bdl_v3_dot(v, c->right), bdl_v3_dot(v, c->forward), bdl_v3_dot(v, c->down)};
}

/// Sphere i's volume inside each cell's boxes, added to the cells.
static void sphere_solids(const bdl_dia_camera *c, const bdl_dia_scene *s, long i,
                          const bdl_dia_truth_def *t, const cell_boxes *b,
                          bdl_dia_cell_truth *cells)
{
    const int nx = b->nx, ny = b->ny;
    const double cw = b->cw, chh = b->ch, a0 = b->a0, b0 = b->b0;
    const bdl_vec3 q = camera_coordinates(c, bdl_v3_sub(s->pos[i], c->def.position));
    const double r = s->radius[i];
    int cx0 = (int)floor((q.x - r - a0) / cw), cx1 = (int)floor((q.x + r - a0) / cw);
    int cy0 = (int)floor((q.z - r - b0) / chh), cy1 = (int)floor((q.z + r - b0) / chh);
    for (int cy = cy0 < 0 ? 0 : cy0; cy <= cy1 && cy < ny; ++cy)
        for (int cx = cx0 < 0 ? 0 : cx0; cx <= cx1 && cx < nx; ++cx) {
            bdl_vec3 lo = {a0 + cx * cw, t->front, b0 + cy * chh};
            bdl_vec3 hi = {a0 + (cx + 1) * cw, t->back, b0 + (cy + 1) * chh};
            cells[cy * nx + cx].solids_depth += bdl_dia_sphere_box_volume(q, r, lo, hi);
            hi.y = t->front + t->layer;
            cells[cy * nx + cx].solids_layer += bdl_dia_sphere_box_volume(q, r, lo, hi);
        }
}

/// The capsules' volumes in the cells: one grid for all the cells' boxes, whose depth planes are
/// the front, the end of the first layer and the back, so that each capsule is integrated once
/// (dia/capsule.h). Slab 0 is in both boxes; slab 1, when there is one, in the whole depth when the
/// layer ends before the back, else in the layer only.
static bdl_result capsule_solids(const bdl_dia_camera *c, const bdl_dia_scene *s,
                                 const bdl_dia_truth_def *t, const cell_boxes *b,
                                 bdl_dia_cell_truth *cells)
{
    const int nx = b->nx, ny = b->ny;
    const double layer_end = t->front + t->layer;
    const double py[3] = {t->front, fmin(layer_end, t->back), fmax(layer_end, t->back)};
    const int slabs = py[2] > py[1] ? 2 : 1;
    double *px = malloc((size_t)(nx + 1) * sizeof(double));
    double *pz = malloc((size_t)(ny + 1) * sizeof(double));
    double *volume = calloc((size_t)nx * ny * slabs, sizeof(double));
    bdl_result res = px && pz && volume ? BDL_OK : BDL_ERR_NOMEM;
    for (int k = 0; px && k <= nx; ++k)
        px[k] = b->a0 + k * b->cw; // the same cell edges as the spheres' boxes
    for (int k = 0; pz && k <= ny; ++k)
        pz[k] = b->b0 + k * b->ch;
    const bdl_dia_grid g = {{nx, slabs, ny}, {px, py, pz}};
    for (long i = 0; res == BDL_OK && i < s->count; ++i) {
        const double h = half_length(s, i);
        if (h > 0.0 &&
            !bdl_dia_capsule_grid_volume(
                camera_coordinates(c, bdl_v3_sub(s->pos[i], c->def.position)),
                bdl_v3_scale(camera_coordinates(c, s->axis[i]), h), s->radius[i], &g, volume))
            res = BDL_ERR_NOMEM;
    }
    for (int k = 0; res == BDL_OK && k < nx * ny; ++k) {
        const double *v = volume + (size_t)(k / nx) * slabs * nx + k % nx;
        cells[k].solids_depth += v[0] + (slabs > 1 && layer_end < t->back ? v[nx] : 0.0);
        cells[k].solids_layer += v[0] + (slabs > 1 && layer_end > t->back ? v[nx] : 0.0);
    }
    free(px);
    free(pz);
    free(volume);
    return res;
}

/// Solids fractions: each particle's volume inside each cell's box.
static bdl_result solids_truth(const bdl_dia_camera *c, const bdl_dia_scene *s,
                               const bdl_dia_image *im, const bdl_dia_truth_def *t,
                               bdl_dia_cell_truth *cells)
{
    const cell_boxes b = make_cell_boxes(c, im, t);
    for (long i = 0; i < s->count; ++i)
        if (half_length(s, i) == 0.0)
            sphere_solids(c, s, i, t, &b, cells);
    bdl_result r = s->axis ? capsule_solids(c, s, t, &b, cells) : BDL_OK;
    for (int k = 0; k < b.nx * b.ny; ++k) {
        cells[k].solids_depth /= b.cw * b.ch * (t->back - t->front);
        // (a scene without particles' sizes has no first layer: none of its solids is in it)
        cells[k].solids_layer =
            t->layer > 0.0 ? cells[k].solids_layer / (b.cw * b.ch * t->layer) : 0.0;
    }
    return r;
}

bdl_result bdl_dia_truth(const bdl_dia_camera *c, const bdl_dia_scene *s, const bdl_dia_image *im,
                         const bdl_dia_truth_def *t, bdl_dia_cell_truth *cells, long *visible)
{
    const int ns = im->samples, sw = im->width * ns, sh = im->height * ns;
    const int nx = t->cells[0], ny = t->cells[1];
    if (visible) {
        memset(visible, 0, (size_t)s->count * sizeof(long));
        for (size_t k = 0; k < (size_t)sw * (size_t)sh; ++k)
            if (im->hit[k] >= 0)
                visible[im->hit[k]]++;
    }
    if (!cells)
        return BDL_OK;
    for (int cy = 0; cy < ny; ++cy)
        for (int cx = 0; cx < nx; ++cx) {
            bdl_dia_cell_truth *ct = &cells[cy * nx + cx];
            memset(ct, 0, sizeof *ct);
            ct->u0 = (double)cx * im->width / nx, ct->u1 = (double)(cx + 1) * im->width / nx;
            ct->v0 = (double)cy * im->height / ny, ct->v1 = (double)(cy + 1) * im->height / ny;
        }
    bdl_result r = visible_truth(c, s, im, t, cells);
    if (r == BDL_OK)
        r = solids_truth(c, s, im, t, cells);
    return r;
}
