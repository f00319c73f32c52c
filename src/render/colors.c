// bedlam — the colour of each particle: the field a colour mode shows, mapped through the
// categorical, sequential, diverging or cyclic map over the frame's range (fixed by the view, else
// the data's), and the voidage or solids fraction around each particle when that is the field.
//
// Voidage is the particles' own: their spheres deposited on cells of three diameters
// (analysis/voidage.h). Parcels are not spheres of their drawn size, and the gas already holds
// what they make of the voidage: for them it is the gas's, as for the solids fraction. The
// solids fraction is what the gas sees at the particle, 1 - eps read from the snapshot's copy of
// the gas's cells with the coupling's kernel (analysis/tent.h); without a gas, 1 - the
// particles' own voidage.
//
// A rod's orientation is its axis u up to sign (u and -u are the same rod), with z taken as the
// vertical, as the camera's "up" is: a colour is a function of the snapshot alone, which carries
// no gravity, and the default gravity and every bundled scene's point along -z. Tilt is the
// angle between the axis and the vertical, atan2(|u_xy|, |u_z|), from 0 (upright) to 90 deg
// (lying); azimuth is the angle of the axis's horizontal part from +x, atan2(u_y, u_x), modulo
// 180 deg. A sphere has neither, and a vertical rod has no azimuth: they show the missing-value
// grey.
#include <math.h>
#include <stdlib.h>

#include "analysis/tent.h"
#include "render/colormap.h"
#include "render/renderer_internal.h"

const char *bdl_color_mode_label(bdl_color_mode mode)
{
    return (unsigned)mode < BDL_COLOR_MODE_COUNT ? bdl_color_mode_labels[mode] : "?";
}

const char *bdl_color_mode_unit(bdl_color_mode mode)
{
    return (unsigned)mode < BDL_COLOR_MODE_COUNT ? bdl_color_mode_units[mode] : "";
}

static int diverging(bdl_color_mode mode)
{
    return mode == BDL_COLOR_VX || mode == BDL_COLOR_VY || mode == BDL_COLOR_VZ;
}

bdl_colormap_kind bdl_color_mode_map(bdl_color_mode mode)
{
    if (mode == BDL_COLOR_AZIMUTH)
        return BDL_CMAP_CYCLIC;
    return diverging(mode) ? BDL_CMAP_DIVERGING : BDL_CMAP_SEQUENTIAL;
}

static int orientation_mode(bdl_color_mode mode)
{
    return mode == BDL_COLOR_TILT || mode == BDL_COLOR_AZIMUTH;
}

/// Tilt or azimuth of particle i [deg]; NaN when it has none.
static float orientation(bdl_color_mode mode, const bdl_snapshot *s, long i)
{
    const float deg = (float)(180.0 / BDL_PI);
    const float *a = s->axis ? &s->axis[3 * i] : NULL;
    if (!a || (a[0] == 0.0f && a[1] == 0.0f && (mode == BDL_COLOR_AZIMUTH || a[2] == 0.0f)))
        return NAN;
    if (mode == BDL_COLOR_TILT)
        return deg * atan2f(hypotf(a[0], a[1]), fabsf(a[2]));
    float phi = deg * atan2f(a[1], a[0]); // (-180, 180]
    phi = phi < 0.0f ? phi + 180.0f : phi;
    return phi >= 180.0f ? phi - 180.0f : phi; // a tiny negative angle + 180 rounds to 180
}

/// The scalar a mode maps through the colour map; `local` is the particle's voidage or solids
/// fraction in those modes.
static float field_value(bdl_color_mode mode, const bdl_snapshot *s, long i, float local)
{
    const float *v = &s->vel[3 * i];
    switch (mode) {
    case BDL_COLOR_COORDINATION:
        return (float)s->coordination[i];
    case BDL_COLOR_SPEED:
        return sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    case BDL_COLOR_VX:
    case BDL_COLOR_VY:
    case BDL_COLOR_VZ:
        return v[mode - BDL_COLOR_VX];
    case BDL_COLOR_VOIDAGE:
    case BDL_COLOR_SOLIDS:
        return local;
    case BDL_COLOR_TILT:
    case BDL_COLOR_AZIMUTH:
        return orientation(mode, s, i);
    default:
        return 0.0f;
    }
}

