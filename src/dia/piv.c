// bedlam — PIV: multi-pass FFT cross-correlation with window offset.
//
// For a window a(x) of image A and the window b(x) of image B (each with its mean taken off),
// the cross-correlation R(s) = sum_x a(x) b(x + s) peaks at the displacement s of the pattern
// from A to B. It is computed for all s at once through the FFT, R = F^-1(conj(F a) F b), which
// is circular: R at s and at s - W are the same, so |s| must stay below W / 2, and a large s
// loses the pairs that leave the window (the peak weakens and is biased towards zero). Hence the
// passes (Willert and Gharib 1991; Westerweel, Dabiri and Gharib 1997): a first pass with large
// windows measures the displacement roughly, and every later pass shifts the window in B by the
// previous pass's displacement rounded to whole pixels, so its own peak sits within half a pixel
// of the origin where no pairs are lost. The peak's sub-pixel position along each axis is that
// of the Gaussian through the highest value R_0 and its neighbours R_-1, R_+1:
//     delta = (ln R_-1 - ln R_+1) / (2 ln R_-1 - 4 ln R_0 + 2 ln R_+1),
// exact for the Gaussian particle images a camera sees. Between passes the normalised median
// test (Westerweel and Scarano 2005) replaces vectors that differ from their neighbours'
// median by more than a threshold times the neighbours' median residual (+ 0.1 px), so that one
// bad vector does not misplace the next pass's windows; on the last pass it only flags them.
#include "dia/piv.h"

#include <fftw3.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/// One pass's windows and their vectors.
typedef struct pass_grid {
    int window, stride, nx, ny, x0, y0; ///< window side, stride, count, top-left of the first
    int plan;                           ///< index of the plans for this window size
    double *du, *dv, *peak;
    unsigned char *outlier;
} pass_grid;

/// FFTW plans and buffers for one window size.
typedef struct window_plans {
    int window;
    double *real;            ///< window x window
    fftw_complex *fa, *fb;   ///< window x (window / 2 + 1)
    fftw_plan forward, back; ///< real -> fa, fa -> real
} window_plans;

struct bdl_dia_piv {
    bdl_dia_piv_def def;
    int width, height;
    pass_grid grid[BDL_DIA_PIV_MAX_PASSES];
    window_plans plans[BDL_DIA_PIV_MAX_PASSES];
    int plan_count;
    double *u, *v; ///< the last pass's window centres
    double *scratch;
};

bdl_dia_piv_def bdl_default_piv_def(void)
{
    bdl_dia_piv_def d = {0};
    d.passes = 4;
    d.pass[0] = (bdl_dia_piv_pass){256, 0.5};
    for (int k = 1; k < 4; ++k)
        d.pass[k] = (bdl_dia_piv_pass){128, 0.75};
    d.median_threshold = 2.0;
    return d;
}

static bdl_result check_def(const bdl_dia_piv_def *def, int width, int height)
{
    if (def->passes < 1 || def->passes > BDL_DIA_PIV_MAX_PASSES)
        return BDL_ERR_ARGS;
    for (int k = 0; k < def->passes; ++k) {
        const bdl_dia_piv_pass *p = &def->pass[k];
        if (p->window < 8 || p->window > width || p->window > height)
            return BDL_ERR_ARGS;
        if (!(p->overlap >= 0.0 && p->overlap < 1.0))
            return BDL_ERR_ARGS;
    }
    return def->median_threshold >= 0.0 ? BDL_OK : BDL_ERR_ARGS;
}

/// The plans for a window size, made when the size is first met.
static int plans_for(bdl_dia_piv *piv, int window)
{
    for (int k = 0; k < piv->plan_count; ++k)
        if (piv->plans[k].window == window)
            return k;
    window_plans *p = &piv->plans[piv->plan_count];
    p->window = window;
    p->real = fftw_malloc(sizeof(double) * (size_t)window * window);
    p->fa = fftw_malloc(sizeof(fftw_complex) * (size_t)window * (window / 2 + 1));
    p->fb = fftw_malloc(sizeof(fftw_complex) * (size_t)window * (window / 2 + 1));
    if (!p->real || !p->fa || !p->fb)
        return -1;
    p->forward = fftw_plan_dft_r2c_2d(window, window, p->real, p->fa, FFTW_ESTIMATE);
    p->back = fftw_plan_dft_c2r_2d(window, window, p->fa, p->real, FFTW_ESTIMATE);
    if (!p->forward || !p->back)
        return -1;
    return piv->plan_count++;
}

