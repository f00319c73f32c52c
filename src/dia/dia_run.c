// bedlam — writes the synthetic camera images of a run and their ground truth.
#define _POSIX_C_SOURCE 200809L // getline
#include "dia/dia_run.h"

#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dia/dia.h"
#include "core/file.h"
#include "core/quat.h"

typedef struct camera_state {
    bdl_dia_camera camera;
    bdl_dia_truth_def truth;
    const bdl_dia_scene_def *def;
    char dir[900];
    FILE *index;      ///< frames.csv
    long frame;       ///< number of the next image (or pair)
    double next;      ///< time of the next image (or first frame of a pair) [s]
    double pending_b; ///< time of the pending second frame, or -1
    long written;
} camera_state;

struct bdl_dia_run {
    int count;
    double end_time; ///< the run's end: a pair that would end after it is not started [s]
    camera_state cam[BDL_MAX_DIA];
    char failure[1200]; ///< the file a write failed on, and why
};

/// Records a failed write of `path` (errno says why) and returns BDL_ERR_IO.
static bdl_result write_failed(bdl_dia_run *r, const char *path)
{
    bdl_describe_write_error(r->failure, sizeof r->failure, path, errno);
    return BDL_ERR_IO;
}

/// Times are due when the step lands within half a step of them.
static int due(const bdl_particle_view *v, double t) { return v->time >= t - 0.5 * v->dt; }

/// The camera of a scene section, with the bed's depth range (front and back along the view,
/// from the domain's corners) and the first layer (the largest species or solids phase diameter).
static bdl_result camera_from_scene(const bdl_scene *s, int index, bdl_dia_camera *camera,
                                    bdl_dia_truth_def *truth)
{
    const bdl_dia_scene_def *d = &s->dias[index];
    bdl_dia_def def = {0};
    def.projection = d->projection;
    def.position = d->position;
    def.target = d->target;
    def.up = d->up;
    def.width = d->width, def.height = d->height;
    def.pixel_size = d->pixel_size;
    def.focal_length = d->focal_length;
    def.samples = d->samples;
    def.lighting = d->lighting;
    // Lights: one, or a ring in the image plane around the given point (LEDs around a lens).
    const bdl_vec3 centre = d->has_light_position ? d->light_position : d->position;
    def.light_count = d->lights < 1                    ? 1
                      : d->lights > BDL_DIA_MAX_LIGHTS ? BDL_DIA_MAX_LIGHTS
                                                       : d->lights;
    def.ambient = d->ambient;
    def.dark = d->dark, def.bright = d->bright;
    def.blur = d->blur, def.noise = d->noise, def.gamma = d->gamma;
    def.bits = d->bits;
    def.seed = d->seed;
    bdl_result r = bdl_dia_camera_init(camera, &def);
    if (r != BDL_OK)
        return r;
    for (int k = 0; k < def.light_count; ++k) {
        double angle = 2.0 * BDL_PI * (k + 0.5) / def.light_count;
        double spread = def.light_count > 1 ? d->light_spread : 0.0;
        bdl_vec3 p = bdl_v3_madd(centre, camera->right, spread * cos(angle));
        camera->def.light_position[k] = bdl_v3_madd(p, camera->down, spread * sin(angle));
        camera->def.light_intensity[k] = d->light_intensity / def.light_count;
    }
    // The bed's depth range: the domain's corners along the view.
    double front = INFINITY, back = -INFINITY;
    for (int k = 0; k < 8; ++k) {
        bdl_vec3 x = {k & 1 ? s->domain_max.x : s->domain_min.x,
                      k & 2 ? s->domain_max.y : s->domain_min.y,
                      k & 4 ? s->domain_max.z : s->domain_min.z};
        double depth = bdl_v3_dot(bdl_v3_sub(x, def.position), camera->forward);
        front = fmin(front, depth);
        back = fmax(back, depth);
    }
    double layer = 0.0;
    for (int k = 0; k < s->species_count; ++k)
        layer =
            fmax(layer, s->species[k].size_dist == BDL_SIZE_SINGLE ? s->species[k].diameter
                                                                   : s->species[k].diameter_max);
    // Solids phases on the grid (a scene without particles): drawn as spheres of their diameters
    // (larger above 200 000 spheres; the layer stays a particle diameter deep).
    if (s->solids.enabled)
        layer = s->solids.phase_count == 0 ? s->solids.def.diameter : 0.0;
    for (int m = 0; s->solids.enabled && m < s->solids.phase_count; ++m)
        layer = fmax(layer, s->solids.phases[m].diameter);
    camera->def.fade_start = front;
    camera->def.fade_length = d->fade;
    truth->cells[0] = d->cells_across, truth->cells[1] = d->cells_down;
    truth->front = front, truth->back = back;
    truth->layer = fmin(layer, back - front);
    return BDL_OK;
}

