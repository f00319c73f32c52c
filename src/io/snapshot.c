// bedlam — storage of snapshots.
#include "io/snapshot.h"

#include <stdlib.h>
#include <string.h>

static int grow(void **array, long count, size_t size)
{
    void *a = realloc(*array, (size_t)count * size);
    if (!a)
        return 0;
    *array = a;
    return 1;
}

int bdl_snapshot_reserve(bdl_snapshot *s, long n)
{
    if (n <= s->capacity)
        return 1;
    long cap = n + n / 4 + 64;
    if (!grow((void **)&s->pos, cap, 3 * sizeof(float)) ||
        !grow((void **)&s->vel, cap, 3 * sizeof(float)) ||
        !grow((void **)&s->radius, cap, sizeof(float)) ||
        !grow((void **)&s->coordination, cap, sizeof(uint8_t)) ||
        !grow((void **)&s->species, cap, sizeof(int32_t)) ||
        !grow((void **)&s->id, cap, sizeof(uint32_t)))
        return 0;
    s->capacity = cap;
    return 1;
}

int bdl_snapshot_reserve_axis(bdl_snapshot *s, long n)
{
    if (n <= s->axis_capacity)
        return 1;
    long cap = n + n / 4 + 64;
    if (!grow((void **)&s->axis, cap, 3 * sizeof(float)))
        return 0;
    s->axis_capacity = cap;
    return 1;
}

int bdl_snapshot_reserve_slice(bdl_snapshot *s, long cells)
{
    if (cells <= s->slice_capacity)
        return 1;
    if (!grow((void **)&s->slice, cells, sizeof(float)))
        return 0;
    s->slice_capacity = cells;
    return 1;
}

int bdl_snapshot_reserve_voidage(bdl_snapshot *s, long cells)
{
    if (cells <= s->voidage_capacity)
        return 1;
    if (!grow((void **)&s->voidage, cells, sizeof(float)))
        return 0;
    s->voidage_capacity = cells;
    return 1;
}

void bdl_snapshot_free(bdl_snapshot *s)
{
    free(s->voidage);
    free(s->slice);
    free(s->axis);
    free(s->pos);
    free(s->vel);
    free(s->radius);
    free(s->coordination);
    free(s->species);
    free(s->id);
    memset(s, 0, sizeof *s);
}