static bdl_result setup_pass(bdl_dia_piv *piv, int k)
{
    pass_grid *g = &piv->grid[k];
    g->window = piv->def.pass[k].window;
    g->stride = (int)lround(g->window * (1.0 - piv->def.pass[k].overlap));
    g->stride = g->stride < 1 ? 1 : g->stride;
    g->nx = (piv->width - g->window) / g->stride + 1;
    g->ny = (piv->height - g->window) / g->stride + 1;
    g->x0 = (piv->width - ((g->nx - 1) * g->stride + g->window)) / 2;
    g->y0 = (piv->height - ((g->ny - 1) * g->stride + g->window)) / 2;
    const size_t n = (size_t)g->nx * g->ny;
    g->du = malloc(n * sizeof(double));
    g->dv = malloc(n * sizeof(double));
    g->peak = malloc(n * sizeof(double));
    g->outlier = calloc(n, 1);
    g->plan = plans_for(piv, g->window);
    return g->du && g->dv && g->peak && g->outlier && g->plan >= 0 ? BDL_OK : BDL_ERR_NOMEM;
}

bdl_result bdl_dia_piv_create(const bdl_dia_piv_def *def, int width, int height, bdl_dia_piv **out)
{
    *out = NULL;
    bdl_result res = check_def(def, width, height);
    if (res != BDL_OK)
        return res;
    bdl_dia_piv *piv = calloc(1, sizeof(*piv));
    if (!piv)
        return BDL_ERR_NOMEM;
    piv->def = *def, piv->width = width, piv->height = height;
    for (int k = 0; k < def->passes && res == BDL_OK; ++k)
        res = setup_pass(piv, k);
    if (res == BDL_OK) {
        const pass_grid *g = &piv->grid[def->passes - 1];
        const size_t n = (size_t)g->nx * g->ny;
        size_t most = 0; // the median test's scratch serves every pass
        for (int k = 0; k < def->passes; ++k)
            if ((size_t)piv->grid[k].nx * piv->grid[k].ny > most)
                most = (size_t)piv->grid[k].nx * piv->grid[k].ny;
        piv->u = malloc(n * sizeof(double));
        piv->v = malloc(n * sizeof(double));
        piv->scratch = malloc(2 * most * sizeof(double));
        if (!piv->u || !piv->v || !piv->scratch)
            res = BDL_ERR_NOMEM;
        for (size_t m = 0; res == BDL_OK && m < n; ++m) {
            piv->u[m] = g->x0 + (double)(m % g->nx) * g->stride + 0.5 * g->window;
            piv->v[m] = g->y0 + (double)(m / g->nx) * g->stride + 0.5 * g->window;
        }
    }
    if (res != BDL_OK) {
        bdl_dia_piv_destroy(piv);
        return res;
    }
    *out = piv;
    return BDL_OK;
}

void bdl_dia_piv_destroy(bdl_dia_piv *piv)
{
    if (!piv)
        return;
    for (int k = 0; k < BDL_DIA_PIV_MAX_PASSES; ++k) {
        pass_grid *g = &piv->grid[k];
        free(g->du), free(g->dv), free(g->peak), free(g->outlier);
    }
    for (int k = 0; k <= piv->plan_count && k < BDL_DIA_PIV_MAX_PASSES; ++k) {
        window_plans *p = &piv->plans[k];
        if (p->forward)
            fftw_destroy_plan(p->forward);
        if (p->back)
            fftw_destroy_plan(p->back);
        fftw_free(p->real), fftw_free(p->fa), fftw_free(p->fb);
    }
    free(piv->u), free(piv->v), free(piv->scratch);
    free(piv);
}

/// Copies the window x window block at (x0, y0) of img into out with its mean taken off; pixels
/// outside the image are set to the mean (zero after). Returns the sum of squares.
static double load_window(const double *img, int width, int height, int x0, int y0, int window,
                          double *out)
{
    double sum = 0.0;
    long inside = 0;
    for (int y = 0; y < window; ++y)
        for (int x = 0; x < window; ++x) {
            int xx = x0 + x, yy = y0 + y;
            if (xx >= 0 && yy >= 0 && xx < width && yy < height)
                sum += img[(size_t)yy * width + xx], ++inside;
        }
    const double mean = inside > 0 ? sum / (double)inside : 0.0;
    double squares = 0.0;
    for (int y = 0; y < window; ++y)
        for (int x = 0; x < window; ++x) {
            int xx = x0 + x, yy = y0 + y;
            double g = xx >= 0 && yy >= 0 && xx < width && yy < height
                           ? img[(size_t)yy * width + xx] - mean
                           : 0.0;
            out[(size_t)y * window + x] = g;
            squares += g * g;
        }
    return squares;
}

