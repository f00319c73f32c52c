// bedlam — multigrid-preconditioned conjugate gradients for the pressure equation.
//
// Internally the equation is written as M x = b with M = -div(c grad) (symmetric positive
// semi-definite) on compact cell arrays, per unit volume: the coupling of two cells across a
// face normal to axis a is K = c / h_a^2, and a Dirichlet side couples a boundary cell to its
// ghost value 2 p_side - x, which adds 2K to the diagonal and 2K p_side to b.
#include "core/parallel.h"
#include "cfd/poisson.h"
#if defined(BDL_WITH_MPI)
#include "cfd/poisson_hypre.h"
#endif

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define MAX_LEVELS      16
#define CHUNKS          64 ///< fixed partition for sums: the same for any thread count
#define SMOOTH_SWEEPS   2  ///< Jacobi sweeps before and after the coarse correction
#define COARSEST_SWEEPS 40 ///< Jacobi sweeps on the coarsest level
#define JACOBI_WEIGHT   0.8

typedef struct level {
    int n[3];
    int coarsen[3]; ///< how this level is coarsened into the next
    long cells;
    double *K[3]; ///< face couplings, compact face arrays (n[a] + 1 faces along a)
    double *diag;
    double *x, *b, *r, *t;
} level;

struct bdl_poisson {
    bdl_grid grid;
    int periodic[3];
    int dirichlet[6];
    int singular; ///< no Dirichlet side: the solution is defined up to a constant
    int level_count;
    level levels[MAX_LEVELS];
    double *d, *q, *z; ///< CG vectors on the finest level
    double *xc, *r;    ///< solution and residual on the finest level
    double *zeros;     ///< a row of zero couplings (n[0] + 1)
    /// The direct solver: M's lower band (band_cholesky's storage, kd + 1 rows a cell), factored
    /// by the last bdl_poisson_set_coefficients when `factored` (otherwise the multigrid's
    /// levels are built and CG solves).
    double *band;
    int kd, factored;
#if defined(BDL_WITH_MPI)
    bdl_hypre_poisson *hypre; ///< NULL: bedlam's own solver
#endif
};

BDL_CHOICE_WORDS(bdl_pressure_solver, BDL_PRESSURE_SOLVERS);
const char *const bdl_pressure_solver_labels[] = {BDL_PRESSURE_SOLVERS(BDL_ENUM_LABEL) NULL};

int bdl_pressure_solver_available(bdl_pressure_solver solver)
{
#if defined(BDL_WITH_MPI)
    return solver == BDL_PRESSURE_MGPCG || solver == BDL_PRESSURE_HYPRE ||
           solver == BDL_PRESSURE_DIRECT;
#else
    return solver == BDL_PRESSURE_MGPCG || solver == BDL_PRESSURE_DIRECT;
#endif
}

int bdl_poisson_direct_band(const int n[3], const int periodic[3])
{
    for (int a = 0; a < 3; ++a)
        if (periodic[a] && n[a] > 1)
            return -1;
    if (n[2] > 1)
        return n[0] * n[1];
    return n[1] > 1 ? n[0] : n[0] > 1 ? 1 : 0;
}

double bdl_poisson_direct_cost(const int n[3], const int periodic[3])
{
    const double band = bdl_poisson_direct_band(n, periodic);
    return (double)n[0] * n[1] * n[2] * band * band;
}

/// With hypre, the solver's own (1) or bedlam's (0).
static int uses_hypre(const bdl_poisson *p)
{
#if defined(BDL_WITH_MPI)
    return p->hypre != NULL;
#else
    (void)p;
    return 0;
#endif
}

static long cell_of(const level *L, int i, int j, int k)
{
    return ((long)k * L->n[1] + j) * L->n[0] + i;
}

static long face_of(const level *L, int a, int i, int j, int k)
{
    long f0 = L->n[0] + (a == 0), f1 = L->n[1] + (a == 1);
    return ((long)k * f1 + j) * f0 + i;
}

static long face_count(const level *L, int a)
{
    return (long)(L->n[0] + (a == 0)) * (L->n[1] + (a == 1)) * (L->n[2] + (a == 2));
}