static void json_vec(FILE *f, const char *name, bdl_vec3 v, const char *tail)
{
    fprintf(f, "  \"%s\": [%.17g, %.17g, %.17g]%s\n", name, v.x, v.y, v.z, tail);
}

static bdl_result write_camera_json(const camera_state *c, double dt)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/camera.json", c->dir);
    bdl_atomic_file af;
    bdl_result r = bdl_atomic_open(&af, path);
    if (r != BDL_OK)
        return r;
    const bdl_dia_def *d = &c->camera.def;
    FILE *f = af.file;
    fprintf(f, "{\n  \"name\": \"%s\",\n  \"kind\": \"dia\",\n", c->def->name);
    fprintf(f, "  \"projection\": \"%s\",\n", bdl_dia_projection_names[d->projection]);
    fprintf(f, "  \"width\": %d,\n  \"height\": %d,\n  \"pixel_size\": %.17g,\n", d->width,
            d->height, d->pixel_size);
    fprintf(f, "  \"focal_length\": %.17g,\n",
            d->projection == BDL_DIA_PERSPECTIVE ? d->focal_length : 0.0);
    json_vec(f, "position", d->position, ",");
    json_vec(f, "right", c->camera.right, ",");
    json_vec(f, "down", c->camera.down, ",");
    json_vec(f, "forward", c->camera.forward, ",");
    fprintf(f, "  \"mapping\": \"depth = (x - position).forward; s = pixel_size (orthographic) or "
               "pixel_size * depth / focal_length (perspective); u = width/2 + (x - "
               "position).right / s; v = height/2 + (x - position).down / s; pixel (i, j) covers "
               "[i, i+1) x [j, j+1), rows from the top\",\n");
    fprintf(f, "  \"lighting\": \"%s\",\n  \"dark\": %.6g,\n  \"bright\": %.6g,\n",
            bdl_dia_lighting_names[d->lighting], d->dark, d->bright);
    fprintf(f, "  \"ambient\": %.6g,\n  \"lights\": [", d->ambient);
    for (int k = 0; k < d->light_count; ++k)
        fprintf(f, "%s{\"position\": [%.9g, %.9g, %.9g], \"intensity\": %.6g}", k ? ", " : "",
                d->light_position[k].x, d->light_position[k].y, d->light_position[k].z,
                d->light_intensity[k]);
    fprintf(f, "],\n");
    fprintf(f, "  \"fade\": %.6g,\n", d->fade_length);
    fprintf(f, "  \"samples\": %d,\n  \"blur\": %.6g,\n  \"noise\": %.6g,\n  \"gamma\": %.6g,\n",
            d->samples, d->blur, d->noise, d->gamma);
    fprintf(f, "  \"bits\": %d,\n  \"cells\": [%d, %d],\n", d->bits, c->truth.cells[0],
            c->truth.cells[1]);
    fprintf(f, "  \"front_depth\": %.17g,\n  \"back_depth\": %.17g,\n  \"layer_depth\": %.17g,\n",
            c->truth.front, c->truth.back, c->truth.layer);
    fprintf(f,
            "  \"start\": %.17g,\n  \"stop\": %.17g,\n  \"interval\": %.17g,\n  \"pair_dt\": "
            "%.17g,\n  \"dt\": %.17g\n}\n",
            c->def->start, c->def->stop, c->def->interval, c->def->pair_dt, dt);
    return bdl_atomic_commit(&af);
}

/// The last row kept of a camera's index on resuming.
typedef struct index_row {
    long frame;   ///< its image number; -1: no row kept
    double time;  ///< when it was taken [s]
    int first_of; ///< its image is the first of a PIV pair ("_a")
} index_row;

/// Reads one row "frame,time,image,..." into `row`; 0 when it is not one.
static int parse_row(const char *line, index_row *row)
{
    char *end;
    const long frame = strtol(line, &end, 10);
    if (end == line || *end != ',')
        return 0;
    const char *t = end + 1;
    const double time = strtod(t, &end);
    if (end == t || *end != ',')
        return 0;
    const char *comma = strchr(end + 1, ',');
    *row = (index_row){frame, time,
                       comma && comma - (end + 1) > 6 && !strncmp(comma - 6, "_a.png", 6)};
    return 1;
}

