// bedlam — species: size distributions.
#include "dem/species.h"

BDL_CHOICE_WORDS(bdl_shape, BDL_SHAPES);
BDL_CHOICE_WORDS(bdl_size_dist, BDL_SIZE_DISTS);

double bdl_species_max_diameter(const bdl_species_def *s)
{
    return s->size_dist == BDL_SIZE_SINGLE ? s->diameter : s->diameter_max;
}

double bdl_species_min_diameter(const bdl_species_def *s)
{
    return s->size_dist == BDL_SIZE_SINGLE ? s->diameter : s->diameter_min;
}

double bdl_species_draw_diameter(const bdl_species_def *s, bdl_rng *rng)
{
    switch (s->size_dist) {
    case BDL_SIZE_UNIFORM:
        return bdl_rng_range(rng, s->diameter_min, s->diameter_max);
    case BDL_SIZE_NORMAL:
        for (int tries = 0; tries < 1000; ++tries) {
            double d = s->diameter + s->diameter_std * bdl_rng_normal(rng);
            if (d >= s->diameter_min && d <= s->diameter_max)
                return d;
        }
        return s->diameter;
    default:
        return s->diameter;
    }
}
