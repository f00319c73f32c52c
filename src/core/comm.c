#include "core/comm.h"

#if defined(BDL_WITH_MPI)
#include <HYPRE_utilities.h>
#include <mpi.h>
#include <stdio.h>
#include <stdlib.h>

static int started; ///< MPI_Init was called here (not before, by a test's harness)

int bdl_comm_init(int *argc, char ***argv)
{
    int already = 0;
    MPI_Initialized(&already);
    if (!already) {
        // The solver steps (and calls MPI) on a thread of its own, one thread at a time.
        int provided = 0;
        if (MPI_Init_thread(argc, argv, MPI_THREAD_SERIALIZED, &provided) != MPI_SUCCESS)
            return -1;
        if (provided < MPI_THREAD_SERIALIZED) {
            MPI_Finalize();
            return -1;
        }
        started = 1;
    }
    HYPRE_Init();
    return 0;
}

void bdl_comm_finalize(void)
{
    int up = 0, down = 0;
    MPI_Initialized(&up);
    MPI_Finalized(&down);
    if (!up || down)
        return;
    HYPRE_Finalize();
    if (started)
        MPI_Finalize();
    started = 0;
}

static int running(void)
{
    int up = 0, down = 0;
    MPI_Initialized(&up);
    MPI_Finalized(&down);
    return up && !down;
}

int bdl_comm_built(void) { return 1; }

int bdl_comm_rank(void)
{
    int rank = 0;
    if (running())
        MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    return rank;
}

int bdl_comm_size(void)
{
    int size = 1;
    if (running())
        MPI_Comm_size(MPI_COMM_WORLD, &size);
    return size;
}

double bdl_comm_max(double value)
{
    double out = value;
    if (running())
        MPI_Allreduce(&value, &out, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return out;
}

double bdl_comm_min(double value)
{
    double out = value;
    if (running())
        MPI_Allreduce(&value, &out, 1, MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD);
    return out;
}

void bdl_comm_sum(double *values, int count)
{
    const int size = bdl_comm_size();
    if (size == 1 || count <= 0)
        return;
    // Gathered and added in rank order on every rank: MPI_Allreduce may add in any order.
    double *all = malloc((size_t)size * (size_t)count * sizeof *all);
    if (!all)
        bdl_comm_abort("out of memory summing over the ranks");
    MPI_Allgather(values, count, MPI_DOUBLE, all, count, MPI_DOUBLE, MPI_COMM_WORLD);
    for (int c = 0; c < count; ++c) {
        double sum = 0.0;
        for (int r = 0; r < size; ++r)
            sum += all[(size_t)r * (size_t)count + (size_t)c];
        values[c] = sum;
    }
    free(all);
}

bdl_exact_sum bdl_comm_sum_exact(bdl_exact_sum value)
{
    const int size = bdl_comm_size();
    if (size == 1)
        return value;
    bdl_exact_sum *all = malloc((size_t)size * sizeof *all);
    if (!all)
        bdl_comm_abort("out of memory summing over the ranks");
    MPI_Allgather(&value, (int)sizeof value, MPI_BYTE, all, (int)sizeof value, MPI_BYTE,
                  MPI_COMM_WORLD);
    bdl_exact_sum sum = 0;
    for (int r = 0; r < size; ++r)
        sum += all[r];
    free(all);
    return sum;
}

void bdl_comm_broadcast(void *data, size_t bytes, int root)
{
    if (!running() || bdl_comm_size() == 1)
        return;
    char *at = data;
    while (bytes > 0) { // MPI counts are ints
        const int chunk = bytes > (1u << 30) ? 1 << 30 : (int)bytes;
        MPI_Bcast(at, chunk, MPI_BYTE, root, MPI_COMM_WORLD);
        at += chunk;
        bytes -= (size_t)chunk;
    }
}

void bdl_comm_barrier(void)
{
    if (running())
        MPI_Barrier(MPI_COMM_WORLD);
}

_Noreturn void bdl_comm_abort(const char *why)
{
    fprintf(stderr, "error: rank %d of %d: %s; the job is stopped\n", bdl_comm_rank(),
            bdl_comm_size(), why);
    fflush(stderr);
    if (running())
        MPI_Abort(MPI_COMM_WORLD, 1);
    exit(1);
}

int bdl_comm_broadcast_int(int value, int root)
{
    if (running() && bdl_comm_size() > 1)
        MPI_Bcast(&value, 1, MPI_INT, root, MPI_COMM_WORLD);
    return value;
}

#else

#include <stdio.h>
#include <stdlib.h>

int bdl_comm_init(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    return 0;
}

void bdl_comm_finalize(void) {}

int bdl_comm_built(void) { return 0; }

int bdl_comm_rank(void) { return 0; }

int bdl_comm_size(void) { return 1; }

double bdl_comm_max(double value) { return value; }

double bdl_comm_min(double value) { return value; }

void bdl_comm_sum(double *values, int count)
{
    (void)values;
    (void)count;
}

void bdl_comm_broadcast(void *data, size_t bytes, int root)
{
    (void)data;
    (void)bytes;
    (void)root;
}

void bdl_comm_barrier(void) {}

bdl_exact_sum bdl_comm_sum_exact(bdl_exact_sum value) { return value; }

_Noreturn void bdl_comm_abort(const char *why)
{
    fprintf(stderr, "error: %s\n", why);
    exit(1);
}

int bdl_comm_broadcast_int(int value, int root)
{
    (void)root;
    return value;
}

#endif
