#include "cfd/poisson_hypre.h"

#include <HYPRE_struct_ls.h>
#include <mpi.h>
#include <stdlib.h>

#define STENCIL 7

struct bdl_hypre_poisson {
    int n[3];
    int periodic[3];
    int singular; ///< pin the first cell (bdl_hypre_poisson_create)
    long cells;
    HYPRE_StructGrid grid;
    HYPRE_StructStencil stencil;
    HYPRE_StructMatrix matrix;
    HYPRE_StructVector b, x;
    HYPRE_StructSolver pcg, pfmg; ///< NULL until the first bdl_hypre_poisson_set
    double *values;               ///< STENCIL x cells, for the matrix's rows
};

static const int offsets[STENCIL][3] = {{0, 0, 0}, {-1, 0, 0}, {1, 0, 0}, {0, -1, 0},
                                        {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};

bdl_hypre_poisson *bdl_hypre_poisson_create(const int n[3], const int periodic[3], int singular)
{
    bdl_hypre_poisson *h = calloc(1, sizeof *h);
    if (!h)
        return NULL;
    h->singular = singular;
    HYPRE_Int lower[3] = {0, 0, 0}, upper[3], period[3];
    for (int a = 0; a < 3; ++a) {
        h->n[a] = n[a];
        h->periodic[a] = periodic[a] && n[a] > 1;
        upper[a] = n[a] - 1;
        period[a] = h->periodic[a] ? n[a] : 0;
    }
    h->cells = (long)n[0] * n[1] * n[2];
    h->values = malloc((size_t)h->cells * STENCIL * sizeof *h->values);
    if (!h->values) {
        free(h);
        return NULL;
    }
    // One box, this process's: the grid is not yet divided between ranks.
    HYPRE_StructGridCreate(MPI_COMM_SELF, 3, &h->grid);
    HYPRE_StructGridSetExtents(h->grid, lower, upper);
    HYPRE_StructGridSetPeriodic(h->grid, period);
    HYPRE_StructGridAssemble(h->grid);
    HYPRE_StructStencilCreate(3, STENCIL, &h->stencil);
    for (int e = 0; e < STENCIL; ++e) {
        HYPRE_Int off[3] = {offsets[e][0], offsets[e][1], offsets[e][2]};
        HYPRE_StructStencilSetElement(h->stencil, e, off);
    }
    HYPRE_StructMatrixCreate(MPI_COMM_SELF, h->grid, h->stencil, &h->matrix);
    HYPRE_StructMatrixInitialize(h->matrix);
    HYPRE_StructVectorCreate(MPI_COMM_SELF, h->grid, &h->b);
    HYPRE_StructVectorCreate(MPI_COMM_SELF, h->grid, &h->x);
    HYPRE_StructVectorInitialize(h->b);
    HYPRE_StructVectorInitialize(h->x);
    return h;
}

static void destroy_solver(bdl_hypre_poisson *h)
{
    if (h->pcg)
        HYPRE_StructPCGDestroy(h->pcg);
    if (h->pfmg)
        HYPRE_StructPFMGDestroy(h->pfmg);
    h->pcg = h->pfmg = NULL;
}

void bdl_hypre_poisson_destroy(bdl_hypre_poisson *h)
{
    if (!h)
        return;
    destroy_solver(h);
    HYPRE_StructVectorDestroy(h->x);
    HYPRE_StructVectorDestroy(h->b);
    HYPRE_StructMatrixDestroy(h->matrix);
    HYPRE_StructStencilDestroy(h->stencil);
    HYPRE_StructGridDestroy(h->grid);
    free(h->values);
    free(h);
}

static long face_index(const bdl_hypre_poisson *h, int a, int i, int j, int k)
{
    const long f0 = h->n[0] + (a == 0), f1 = h->n[1] + (a == 1);
    return ((long)k * f1 + j) * f0 + i;
}

void bdl_hypre_poisson_set(bdl_hypre_poisson *h, const double *diag, double *const K[3])
{
    long c = 0;
    for (int k = 0; k < h->n[2]; ++k)
        for (int j = 0; j < h->n[1]; ++j)
            for (int i = 0; i < h->n[0]; ++i, ++c) {
                double *row = h->values + c * STENCIL;
                const int at[3] = {i, j, k};
                row[0] = diag[c];
                for (int a = 0; a < 3; ++a) {
                    int hi[3] = {i, j, k};
                    hi[a] += 1;
                    const int wraps = h->periodic[a];
                    const double lo_k = K[a][face_index(h, a, i, j, k)],
                                 hi_k = K[a][face_index(h, a, hi[0], hi[1], hi[2])];
                    row[1 + 2 * a] = at[a] > 0 || wraps ? -lo_k : 0.0;
                    row[2 + 2 * a] = at[a] < h->n[a] - 1 || wraps ? -hi_k : 0.0;
                }
            }
    if (h->singular)
        h->values[0] *= 2.0;
    HYPRE_Int lower[3] = {0, 0, 0}, upper[3] = {h->n[0] - 1, h->n[1] - 1, h->n[2] - 1};
    HYPRE_Int entries[STENCIL] = {0, 1, 2, 3, 4, 5, 6};
    HYPRE_StructMatrixSetBoxValues(h->matrix, lower, upper, STENCIL, entries, h->values);
    HYPRE_StructMatrixAssemble(h->matrix);
    // The preconditioner is built from the matrix: a new one for new coefficients.
    destroy_solver(h);
    HYPRE_StructPCGCreate(MPI_COMM_SELF, &h->pcg);
    HYPRE_StructPCGSetTwoNorm(h->pcg, 1);
    HYPRE_StructPFMGCreate(MPI_COMM_SELF, &h->pfmg);
    HYPRE_StructPFMGSetMaxIter(h->pfmg, 1);
    HYPRE_StructPFMGSetTol(h->pfmg, 0.0);
    HYPRE_StructPFMGSetZeroGuess(h->pfmg);
    HYPRE_StructPFMGSetRelaxType(h->pfmg, 1); // weighted Jacobi: symmetric, as CG needs
    HYPRE_StructPFMGSetNumPreRelax(h->pfmg, 2);
    HYPRE_StructPFMGSetNumPostRelax(h->pfmg, 2);
    HYPRE_StructPCGSetPrecond(h->pcg, HYPRE_StructPFMGSolve, HYPRE_StructPFMGSetup, h->pfmg);
    HYPRE_StructPCGSetup(h->pcg, h->matrix, h->b, h->x);
}

int bdl_hypre_poisson_solve(bdl_hypre_poisson *h, const double *b, double *x, double tol,
                            int max_iter, int *iterations, double *residual)
{
    HYPRE_Int lower[3] = {0, 0, 0}, upper[3] = {h->n[0] - 1, h->n[1] - 1, h->n[2] - 1};
    HYPRE_StructVectorSetBoxValues(h->b, lower, upper, (double *)b);
    HYPRE_StructVectorSetBoxValues(h->x, lower, upper, x);
    HYPRE_StructVectorAssemble(h->b);
    HYPRE_StructVectorAssemble(h->x);
    HYPRE_StructPCGSetTol(h->pcg, tol);
    HYPRE_StructPCGSetMaxIter(h->pcg, max_iter);
    HYPRE_StructPCGSolve(h->pcg, h->matrix, h->b, h->x);
    HYPRE_ClearAllErrors(); // not converging is reported below, not through hypre's flag
    HYPRE_StructVectorGetBoxValues(h->x, lower, upper, x);
    HYPRE_Int its = 0;
    HYPRE_Real res = 0.0;
    HYPRE_StructPCGGetNumIterations(h->pcg, &its);
    HYPRE_StructPCGGetFinalRelativeResidualNorm(h->pcg, &res);
    *iterations = (int)its;
    *residual = res;
    return res <= tol;
}