/// A resumed camera's frames.csv rewritten (atomically) without the rows of images taken after
/// t_keep [s], which the run is about to take again; `last` is the last row kept. Returns 0 when
/// there is no index with a header to continue, 1 when there is, -1 on a failure.
static int trim_index(const char *path, double t_keep, index_row *last)
{
    last->frame = -1;
    char why[256];
    FILE *in = bdl_open_regular(path, why, sizeof why);
    if (!in)
        return 0;
    bdl_atomic_file af;
    if (bdl_atomic_open(&af, path) != BDL_OK) {
        fclose(in);
        return -1;
    }
    char *line = NULL;
    size_t capacity = 0;
    long lines = 0;
    ssize_t length;
    while ((length = getline(&line, &capacity, in)) > 0 && line[length - 1] == '\n') {
        index_row row;
        const int keep = lines++ == 0 || (parse_row(line, &row) && row.time <= t_keep);
        if (keep)
            fputs(line, af.file);
        if (keep && lines > 1)
            *last = row;
    }
    free(line);
    const int read_error = ferror(in);
    fclose(in);
    if (read_error || lines == 0) {
        bdl_atomic_abort(&af);
        return read_error ? -1 : 0;
    }
    return bdl_atomic_commit(&af) == BDL_OK ? 1 : -1;
}

/// frames.csv of camera c, and where its numbering stands. Image k is at start + k interval: a
/// resumed run drops the rows after its checkpoint and continues the numbering after the last
/// image kept (and takes the second frame of a PIV pair whose first one it kept). A camera whose
/// index is not in the output folder yet (a camera added on resuming, or a resumed run writing
/// to a new folder) starts its index with the header and takes the image due now.
static bdl_result open_index(camera_state *c, const bdl_particle_view *now, int resume, char *why,
                             size_t len)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/frames.csv", c->dir);
    const double t0 = now->time, start = c->def->start, interval = c->def->interval;
    index_row last = {-1, 0.0, 0};
    const int continues = resume ? trim_index(path, t0 + 0.5 * now->dt, &last) : 0;
    if (continues < 0) {
        bdl_describe_write_error(why, len, path, errno);
        return BDL_ERR_IO;
    }
    long frame = t0 <= start ? 0 : (long)ceil((t0 - start) / interval - 1e-9);
    if (continues && due(now, start + frame * interval))
        ++frame; // taken by the first run
    c->frame = frame;
    c->next = start + frame * interval;
    if (continues && last.first_of && c->def->pair_dt > 0.0) { // the pair's second frame is due
        c->frame = last.frame;
        c->pending_b = last.time + c->def->pair_dt;
    }
    c->index = fopen(path, continues ? "a" : "w");
    if (!c->index) {
        bdl_describe_write_error(why, len, path, errno);
        return BDL_ERR_IO;
    }
    if (!continues)
        fprintf(c->index, "frame,time,image,particles,cells\n");
    return BDL_OK;
}

bdl_result bdl_dia_run_open(const bdl_scene *s, const bdl_particle_view *now, const char *out_dir,
                            int resume, bdl_dia_run **out, char *why, size_t len)
{
    *out = NULL;
    if (s->dia_count == 0)
        return BDL_OK;
    bdl_dia_run *r = calloc(1, sizeof *r);
    if (!r)
        return BDL_ERR_NOMEM;
    r->end_time = s->end_time;
    for (int k = 0; k < s->dia_count; ++k) {
        camera_state *c = &r->cam[r->count++];
        c->def = &s->dias[k];
        c->pending_b = -1.0;
        if (camera_from_scene(s, k, &c->camera, &c->truth) != BDL_OK) {
            snprintf(why, len, "[camera %s]: the view is degenerate", c->def->name);
            bdl_dia_run_close(r);
            return BDL_ERR_SCENE;
        }
        snprintf(c->dir, sizeof c->dir, "%s/dia/%s", out_dir, c->def->name);
        if (bdl_check_writable_dir(c->dir, why, len) != BDL_OK ||
            write_camera_json(c, now->dt) != BDL_OK) {
            if (!why[0])
                snprintf(why, len, "cannot write %s/camera.json", c->dir);
            bdl_dia_run_close(r);
            return BDL_ERR_IO;
        }
        if (open_index(c, now, resume, why, len) != BDL_OK) {
            bdl_dia_run_close(r);
            return BDL_ERR_IO;
        }
    }
    *out = r;
    return BDL_OK;
}