uint8_t bdl_color_byte(float c)
{
    c = c < 0.0f ? 0.0f : (c > 1.0f ? 1.0f : c);
    return (uint8_t)lrintf(255.0f * c);
}

void bdl_particle_color(bdl_color_mode mode, const bdl_snapshot *snap, long i, float local,
                        const float range[2], uint8_t rgb[3])
{
    float c[3];
    if (mode == BDL_COLOR_SPECIES) {
        bdl_category_color(snap->species[i], c);
    } else {
        float x = field_value(mode, snap, i, local);
        float span = range[1] - range[0];
        float t = span > 0.0f ? (x - range[0]) / span : 0.5f;
        bdl_colormap_kind map = bdl_color_mode_map(mode);
        if (map == BDL_CMAP_CYCLIC)
            t -= floorf(t); // a range narrower than the period wraps round
        if (orientation_mode(mode) && isnan(x))
            bdl_colormap_missing(c);
        else
            bdl_colormap_eval(map, t, c);
    }
    for (int k = 0; k < 3; ++k)
        rgb[k] = bdl_color_byte(c[k]);
}

/// The data's range for automatic colouring: speeds and solids fractions from 0, velocity
/// components symmetric about 0, coordination numbers from 0 in whole steps; the angles over
/// their whole span.
static void auto_range(const bdl_render_colors *c, bdl_color_mode mode, const bdl_snapshot *s,
                       float range[2])
{
    if (orientation_mode(mode)) { // all the angles there are, the same in every frame
        range[0] = 0.0f;
        range[1] = mode == BDL_COLOR_TILT ? 90.0f : 180.0f;
        return;
    }
    float lo = INFINITY, hi = -INFINITY;
    for (long i = 0; i < s->count; ++i) {
        float x = field_value(mode, s, i, c->local_at ? c->local_at[i] : 1.0f);
        lo = fminf(lo, x);
        hi = fmaxf(hi, x);
    }
    if (s->count == 0)
        lo = hi = 0.0f;
    switch (mode) {
    case BDL_COLOR_COORDINATION:
        range[0] = 0.0f;
        range[1] = fmaxf(hi, 1.0f);
        break;
    case BDL_COLOR_SPEED:
    case BDL_COLOR_SOLIDS:
        range[0] = 0.0f;
        range[1] = hi > 0.0f ? hi : 1.0f;
        break;
    case BDL_COLOR_VX:
    case BDL_COLOR_VY:
    case BDL_COLOR_VZ: {
        float m = fmaxf(fabsf(lo), fabsf(hi));
        range[0] = m > 0.0f ? -m : -1.0f;
        range[1] = m > 0.0f ? m : 1.0f;
        break;
    }
    default:
        range[0] = lo;
        range[1] = hi > lo ? hi : lo + 1.0f;
        break;
    }
}

/// The grid is made on first use, from the scene's domain and its largest particle.
static int voidage_grid_ready(bdl_render_colors *c, const bdl_scene *scene)
{
    if (c->voidage_ready)
        return 1;
    double lo[3] = {scene->domain_min.x, scene->domain_min.y, scene->domain_min.z};
    double hi[3] = {scene->domain_max.x, scene->domain_max.y, scene->domain_max.z};
    double d = 0.0;
    for (int k = 0; k < scene->species_count; ++k)
        d = fmax(d, fmax(scene->species[k].diameter, scene->species[k].diameter_max));
    // Cells of three diameters: enough particles per cell for a mean, small enough to
    // resolve bubbles and the free surface.
    if (bdl_voidage_grid_init(&c->voidage, lo, hi, 3.0 * d, scene->periodic) != BDL_OK)
        return 0;
    c->voidage_ready = 1;
    return 1;
}