static int level_alloc(level *L)
{
    L->cells = (long)L->n[0] * L->n[1] * L->n[2];
    for (int a = 0; a < 3; ++a)
        if (!(L->K[a] = calloc((size_t)face_count(L, a), sizeof(double))))
            return 0;
    L->diag = calloc((size_t)L->cells, sizeof(double));
    L->x = calloc((size_t)L->cells, sizeof(double));
    L->b = calloc((size_t)L->cells, sizeof(double));
    L->r = calloc((size_t)L->cells, sizeof(double));
    L->t = calloc((size_t)L->cells, sizeof(double));
    return L->diag && L->x && L->b && L->r && L->t;
}

static void level_free(level *L)
{
    for (int a = 0; a < 3; ++a)
        free(L->K[a]);
    free(L->diag);
    free(L->x);
    free(L->b);
    free(L->r);
    free(L->t);
}

bdl_poisson *bdl_poisson_create(const bdl_grid *g, const int dirichlet[6])
{
    return bdl_poisson_create_solver(g, dirichlet, BDL_PRESSURE_MGPCG);
}

bdl_poisson *bdl_poisson_create_solver(const bdl_grid *g, const int dirichlet[6],
                                       bdl_pressure_solver solver)
{
    if (!bdl_pressure_solver_available(solver))
        return NULL;
    bdl_poisson *p = calloc(1, sizeof *p);
    if (!p)
        return NULL;
    p->grid = *g;
    p->singular = 1;
    for (int a = 0; a < 3; ++a) {
        p->periodic[a] = g->periodic[a];
        for (int s = 0; s < 2; ++s) {
            p->dirichlet[2 * a + s] = !g->periodic[a] && dirichlet && dirichlet[2 * a + s];
            if (p->dirichlet[2 * a + s])
                p->singular = 0;
        }
    }
    // Levels: halve every even axis until none is even or the grid is tiny.
    int n[3] = {g->n[0], g->n[1], g->n[2]};
    for (int l = 0; l < MAX_LEVELS; ++l) {
        level *L = &p->levels[l];
        memcpy(L->n, n, sizeof n);
        if (!level_alloc(L)) {
            p->level_count = l + 1;
            bdl_poisson_destroy(p);
            return NULL;
        }
        p->level_count = l + 1;
        int any = 0;
        for (int a = 0; a < 3; ++a) {
            L->coarsen[a] = n[a] >= 2; // odd counts too: the last coarse cell has one child
            any |= L->coarsen[a];
        }
        if (!any || L->cells <= 8) {
            memset(L->coarsen, 0, sizeof L->coarsen);
            break;
        }
        for (int a = 0; a < 3; ++a)
            n[a] = L->coarsen[a] ? (n[a] + 1) / 2 : n[a];
    }
    long cells = p->levels[0].cells;
    p->d = calloc((size_t)cells, sizeof(double));
    p->q = calloc((size_t)cells, sizeof(double));
    p->z = calloc((size_t)cells, sizeof(double));
    p->xc = calloc((size_t)cells, sizeof(double));
    p->r = calloc((size_t)cells, sizeof(double));
    p->zeros = calloc((size_t)g->n[0] + 1, sizeof(double));
    if (solver == BDL_PRESSURE_DIRECT) {
        p->kd = bdl_poisson_direct_band(g->n, g->periodic);
        if (p->kd < 0 || p->kd > BDL_POISSON_DIRECT_BAND_MAX ||
            bdl_poisson_direct_cost(g->n, g->periodic) > BDL_POISSON_DIRECT_COST_MAX ||
            !(p->band = malloc((size_t)cells * (size_t)(p->kd + 1) * sizeof(double)))) {
            bdl_poisson_destroy(p);
            return NULL;
        }
    }
    if (!p->d || !p->q || !p->z || !p->xc || !p->r || !p->zeros) {
        bdl_poisson_destroy(p);
        return NULL;
    }
#if defined(BDL_WITH_MPI)
    if (solver == BDL_PRESSURE_HYPRE &&
        !(p->hypre = bdl_hypre_poisson_create(g->n, p->periodic, p->singular))) {
        bdl_poisson_destroy(p);
        return NULL;
    }
#endif
    return p;
}

void bdl_poisson_destroy(bdl_poisson *p)
{
    if (!p)
        return;
    for (int l = 0; l < p->level_count; ++l)
        level_free(&p->levels[l]);
    free(p->d);
    free(p->q);
    free(p->z);
    free(p->xc);
    free(p->r);
    free(p->zeros);
    free(p->band);
#if defined(BDL_WITH_MPI)
    bdl_hypre_poisson_destroy(p->hypre);
#endif
    free(p);
}

