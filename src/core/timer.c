#define _POSIX_C_SOURCE 200809L
#include "core/timer.h"

#include <time.h>

double bdl_wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void bdl_sleep(double seconds)
{
    if (!(seconds > 0.0))
        return;
    struct timespec ts = {(time_t)seconds, (long)((seconds - (double)(time_t)seconds) * 1e9)};
    nanosleep(&ts, NULL);
}