/// Room for one value per particle of the snapshot.
static int local_ready(bdl_render_colors *c, const bdl_snapshot *s)
{
    if (s->count <= c->local_capacity)
        return 1;
    float *a = realloc(c->local_at, (size_t)s->count * sizeof(float));
    if (!a)
        return 0;
    c->local_at = a;
    c->local_capacity = s->count;
    return 1;
}

/// The particles' own voidage at each particle (the snapshot's spheres on cells of three
/// diameters).
static void own_voidage(bdl_render_colors *c, const bdl_snapshot *s)
{
    bdl_voidage_deposit(&c->voidage, s->count, s->pos, s->radius);
    for (long i = 0; i < s->count; ++i)
        c->local_at[i] = bdl_voidage_at(&c->voidage, &s->pos[3 * i]);
}

bdl_tent_field bdl_render_voidage_field(const bdl_snapshot *s)
{
    bdl_tent_field f = {.cell = s->voidage};
    for (int a = 0; a < 3; ++a) {
        f.n[a] = s->voidage_n[a];
        f.periodic[a] = s->voidage_periodic[a];
        f.lo[a] = s->voidage_lo[a];
        f.h[a] = s->voidage_h[a];
        f.width[a] = s->voidage_kernel[a];
    }
    return f;
}

/// The gas's voidage at each particle, read with the coupling's kernel.
static void gas_voidage(bdl_render_colors *c, const bdl_snapshot *s)
{
    const bdl_tent_field f = bdl_render_voidage_field(s);
    for (long i = 0; i < s->count; ++i) {
        const double x[3] = {s->pos[3 * i], s->pos[3 * i + 1], s->pos[3 * i + 2]};
        c->local_at[i] = (float)bdl_tent_sample(&f, x);
    }
}

/// Per particle the value of the voidage or solids mode (see the top of the file); local_at
/// stays NULL when out of memory (every particle then shows the value 1).
static void compute_local(bdl_render_colors *c, const bdl_scene *scene, const bdl_snapshot *s,
                          bdl_color_mode mode)
{
    const int gas = s->voidage_n[0] > 0 && s->voidage;
    const int from_gas = gas && (mode == BDL_COLOR_SOLIDS || s->parcels);
    if (!local_ready(c, s) || (!from_gas && !voidage_grid_ready(c, scene))) {
        free(c->local_at); // no stale values of another frame
        c->local_at = NULL;
        c->local_capacity = 0;
        return;
    }
    if (from_gas)
        gas_voidage(c, s);
    else
        own_voidage(c, s);
    if (mode == BDL_COLOR_SOLIDS)
        for (long i = 0; i < s->count; ++i)
            c->local_at[i] = 1.0f - c->local_at[i];
}

void bdl_render_colors_prepare(bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v)
{
    bdl_render_colors *c = &r->colors;
    if (v->color == BDL_COLOR_VOIDAGE || v->color == BDL_COLOR_SOLIDS)
        compute_local(c, &r->scene, s, v->color);
    if (v->range_fixed) {
        c->range[0] = v->range[0];
        c->range[1] = v->range[1];
    } else if (v->color != BDL_COLOR_SPECIES) {
        auto_range(c, v->color, s, c->range);
    }
}

void bdl_render_colors_particle(const bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v,
                                long i, uint8_t rgb[3])
{
    const bdl_render_colors *c = &r->colors;
    const int local = v->color == BDL_COLOR_VOIDAGE || v->color == BDL_COLOR_SOLIDS;
    bdl_particle_color(v->color, s, i, c->local_at && local ? c->local_at[i] : 1.0f, c->range, rgb);
}

void bdl_render_colors_destroy(bdl_renderer *r)
{
    if (r->colors.voidage_ready)
        bdl_voidage_grid_free(&r->colors.voidage);
    free(r->colors.local_at);
}