/// Diagonal of M: every coupling to a neighbour (itself excluded, across a periodic axis of one
/// cell), and twice the coupling of a Dirichlet side.
static void build_diagonal(const bdl_poisson *p, level *L)
{
    BDL_PARALLEL_FOR(
        L->cells >= BDL_GRID_PARALLEL_MIN,
        for (int k = 0; k < L->n[2]; ++k) for (int j = 0; j < L->n[1]; ++j) for (int i = 0;
                                                                                 i < L->n[0]; ++i) {
            int c[3] = {i, j, k};
            double d = 0.0;
            for (int a = 0; a < 3; ++a) {
                int lo[3] = {i, j, k}, hi[3] = {i, j, k};
                hi[a] += 1;
                double klo = L->K[a][face_of(L, a, lo[0], lo[1], lo[2])];
                double khi = L->K[a][face_of(L, a, hi[0], hi[1], hi[2])];
                if (p->periodic[a]) {
                    if (L->n[a] > 1)
                        d += klo + khi;
                    continue;
                }
                d += c[a] == 0 ? 2.0 * klo : klo;
                d += c[a] == L->n[a] - 1 ? 2.0 * khi : khi;
            }
            L->diag[cell_of(L, i, j, k)] = d;
        });
}

/// Coarse couplings: the fine faces making up each coarse face, summed, halved across a
/// coarsened axis.
static void restrict_couplings(const level *F, level *C)
{
    for (int a = 0; a < 3; ++a) {
        double factor = F->coarsen[a] ? 0.5 : 1.0;
        int f1[3] = {C->n[0] + (a == 0), C->n[1] + (a == 1), C->n[2] + (a == 2)};
        for (int k = 0; k < f1[2]; ++k)
            for (int j = 0; j < f1[1]; ++j)
                for (int i = 0; i < f1[0]; ++i) {
                    int base[3] = {i, j, k};
                    int span[3];
                    for (int b = 0; b < 3; ++b) {
                        span[b] = b != a && F->coarsen[b] ? 2 : 1;
                        base[b] = F->coarsen[b] ? 2 * base[b] : base[b];
                    }
                    // The high boundary face of an odd axis is the fine boundary face.
                    if (base[a] > F->n[a])
                        base[a] = F->n[a];
                    double sum = 0.0;
                    for (int dk = 0; dk < span[2]; ++dk)
                        for (int dj = 0; dj < span[1]; ++dj)
                            for (int di = 0; di < span[0]; ++di) {
                                int f[3] = {base[0] + di, base[1] + dj, base[2] + dk};
                                if ((a != 0 && f[0] >= F->n[0]) || (a != 1 && f[1] >= F->n[1]) ||
                                    (a != 2 && f[2] >= F->n[2]))
                                    continue; // the missing second child of an odd axis' last cell
                                sum += F->K[a][face_of(F, a, f[0], f[1], f[2])];
                            }
                    C->K[a][face_of(C, a, i, j, k)] = factor * sum;
                }
    }
}

/// The Cholesky factor L (M = L L^T) of the symmetric band matrix of n rows and half-bandwidth
/// kd in place, lower band storage: column j holds rows j to j + kd, entry (i, j) at
/// a[j (kd + 1) + i - j] (LAPACK's layout for dpbtrf). Column by column: its diagonal's square
/// root, the column scaled by it, and its outer product taken from the columns to its right.
/// The diagonal is left as its reciprocal 1 / L_jj, for band_solve to multiply by. Returns 0
/// when a pivot is not positive (M not positive definite).
static int band_cholesky(double *a, long n, int kd)
{
    const int ld = kd + 1;
    for (long j = 0; j < n; ++j) {
        double *cj = a + j * ld;
        if (!(cj[0] > 0.0))
            return 0;
        const double inv = 1.0 / sqrt(cj[0]);
        cj[0] = inv;
        const int m = (int)(kd < n - 1 - j ? kd : n - 1 - j);
        for (int i = 1; i <= m; ++i)
            cj[i] *= inv;
        for (int i = 1; i <= m; ++i) {
            double *ci = a + (j + i) * ld; // column j + i: rows j + i to j + m here
            const double f = cj[i];
            for (int l = i; l <= m; ++l)
                ci[l - i] -= f * cj[l];
        }
    }
    return 1;
}