/// Sub-pixel offset of a peak from the values at -1, 0, +1: Gaussian, or parabola when a value
/// is not positive.
static double peak_offset(double rm, double r0, double rp)
{
    if (rm > 0.0 && r0 > 0.0 && rp > 0.0) {
        double lm = log(rm), l0 = log(r0), lp = log(rp), den = 2.0 * lm - 4.0 * l0 + 2.0 * lp;
        if (den < 0.0)
            return (lm - lp) / den;
    }
    double den = 2.0 * (rm - 2.0 * r0 + rp);
    return den < 0.0 ? (rm - rp) / den : 0.0;
}

/// Correlates the window at (ax, ay) in a with the one at (bx, by) in b: the displacement of
/// the peak [px] and the correlation coefficient there.
static void correlate(bdl_dia_piv *piv, window_plans *p, const double *a, const double *b, int ax,
                      int ay, int bx, int by, double *sx, double *sy, double *peak)
{
    const int W = p->window, half = W / 2 + 1;
    double qa = load_window(a, piv->width, piv->height, ax, ay, W, p->real);
    fftw_execute_dft_r2c(p->forward, p->real, p->fa);
    double qb = load_window(b, piv->width, piv->height, bx, by, W, p->real);
    fftw_execute_dft_r2c(p->forward, p->real, p->fb);
    for (size_t k = 0; k < (size_t)W * half; ++k) { // conj(A) B
        double re = p->fa[k][0] * p->fb[k][0] + p->fa[k][1] * p->fb[k][1];
        double im = p->fa[k][0] * p->fb[k][1] - p->fa[k][1] * p->fb[k][0];
        p->fa[k][0] = re, p->fa[k][1] = im;
    }
    fftw_execute_dft_c2r(p->back, p->fa, p->real);
    size_t best = 0;
    for (size_t k = 1; k < (size_t)W * W; ++k)
        if (p->real[k] > p->real[best])
            best = k;
    const int px = (int)(best % W), py = (int)(best / W);
    const double *r = p->real;
    double r0 = r[best];
    double ox = peak_offset(r[py * W + (px + W - 1) % W], r0, r[py * W + (px + 1) % W]);
    double oy = peak_offset(r[((py + W - 1) % W) * W + px], r0, r[((py + 1) % W) * W + px]);
    *sx = (px >= W / 2 ? px - W : px) + ox;
    *sy = (py >= W / 2 ? py - W : py) + oy;
    double norm = sqrt(qa * qb) * (double)W * W; // the inverse FFT is not normalised
    *peak = norm > 0.0 ? r0 / norm : 0.0;
}

/// The displacement of a pass's field at (x, y), bilinear between its window centres (held at
/// the edge values beyond them).
static void predict(const pass_grid *g, double x, double y, double *du, double *dv)
{
    double fx = (x - g->x0 - 0.5 * g->window) / g->stride;
    double fy = (y - g->y0 - 0.5 * g->window) / g->stride;
    fx = fx < 0.0 ? 0.0 : fx > g->nx - 1 ? g->nx - 1 : fx;
    fy = fy < 0.0 ? 0.0 : fy > g->ny - 1 ? g->ny - 1 : fy;
    int i0 = (int)fx, j0 = (int)fy;
    int i1 = i0 + 1 < g->nx ? i0 + 1 : i0, j1 = j0 + 1 < g->ny ? j0 + 1 : j0;
    double tx = fx - i0, ty = fy - j0;
    const double *f[2] = {g->du, g->dv};
    double out[2];
    for (int c = 0; c < 2; ++c)
        out[c] = (1 - ty) * ((1 - tx) * f[c][j0 * g->nx + i0] + tx * f[c][j0 * g->nx + i1]) +
                 ty * ((1 - tx) * f[c][j1 * g->nx + i0] + tx * f[c][j1 * g->nx + i1]);
    *du = out[0], *dv = out[1];
}