/// The particles of an image; in scenes with rods each row ends with the axis and the half shaft
/// length (0 for a sphere).
static bdl_result write_particles(const char *path, const bdl_dia_camera *cam,
                                  const bdl_dia_scene *s, const long *visible, int samples)
{
    bdl_atomic_file af;
    bdl_result r = bdl_atomic_open_csv(
        &af, path,
        s->axis ? "id,x,y,z,vx,vy,vz,radius,u,v,depth,visible_samples,visible_fraction,ux,uy,uz,"
                  "half_length"
                : "id,x,y,z,vx,vy,vz,radius,u,v,depth,visible_samples,visible_fraction");
    if (r != BDL_OK)
        return r;
    for (long i = 0; i < s->count; ++i) {
        double u, v, z;
        bdl_dia_project(cam, s->pos[i], &u, &v, &z);
        double area = bdl_dia_outline_area(cam, s, i, samples);
        fprintf(af.file, "%u,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.6f,%.6f,%.9g,%ld,%.4f", s->id[i],
                s->pos[i].x, s->pos[i].y, s->pos[i].z, s->vel[i].x, s->vel[i].y, s->vel[i].z,
                s->radius[i], u, v, z, visible[i], area > 0.0 ? fmin(1.0, visible[i] / area) : 0.0);
        if (s->axis)
            fprintf(af.file, ",%.9g,%.9g,%.9g,%.9g", s->axis[i].x, s->axis[i].y, s->axis[i].z,
                    s->half_length[i]);
        fputc('\n', af.file);
    }
    return bdl_atomic_commit(&af);
}

static bdl_result write_cells(const char *path, const bdl_dia_truth_def *t,
                              const bdl_dia_cell_truth *cells)
{
    bdl_atomic_file af;
    bdl_result r = bdl_atomic_open_csv(&af, path,
                                       "column,row,u0,v0,u1,v1,area_fraction,solids_depth,"
                                       "solids_layer,visible_particles,vx,vy,vz,du,dv");
    if (r != BDL_OK)
        return r;
    for (int j = 0; j < t->cells[1]; ++j)
        for (int i = 0; i < t->cells[0]; ++i) {
            const bdl_dia_cell_truth *c = &cells[j * t->cells[0] + i];
            fprintf(af.file,
                    "%d,%d,%.4f,%.4f,%.4f,%.4f,%.6f,%.6f,%.6f,%ld,%.6g,%.6g,%.6g,%.6g,%.6g\n", i, j,
                    c->u0, c->v0, c->u1, c->v1, c->area_fraction, c->solids_depth, c->solids_layer,
                    c->visible_particles, c->velocity.x, c->velocity.y, c->velocity.z, c->du,
                    c->dv);
        }
    return bdl_atomic_commit(&af);
}