/// Solves L L^T x = b in place with the factor of band_cholesky (its diagonal inverted).
static void band_solve(const double *a, long n, int kd, double *b)
{
    const int ld = kd + 1;
    for (long j = 0; j < n; ++j) { // L y = b
        const double *cj = a + j * ld;
        const int m = (int)(kd < n - 1 - j ? kd : n - 1 - j);
        b[j] *= cj[0];
        for (int i = 1; i <= m; ++i)
            b[j + i] -= cj[i] * b[j];
    }
    for (long j = n - 1; j >= 0; --j) { // L^T x = y
        const double *cj = a + j * ld;
        const int m = (int)(kd < n - 1 - j ? kd : n - 1 - j);
        double sum = b[j];
        for (int i = 1; i <= m; ++i)
            sum -= cj[i] * b[j + i];
        b[j] = sum * cj[0];
    }
}

/// M of the finest level into the band (column c holds rows c to c + kd) and its Cholesky
/// factors; returns whether M was positive definite. Without a Dirichlet side cell 0 is pinned
/// (its row and column the identity's): the rest of the system holds the solution that is zero
/// there, and the mean is removed afterwards.
static int factor_band(bdl_poisson *p)
{
    const level *L = &p->levels[0];
    const int ld = p->kd + 1;
    const long stride[3] = {1, L->n[0], (long)L->n[0] * L->n[1]};
    memset(p->band, 0, (size_t)L->cells * (size_t)ld * sizeof(double));
    for (int k = 0; k < L->n[2]; ++k)
        for (int j = 0; j < L->n[1]; ++j)
            for (int i = 0; i < L->n[0]; ++i) {
                const long c = cell_of(L, i, j, k);
                const int at[3] = {i, j, k};
                double *col = p->band + c * ld;
                col[0] = L->diag[c];
                for (int a = 0; a < 3; ++a) {
                    if (at[a] + 1 >= L->n[a]) // (no periodic axis of more than one cell here)
                        continue;
                    const int hi[3] = {i + (a == 0), j + (a == 1), k + (a == 2)};
                    col[stride[a]] = -L->K[a][face_of(L, a, hi[0], hi[1], hi[2])];
                }
            }
    if (p->singular) {
        memset(p->band, 0, (size_t)ld * sizeof(double));
        p->band[0] = 1.0;
    }
    return band_cholesky(p->band, L->cells, p->kd);
}

void bdl_poisson_set_coefficients(bdl_poisson *p, double *const c[3])
{
    const bdl_grid *g = &p->grid;
    level *L = &p->levels[0];
    for (int a = 0; a < 3; ++a) {
        const double inv_h2 = 1.0 / (g->h[a] * g->h[a]);
        int f1[3] = {L->n[0] + (a == 0), L->n[1] + (a == 1), L->n[2] + (a == 2)};
        BDL_PARALLEL_FOR(
            L->cells >= BDL_GRID_PARALLEL_MIN,
            for (int k = 0; k < f1[2]; ++k) for (int j = 0; j < f1[1]; ++j) for (int i = 0;
                                                                                 i < f1[0]; ++i) {
                int idx[3] = {i, j, k};
                double K = c[a][bdl_grid_index(g, i, j, k)] * inv_h2;
                if (idx[a] == 0 || idx[a] == L->n[a]) {
                    if (p->periodic[a])
                        K = c[a]
                             [bdl_grid_index(g, a == 0 ? 0 : i, a == 1 ? 0 : j, a == 2 ? 0 : k)] *
                            inv_h2;
                    else if (!p->dirichlet[2 * a + (idx[a] != 0)])
                        K = 0.0;
                }
                L->K[a][face_of(L, a, i, j, k)] = K;
            });
    }
    build_diagonal(p, L);
    p->factored = p->band && factor_band(p);
    if (p->factored)
        return;
#if defined(BDL_WITH_MPI)
    if (p->hypre) { // hypre builds its own levels
        bdl_hypre_poisson_set(p->hypre, L->diag, L->K);
        return;
    }
#endif
    for (int l = 1; l < p->level_count; ++l) {
        restrict_couplings(&p->levels[l - 1], &p->levels[l]);
        build_diagonal(p, &p->levels[l]);
    }
}

