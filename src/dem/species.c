// bedlam — species: size distributions.
#include "dem/species.h"

#include "core/vec3.h"

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

void bdl_rod_mass_properties(double r, double shaft, double density, double *mass, double *axial,
                             double *transverse)
{
    const double L = shaft, r2 = r * r, r3 = r2 * r, r4 = r2 * r2, r5 = r4 * r;
    *mass = density * BDL_PI * (r2 * L + 4.0 / 3.0 * r3);
    *axial = BDL_PI * density * (0.5 * r4 * L + 8.0 / 15.0 * r5);
    *transverse = BDL_PI * density *
                  (r2 * L * L * L / 12.0 + 0.75 * r4 * L + r3 * L * L / 3.0 + 8.0 / 15.0 * r5);
}

double bdl_species_volume(const bdl_species_def *s, double d)
{
    if (s->shape != BDL_SHAPE_ROD)
        return BDL_PI / 6.0 * d * d * d;
    const double r = 0.5 * d;
    return BDL_PI * (r * r * (s->length - d) + 4.0 / 3.0 * r * r * r);
}

double bdl_species_max_extent(const bdl_species_def *s)
{
    const double d = bdl_species_max_diameter(s);
    return s->shape == BDL_SHAPE_ROD && s->length > d ? s->length : d;
}

double bdl_species_parcel_count(const bdl_species_def *s, double d)
{
    if (s->parcel_particles > 0.0)
        return s->parcel_particles;
    if (s->parcel_volume > 0.0)
        return s->parcel_volume / bdl_species_volume(s, d);
    return 1.0;
}

double bdl_species_parcel_volume(const bdl_species_def *s)
{
    if (s->parcel_volume > 0.0)
        return s->parcel_volume;
    return bdl_species_parcel_count(s, s->diameter) * bdl_species_volume(s, s->diameter);
}