/// Renders one image of camera c and writes it with its truth; `part` is "" (single), "_a" or
/// "_b". Cell truth goes with single images and first frames.
static bdl_result shoot(bdl_dia_run *run, camera_state *c, const bdl_particle_view *v,
                        const char *part)
{
    bdl_dia_scene s = {v->count, v->pos, v->vel, v->radius, v->id, NULL, NULL};
    bdl_vec3 *axis = NULL;
    if (v->orient && v->half_length) { // a rod's axis is its body z axis
        if (!(axis = malloc((size_t)(v->count > 0 ? v->count : 1) * sizeof(bdl_vec3))))
            return BDL_ERR_NOMEM;
        for (long i = 0; i < v->count; ++i)
            axis[i] = bdl_q_axis_z(v->orient[i]);
        s.axis = axis, s.half_length = v->half_length;
    }
    const bool second = part[0] != '\0' && part[1] == 'b'; // the "_b" image of a pair
    bdl_dia_image im;
    bdl_result r = bdl_dia_render(&c->camera, &s, c->frame * 2 + second, &im);
    if (r != BDL_OK) {
        free(axis);
        return r;
    }
    long *visible = malloc((size_t)(v->count > 0 ? v->count : 1) * sizeof(long));
    const int ncells = c->truth.cells[0] * c->truth.cells[1];
    bdl_dia_cell_truth *cells = second ? NULL : malloc((size_t)ncells * sizeof(bdl_dia_cell_truth));
    char stem[1000], image[1100], parts[1100], cellp[1100];
    snprintf(stem, sizeof stem, "%s/frame_%06ld", c->dir, c->frame);
    snprintf(image, sizeof image, "%s%s.png", stem, part);
    snprintf(parts, sizeof parts, "%s%s_particles.csv", stem, part);
    snprintf(cellp, sizeof cellp, "%s_cells.csv", stem);
    if (!visible || (!second && !cells))
        r = BDL_ERR_NOMEM;
    if (r == BDL_OK)
        r = bdl_dia_truth(&c->camera, &s, &im, &c->truth, cells, visible);
    if (r == BDL_OK && (r = bdl_dia_write_png(&im, c->camera.def.bits, image)) == BDL_ERR_IO)
        write_failed(run, image);
    if (r == BDL_OK &&
        (r = write_particles(parts, &c->camera, &s, visible, im.samples)) == BDL_ERR_IO)
        write_failed(run, parts);
    if (r == BDL_OK && cells && (r = write_cells(cellp, &c->truth, cells)) == BDL_ERR_IO)
        write_failed(run, cellp);
    if (r == BDL_OK) {
        const char *base = strrchr(stem, '/') + 1;
        fprintf(c->index, "%ld,%.9g,%s%s.png,%s%s_particles.csv,%s\n", c->frame, v->time, base,
                part, base, part, cells ? strrchr(cellp, '/') + 1 : "");
        if (fflush(c->index) != 0 || ferror(c->index)) {
            char index[1024];
            snprintf(index, sizeof index, "%s/frames.csv", c->dir);
            r = write_failed(run, index);
        }
        c->written++;
    }
    free(visible);
    free(cells);
    free(axis);
    bdl_dia_image_free(&im);
    return r;
}

bdl_result bdl_dia_run_step(bdl_dia_run *r, const bdl_particle_view *v)
{
    for (int k = 0; r && k < r->count; ++k) {
        camera_state *c = &r->cam[k];
        bdl_result res = BDL_OK;
        if (c->pending_b >= 0.0 && due(v, c->pending_b)) {
            res = shoot(r, c, v, "_b");
            c->pending_b = -1.0;
            c->frame++;
        } else if (c->pending_b < 0.0 && due(v, c->next)) {
            if (c->def->stop > 0.0 && c->next > c->def->stop + 0.5 * v->dt) {
                c->next = INFINITY; // the burst is over
                continue;
            }
            int pair = c->def->pair_dt > 0.0;
            if (pair && v->time + c->def->pair_dt > r->end_time + 0.5 * v->dt) {
                c->next = INFINITY; // the run ends before the pair's second frame
                continue;
            }
            res = shoot(r, c, v, pair ? "_a" : "");
            if (pair)
                c->pending_b = v->time + c->def->pair_dt;
            else
                c->frame++;
            while (due(v, c->next))
                c->next += c->def->interval;
        }
        if (res != BDL_OK)
            return res;
    }
    return BDL_OK;
}

int bdl_dia_run_due(const bdl_dia_run *r, const bdl_particle_view *v)
{
    for (int k = 0; r && k < r->count; ++k) {
        const camera_state *c = &r->cam[k];
        if (c->pending_b >= 0.0 ? due(v, c->pending_b) : due(v, c->next))
            return 1;
    }
    return 0;
}

bdl_result bdl_dia_run_sync(bdl_dia_run *r)
{
    for (int k = 0; r && k < r->count; ++k)
        if (bdl_sync_file(r->cam[k].index) != BDL_OK) {
            char index[1024];
            snprintf(index, sizeof index, "%s/frames.csv", r->cam[k].dir);
            return write_failed(r, index);
        }
    return BDL_OK;
}

const char *bdl_dia_run_failure(const bdl_dia_run *r) { return r ? r->failure : ""; }

long bdl_dia_run_count(const bdl_dia_run *r)
{
    long n = 0;
    for (int k = 0; r && k < r->count; ++k)
        n += r->cam[k].written;
    return n;
}

void bdl_dia_run_close(bdl_dia_run *r)
{
    if (!r)
        return;
    for (int k = 0; k < r->count; ++k)
        if (r->cam[k].index)
            fclose(r->cam[k].index);
    free(r);
}