/// The neighbours of row m (of n) along axis a: coupling rows and value rows, low then high.
/// A side without a neighbour couples through a row of zeros (a Dirichlet side is in the
/// diagonal), so the stencil below needs no branches.
typedef struct row_link {
    const double *K_lo, *x_lo, *K_hi, *x_hi;
} row_link;

static row_link link_rows(const bdl_poisson *p, const level *L, int a, int j, int k,
                          const double *x)
{
    const double *row = x + cell_of(L, 0, j, k);
    row_link r = {p->zeros, row, p->zeros, row};
    const int n = L->n[a], m = a == 1 ? j : k;
    if (n == 1)
        return r;
    const long stride = a == 1 ? L->n[0] : (long)L->n[0] * L->n[1];
    const double *K = L->K[a];
    const long f_lo = face_of(L, a, 0, j, k),
               f_hi = a == 1 ? face_of(L, a, 0, j + 1, k) : face_of(L, a, 0, j, k + 1);
    if (m > 0)
        r.K_lo = K + f_lo, r.x_lo = row - stride;
    else if (p->periodic[a])
        r.K_lo = K + f_lo, r.x_lo = row + (n - 1) * stride;
    if (m < n - 1)
        r.K_hi = K + f_hi, r.x_hi = row + stride;
    else if (p->periodic[a]) // the wrapping face is stored as face 0
        r.K_hi = K + (a == 1 ? face_of(L, a, 0, 0, k) : face_of(L, a, 0, j, 0)),
        r.x_hi = row - (n - 1) * stride;
    return r;
}

/// The couplings of cell i of a row to its neighbours along y and z, sum K x. An axis of one cell
/// couples through rows of zeros (link_rows), left out here when `y` or `z` is 0: the same sum to
/// the bit (0 x added to a finite sum leaves it unchanged), without the loads.
static inline double off_diagonal(const row_link *y, const row_link *z, int i, int ylink, int zlink)
{
    if (ylink && zlink)
        return y->K_lo[i] * y->x_lo[i] + y->K_hi[i] * y->x_hi[i] + z->K_lo[i] * z->x_lo[i] +
               z->K_hi[i] * z->x_hi[i];
    if (zlink)
        return z->K_lo[i] * z->x_lo[i] + z->K_hi[i] * z->x_hi[i];
    if (ylink)
        return y->K_lo[i] * y->x_lo[i] + y->K_hi[i] * y->x_hi[i];
    return 0.0;
}

/// out = M x on level L.
static void apply(const bdl_poisson *p, const level *L, const double *x, double *out)
{
    const int n0 = L->n[0], n1 = L->n[1], n2 = L->n[2];
    BDL_PARALLEL_FOR(
        L->cells >= BDL_GRID_PARALLEL_MIN,
        for (int k = 0; k < n2; ++k) for (int j = 0; j < n1; ++j) {
            const long c0 = cell_of(L, 0, j, k);
            const double *xr = x + c0, *dg = L->diag + c0;
            double *o = out + c0;
            const row_link y = link_rows(p, L, 1, j, k, x), z = link_rows(p, L, 2, j, k, x);
            const int ylink = n1 > 1, zlink = n2 > 1;
            for (int i = 0; i < n0; ++i)
                o[i] = dg[i] * xr[i] - off_diagonal(&y, &z, i, ylink, zlink);
            if (n0 == 1)
                continue;
            const double *Kx = L->K[0] + face_of(L, 0, 0, j, k);
            for (int i = 1; i < n0; ++i)
                o[i] -= Kx[i] * xr[i - 1];
            for (int i = 0; i < n0 - 1; ++i)
                o[i] -= Kx[i + 1] * xr[i + 1];
            if (p->periodic[0]) {
                o[0] -= Kx[0] * xr[n0 - 1];
                o[n0 - 1] -= Kx[0] * xr[0];
            }
        });
}

/// Sum of a[i] b[i] (b NULL: of a[i]) in CHUNKS fixed chunks added in order, so the result does
/// not depend on the thread count.
static double chunked_sum(const double *a, const double *b, long n)
{
    double partial[CHUNKS];
    BDL_PARALLEL_FOR(
        n >= BDL_GRID_PARALLEL_MIN, for (int c = 0; c < CHUNKS; ++c) {
            long lo = n * c / CHUNKS, hi = n * (c + 1) / CHUNKS;
            double s = 0.0;
            for (long i = lo; i < hi; ++i)
                s += b ? a[i] * b[i] : a[i];
            partial[c] = s;
        });
    double s = 0.0;
    for (int c = 0; c < CHUNKS; ++c)
        s += partial[c];
    return s;
}

