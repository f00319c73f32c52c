// bedlam — the pressure equation handed to hypre (builds with MPI only; cfd/poisson.h chooses).
//
// The matrix is poisson.c's M = -div(c grad) row by row: its diagonal and its couplings K to the
// six neighbours, set through hypre's structured-grid interface (Struct) as a seven-point
// stencil; periodic axes are hypre's periodic grid. Solved by hypre's conjugate gradients with
// one V-cycle of its PFMG multigrid as the preconditioner, stopping on the relative residual in
// the 2-norm, as bedlam's own solver does.
#ifndef BDL_POISSON_HYPRE_H
#define BDL_POISSON_HYPRE_H

typedef struct bdl_hypre_poisson bdl_hypre_poisson;

/// A solver for the grid of n cells (periodic[a]: axis a wraps; an axis of one cell never does).
/// `singular`: no side holds the pressure, so M has the constants as its null space. hypre's
/// multigrid does not keep to the consistent part, so the first cell's row is pinned (its
/// diagonal doubled): with a right-hand side of zero mean that system's solution is M's, shifted
/// to make the first cell's value zero (the caller removes the mean). NULL when out of memory.
bdl_hypre_poisson *bdl_hypre_poisson_create(const int n[3], const int periodic[3], int singular);
void bdl_hypre_poisson_destroy(bdl_hypre_poisson *h);

/// The rows: `diag` per cell and the couplings K[a] on the faces (compact arrays in poisson.c's
/// layout: cells x fastest, n[a] + 1 faces along a). A face on a side that is not periodic
/// couples to nothing (its Dirichlet part is in diag). Sets the preconditioner up.
void bdl_hypre_poisson_set(bdl_hypre_poisson *h, const double *diag, double *const K[3]);

/// Solves M x = b (compact arrays) from the x given, to the relative residual `tol` in at most
/// `max_iter` iterations. Returns 1 when converged; `iterations` and `residual` (final relative
/// residual) are filled.
int bdl_hypre_poisson_solve(bdl_hypre_poisson *h, const double *b, double *x, double tol,
                            int max_iter, int *iterations, double *residual);

#endif