static void run_pass(bdl_dia_piv *piv, int k, const double *a, const double *b)
{
    pass_grid *g = &piv->grid[k];
    window_plans *p = &piv->plans[g->plan];
    for (int j = 0; j < g->ny; ++j)
        for (int i = 0; i < g->nx; ++i) {
            const int ax = g->x0 + i * g->stride, ay = g->y0 + j * g->stride;
            double pu = 0.0, pv = 0.0, sx, sy;
            if (k > 0)
                predict(&piv->grid[k - 1], ax + 0.5 * g->window, ay + 0.5 * g->window, &pu, &pv);
            const int ou = (int)lround(pu), ov = (int)lround(pv);
            const size_t m = (size_t)j * g->nx + i;
            correlate(piv, p, a, b, ax, ay, ax + ou, ay + ov, &sx, &sy, &g->peak[m]);
            g->du[m] = ou + sx, g->dv[m] = ov + sy;
        }
}

static double median(double *x, int n)
{
    for (int i = 1; i < n; ++i) // insertion sort: n <= 8
        for (int j = i; j > 0 && x[j - 1] > x[j]; --j) {
            double t = x[j];
            x[j] = x[j - 1], x[j - 1] = t;
        }
    return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

/// The normalised median residual of component f at window (i, j) and its neighbours' median.
/// A neighbour beyond the field's edge is taken as the reflection of the one opposite through
/// (i, j), 2 f(i, j) - f(opposite), so that a field with a uniform gradient passes the test at
/// its edges as inside.
static double median_residual(const pass_grid *g, const double *f, int i, int j, double *med)
{
    double nb[8], res[8];
    int n = 0;
    const double f0 = f[j * g->nx + i];
    for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
            int ii = i + di, jj = j + dj, io = i - di, jo = j - dj;
            if (!di && !dj)
                continue;
            if (ii >= 0 && jj >= 0 && ii < g->nx && jj < g->ny)
                nb[n++] = f[jj * g->nx + ii];
            else if (io >= 0 && jo >= 0 && io < g->nx && jo < g->ny)
                nb[n++] = 2.0 * f0 - f[jo * g->nx + io];
        }
    if (n < 2) {
        *med = f0;
        return 0.0;
    }
    double tmp[8];
    memcpy(tmp, nb, sizeof(double) * n);
    *med = median(tmp, n);
    for (int m = 0; m < n; ++m)
        res[m] = fabs(nb[m] - *med);
    return fabs(f0 - *med) / (median(res, n) + 0.1);
}

/// Flags every vector first, against the unchanged field, then (with `replace`) replaces the
/// flagged ones by their neighbours' medians.
static void median_test(pass_grid *g, double threshold, int replace, double *scratch)
{
    const size_t n = (size_t)g->nx * g->ny;
    for (int j = 0; j < g->ny; ++j)
        for (int i = 0; i < g->nx; ++i) {
            const size_t m = (size_t)j * g->nx + i;
            double mu, mv;
            double ru = median_residual(g, g->du, i, j, &mu);
            double rv = median_residual(g, g->dv, i, j, &mv);
            g->outlier[m] = threshold > 0.0 && (ru > threshold || rv > threshold);
            scratch[m] = mu, scratch[n + m] = mv;
        }
    for (size_t m = 0; replace && m < n; ++m)
        if (g->outlier[m])
            g->du[m] = scratch[m], g->dv[m] = scratch[n + m];
}

bdl_result bdl_dia_piv_run(bdl_dia_piv *piv, const double *a, const double *b,
                           bdl_dia_piv_field *field)
{
    for (int k = 0; k < piv->def.passes; ++k) {
        run_pass(piv, k, a, b);
        median_test(&piv->grid[k], piv->def.median_threshold, k + 1 < piv->def.passes,
                    piv->scratch);
    }
    const pass_grid *g = &piv->grid[piv->def.passes - 1];
    *field = (bdl_dia_piv_field){g->nx, g->ny, piv->u, piv->v, g->du, g->dv, g->peak, g->outlier};
    return BDL_OK;
}

void bdl_dia_mass_flux(const double *voidage, const double *vel_u, const double *vel_v, long n,
                       double density, double *flux_u, double *flux_v)
{
    for (long k = 0; k < n; ++k) {
        double solids = density * (1.0 - voidage[k]);
        flux_u[k] = solids * vel_u[k];
        flux_v[k] = solids * vel_v[k];
    }
}