static double dot(const double *a, const double *b, long n) { return chunked_sum(a, b, n); }

static void remove_mean(double *a, long n)
{
    double mean = chunked_sum(a, NULL, n) / (double)n;
    BDL_PARALLEL_FOR(n >= BDL_GRID_PARALLEL_MIN, for (long i = 0; i < n; ++i) a[i] -= mean;);
}

static void jacobi(const bdl_poisson *p, level *L, int sweeps)
{
    for (int s = 0; s < sweeps; ++s) {
        apply(p, L, L->x, L->t);
        BDL_PARALLEL_FOR(L->cells >= BDL_GRID_PARALLEL_MIN,
                         for (long c = 0; c < L->cells; ++c) if (L->diag[c] > 0.0) L->x[c] +=
                         JACOBI_WEIGHT * (L->b[c] - L->t[c]) / L->diag[c];);
    }
}

/// One Gauss-Seidel sweep over the cells of one colour ((i + j + k) % 2 == color), in place.
/// Cells of a colour never neighbour each other (see red_black_ok), so the order within a sweep
/// and the thread count do not matter.
static void colour_sweep(const bdl_poisson *p, level *L, int color)
{
    const int n0 = L->n[0], n1 = L->n[1], n2 = L->n[2];
    double *x = L->x;
    BDL_PARALLEL_FOR(
        L->cells >= BDL_GRID_PARALLEL_MIN,
        for (int k = 0; k < n2; ++k) for (int j = 0; j < n1; ++j) {
            const long c0 = cell_of(L, 0, j, k);
            double *xr = x + c0;
            const double *dg = L->diag + c0, *b = L->b + c0;
            const row_link y = link_rows(p, L, 1, j, k, x), z = link_rows(p, L, 2, j, k, x);
            const double *Kx = L->K[0] + face_of(L, 0, 0, j, k);
            const int wrap = p->periodic[0] && n0 > 1, ylink = n1 > 1, zlink = n2 > 1;
            for (int i = (j + k + color) & 1; i < n0; i += 2) {
                double off = off_diagonal(&y, &z, i, ylink, zlink);
                if (n0 > 1) {
                    off += i > 0 ? Kx[i] * xr[i - 1] : wrap ? Kx[0] * xr[n0 - 1] : 0.0;
                    off += i < n0 - 1 ? Kx[i + 1] * xr[i + 1] : wrap ? Kx[0] * xr[0] : 0.0;
                }
                if (dg[i] > 0.0)
                    xr[i] = (b[i] + off) / dg[i];
            }
        });
}

/// Red-black ordering needs every neighbour to have the other colour: no periodic axis with an
/// odd number of cells above one (whose last and first cells would share a colour).
static int red_black_ok(const bdl_poisson *p, const level *L)
{
    for (int a = 0; a < 3; ++a)
        if (p->periodic[a] && L->n[a] > 1 && L->n[a] % 2 == 1)
            return 0;
    return 1;
}

/// Smoothing on level L: red-black Gauss-Seidel, red then black before the coarse correction and
/// black then red after it (so the V-cycle stays a symmetric operator, as CG needs); damped
/// Jacobi where red-black ordering is impossible.
static void smooth(const bdl_poisson *p, level *L, int sweeps, int after)
{
    if (!red_black_ok(p, L)) {
        jacobi(p, L, sweeps);
        return;
    }
    for (int s = 0; s < sweeps; ++s) {
        colour_sweep(p, L, after ? 1 : 0);
        colour_sweep(p, L, after ? 0 : 1);
    }
}

