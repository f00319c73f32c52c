// bedlam — the pressure equation: div(c grad p) = f on the cell-centred grid, solved by
// conjugate gradients preconditioned with one symmetric multigrid V-cycle.
//
// c is given on the faces (c > 0). Each non-periodic side of the domain is either Neumann (the
// flux through it is already in f, so c there is ignored) or Dirichlet (p = p_side on the side,
// through a ghost value). Without a Dirichlet side the problem is singular: f is made
// consistent by removing its mean, and the solution has mean zero.
//
// The multigrid coarsens every axis whose cell count is even, by two, with coarse coefficients
// from aggregating the fine faces (half their sum across a coarsened axis, which is what
// re-discretising with the mean coefficient on the coarse cell gives), piecewise-constant
// transfers and damped Jacobi smoothing. Every loop is over a fixed partition of the cells and
// every sum is taken in a fixed order, so the result does not depend on the thread count.
#ifndef BDL_POISSON_H
#define BDL_POISSON_H

#include "cfd/grid.h"
#include "core/names.h"

/// Who solves it: bedlam's own multigrid-preconditioned CG, hypre's conjugate gradients
/// preconditioned by its structured-grid multigrid PFMG (cfd/poisson_hypre.h; builds with MPI
/// only), or the Cholesky factorisation of the banded matrix (cells numbered x fastest, so the
/// band is the cells of an x row, or of an x-y layer in three dimensions: for grids that are
/// narrow across x and y).
#define BDL_PRESSURE_SOLVERS(X)                                                                    \
    X(PRESSURE_MGPCG, "mgpcg", "multigrid-preconditioned CG")                                      \
    X(PRESSURE_HYPRE, "hypre", "hypre's PFMG-preconditioned CG")                                   \
    X(PRESSURE_DIRECT, "direct", "banded Cholesky")
BDL_CHOICES(bdl_pressure_solver, BDL_PRESSURE_SOLVERS);
extern const char *const bdl_pressure_solver_labels[];

/// 1 when this build has `solver` (hypre: built with -DBDL_WITH_MPI=ON).
int bdl_pressure_solver_available(bdl_pressure_solver solver);

typedef struct bdl_poisson bdl_poisson;

/// The largest half-bandwidth the direct solver takes, and the largest cost of its factorisation
/// (cells x band^2 multiply-adds, about a second a step at the most; the band's memory, cells x
/// (band + 1) doubles, stays below 0.1 GB at the largest band).
#define BDL_POISSON_DIRECT_BAND_MAX 1024
#define BDL_POISSON_DIRECT_COST_MAX 1e9

/// The half-bandwidth of the direct solver's matrix on a grid of n cells: the cells of an x row,
/// or of an x-y layer where there is more than one cell along z (1 for a single column). -1
/// where it cannot be banded: a periodic axis with more than one cell couples the first and last
/// cells.
int bdl_poisson_direct_band(const int n[3], const int periodic[3]);

/// The direct solver's factorisation: cells x band^2 multiply-adds (when it bands).
double bdl_poisson_direct_cost(const int n[3], const int periodic[3]);

typedef struct bdl_poisson_stats {
    int iterations;
    double residual; ///< final |f - A p|_2 / |f|_2 (0 when f = 0)
    double initial_residual;
} bdl_poisson_stats;

/// `dirichlet[2a + s]` says whether side s (0 low, 1 high) of axis a holds a fixed pressure.
/// NULL when out of memory.
bdl_poisson *bdl_poisson_create(const bdl_grid *g, const int dirichlet[6]);
/// The same with the solver chosen; NULL also when this build does not have it.
bdl_poisson *bdl_poisson_create_solver(const bdl_grid *g, const int dirichlet[6],
                                       bdl_pressure_solver solver);
void bdl_poisson_destroy(bdl_poisson *p);

/// Face coefficients c, one padded face array per axis (see grid.h), and the multigrid's coarse
/// levels built from them.
void bdl_poisson_set_coefficients(bdl_poisson *p, double *const c[3]);

/// Solves div(c grad x) = f, starting from the x given (padded cell arrays; only the cells are
/// read and written). p_side[2a + s] is the pressure of each Dirichlet side. Stops when the
/// relative residual is below `tol` or after `max_iter` iterations. Returns 1 when converged.
int bdl_poisson_solve(bdl_poisson *p, double *x, const double *f, const double p_side[6],
                      double tol, int max_iter, bdl_poisson_stats *stats);

/// r = f - div(c grad x) in the cells (padded arrays), with the same boundary treatment.
void bdl_poisson_residual(bdl_poisson *p, const double *x, const double *f, const double p_side[6],
                          double *r);

#endif
