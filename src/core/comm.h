// bedlam — the processes of a run: MPI ranks, or one process.
//
// Built with -DBDL_WITH_MPI=ON (OpenMPI, and hypre for the pressure equation) a run may be
// started as `mpirun -np N bedlam ...`: every rank runs the same program on its part of the
// problem. Built without it, every function here is that of a single rank and nothing links MPI.
// bdl_comm_init must come first in main and bdl_comm_finalize last; between them the library
// functions below are collective where they say so (every rank calls them, in the same order).
#ifndef BDL_COMM_H
#define BDL_COMM_H

#include <stddef.h>

#include "core/exact_sum.h"

/// Starts MPI (and hypre) when built with it; a no-op otherwise. Returns 0, or -1 when MPI could
/// not be started.
int bdl_comm_init(int *argc, char ***argv);
/// Stops hypre and MPI (a no-op without them, or when bdl_comm_init was not called).
void bdl_comm_finalize(void);

/// 1 when built with MPI.
int bdl_comm_built(void);
/// This process's rank and the number of ranks (0 and 1 without MPI, or before bdl_comm_init).
int bdl_comm_rank(void);
int bdl_comm_size(void);

/// Collective: the largest (smallest) of every rank's value.
double bdl_comm_max(double value);
double bdl_comm_min(double value);
/// Collective: the sum of every rank's `count` values, in place (rank order: the same bits on
/// every rank, for a given rank count).
void bdl_comm_sum(double *values, int count);
/// Collective: every rank's exact sum added (exactly: the same bits for any rank count).
bdl_exact_sum bdl_comm_sum_exact(bdl_exact_sum value);
/// Collective: `bytes` of `data` from rank `root` to every rank.
void bdl_comm_broadcast(void *data, size_t bytes, int root);
/// Ends every rank of the job at once (MPI_Abort), after printing `why` with this rank's number
/// to stderr: for a failure on one rank in the middle of an exchange the others wait in. Without
/// MPI it exits the process (code 1).
_Noreturn void bdl_comm_abort(const char *why);

/// Collective: rank `root`'s value on every rank.
int bdl_comm_broadcast_int(int value, int root);
/// Collective: stops every rank until all have reached it.
void bdl_comm_barrier(void);

#endif