/// x = V-cycle(b) on level l, from x = 0: a fixed linear, symmetric operator of b.
static void vcycle(const bdl_poisson *p, int l)
{
    level *L = (level *)&p->levels[l];
    memset(L->x, 0, (size_t)L->cells * sizeof(double));
    if (l == p->level_count - 1) {
        jacobi(p, L, COARSEST_SWEEPS);
        return;
    }
    smooth(p, L, SMOOTH_SWEEPS, 0);
    apply(p, L, L->x, L->t);
    level *C = (level *)&p->levels[l + 1];
    memset(C->b, 0, (size_t)C->cells * sizeof(double));
    for (int k = 0; k < L->n[2]; ++k)
        for (int j = 0; j < L->n[1]; ++j)
            for (int i = 0; i < L->n[0]; ++i) {
                long c = cell_of(L, i, j, k);
                long cc = cell_of(C, L->coarsen[0] ? i / 2 : i, L->coarsen[1] ? j / 2 : j,
                                  L->coarsen[2] ? k / 2 : k);
                C->b[cc] += L->b[c] - L->t[c];
            }
    vcycle(p, l + 1);
    BDL_PARALLEL_FOR(L->cells >= BDL_GRID_PARALLEL_MIN,
                     for (int k = 0; k < L->n[2]; ++k) for (int j = 0; j < L->n[1];
                                                            ++j) for (int i = 0; i < L->n[0]; ++i)
                         L->x[cell_of(L, i, j, k)] +=
                     C->x[cell_of(C, L->coarsen[0] ? i / 2 : i, L->coarsen[1] ? j / 2 : j,
                                  L->coarsen[2] ? k / 2 : k)];);
    smooth(p, L, SMOOTH_SWEEPS, 1);
}

/// z = V-cycle(r) on the finest level.
static void precondition(bdl_poisson *p, const double *r, double *z)
{
    level *L = &p->levels[0];
    memcpy(L->b, r, (size_t)L->cells * sizeof(double));
    vcycle(p, 0);
    memcpy(z, L->x, (size_t)L->cells * sizeof(double));
    if (p->singular)
        remove_mean(z, L->cells);
}

/// b = -f + Dirichlet terms, compact, from the padded f.
static void right_hand_side(const bdl_poisson *p, const double *f, const double p_side[6],
                            double *b)
{
    const bdl_grid *g = &p->grid;
    const level *L = &p->levels[0];
    BDL_PARALLEL_FOR(
        L->cells >= BDL_GRID_PARALLEL_MIN,
        for (int k = 0; k < L->n[2]; ++k) for (int j = 0; j < L->n[1]; ++j) for (int i = 0;
                                                                                 i < L->n[0]; ++i) {
            double v = -f[bdl_grid_index(g, i, j, k)];
            int idx[3] = {i, j, k};
            for (int a = 0; a < 3; ++a) {
                int hi[3] = {i, j, k};
                hi[a] += 1;
                if (idx[a] == 0 && p->dirichlet[2 * a])
                    v += 2.0 * L->K[a][face_of(L, a, i, j, k)] * p_side[2 * a];
                if (idx[a] == L->n[a] - 1 && p->dirichlet[2 * a + 1])
                    v += 2.0 * L->K[a][face_of(L, a, hi[0], hi[1], hi[2])] * p_side[2 * a + 1];
            }
            b[cell_of(L, i, j, k)] = v;
        });
}

static void to_compact(const bdl_poisson *p, const double *padded, double *compact)
{
    const level *L = &p->levels[0];
    BDL_PARALLEL_FOR(L->cells >= BDL_GRID_PARALLEL_MIN,
                     for (int k = 0; k < L->n[2]; ++k) for (int j = 0; j < L->n[1];
                                                            ++j) for (int i = 0; i < L->n[0]; ++i)
                         compact[cell_of(L, i, j, k)] = padded[bdl_grid_index(&p->grid, i, j, k)];);
}

static void to_padded(const bdl_poisson *p, const double *compact, double *padded)
{
    const level *L = &p->levels[0];
    BDL_PARALLEL_FOR(L->cells >= BDL_GRID_PARALLEL_MIN,
                     for (int k = 0; k < L->n[2]; ++k) for (int j = 0; j < L->n[1];
                                                            ++j) for (int i = 0; i < L->n[0]; ++i)
                         padded[bdl_grid_index(&p->grid, i, j, k)] = compact[cell_of(L, i, j, k)];);
}

void bdl_poisson_residual(bdl_poisson *p, const double *x, const double *f, const double p_side[6],
                          double *r)
{
    level *L = &p->levels[0];
    double *xc = p->d, *b = p->q, *mx = p->z;
    to_compact(p, x, xc);
    right_hand_side(p, f, p_side, b);
    apply(p, L, xc, mx);
    // f - div(c grad x) = -(b - M x) in the original sign.
    for (long c = 0; c < L->cells; ++c)
        mx[c] = -(b[c] - mx[c]);
    to_padded(p, mx, r);
}

/// The direct solve: x += M^-1 r from the band's factors, r then the new residual; again on
/// that residual (iterative refinement) while it is above tol, at most three times in all.
/// Returns whether the residual ends at or below tol.
static int solve_band(bdl_poisson *p, double *r, double *x, double norm_b, double tol,
                      bdl_poisson_stats *st)
{
    const level *L = &p->levels[0];
    const long n = L->cells;
    double *dx = p->d;
    for (int pass = 1; pass <= 3; ++pass) {
        memcpy(dx, r, (size_t)n * sizeof(double));
        if (p->singular)
            dx[0] = 0.0;
        band_solve(p->band, n, p->kd, dx);
        for (long i = 0; i < n; ++i)
            x[i] += dx[i];
        apply(p, L, dx, p->q);
        for (long i = 0; i < n; ++i)
            r[i] -= p->q[i];
        st->iterations = pass;
        st->residual = norm_b > 0.0 ? sqrt(dot(r, r, n)) / norm_b : 0.0;
        if (st->residual <= tol)
            return 1;
    }
    return 0;
}

int bdl_poisson_solve(bdl_poisson *p, double *x, const double *f, const double p_side[6],
                      double tol, int max_iter, bdl_poisson_stats *stats)
{
    level *L = &p->levels[0];
    const long n = L->cells;
    double *xc = p->xc, *r = p->r;
    to_compact(p, x, xc);
    right_hand_side(p, f, p_side, r);
    if (p->singular)
        remove_mean(r, n);
    const double norm_b = sqrt(dot(r, r, n));
    apply(p, L, xc, p->q);
    BDL_PARALLEL_FOR(n >= BDL_GRID_PARALLEL_MIN, for (long i = 0; i < n; ++i) r[i] -= p->q[i];);
    double res = norm_b > 0.0 ? sqrt(dot(r, r, n)) / norm_b : 0.0;
    bdl_poisson_stats st = {0, res, res};
    int converged = res <= tol;
#if defined(BDL_WITH_MPI)
    if (!converged && p->hypre) {
        // r = b - M x0; hypre is given b itself (a Dirichlet side's part and all).
        right_hand_side(p, f, p_side, r);
        if (p->singular)
            remove_mean(r, n);
        converged =
            bdl_hypre_poisson_solve(p->hypre, r, xc, tol, max_iter, &st.iterations, &st.residual);
        // The residual of the system itself (hypre's is its pinned one when singular).
        apply(p, L, xc, p->q);
        for (long i = 0; i < n; ++i)
            p->q[i] = r[i] - p->q[i];
        st.residual = norm_b > 0.0 ? sqrt(dot(p->q, p->q, n)) / norm_b : 0.0;
    }
#endif
    if (!converged && p->factored)
        converged = solve_band(p, r, xc, norm_b, tol, &st);
    if (!converged && !uses_hypre(p) && !p->factored) {
        precondition(p, r, p->z);
        memcpy(p->d, p->z, (size_t)n * sizeof(double));
        double rz = dot(r, p->z, n);
        for (int it = 1; it <= max_iter; ++it) {
            apply(p, L, p->d, p->q);
            double dq = dot(p->d, p->q, n);
            if (!(dq > 0.0))
                break;
            double alpha = rz / dq;
            BDL_PARALLEL_FOR(
                n >= BDL_GRID_PARALLEL_MIN, for (long i = 0; i < n; ++i) {
                    xc[i] += alpha * p->d[i];
                    r[i] -= alpha * p->q[i];
                });
            st.iterations = it;
            st.residual = sqrt(dot(r, r, n)) / norm_b;
            if (st.residual <= tol) {
                converged = 1;
                break;
            }
            precondition(p, r, p->z);
            double rz_new = dot(r, p->z, n);
            double beta = rz_new / rz;
            rz = rz_new;
            BDL_PARALLEL_FOR(n >= BDL_GRID_PARALLEL_MIN,
                             for (long i = 0; i < n; ++i) p->d[i] = p->z[i] + beta * p->d[i];);
        }
    }
    if (p->singular)
        remove_mean(xc, n);
    to_padded(p, xc, x);
    if (stats)
        *stats = st;
    return converged;
}
