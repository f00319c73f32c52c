// The damping that realises a restitution: the exact solution with the no-pull clamp against the
// closed forms, the numbers docs/theory-dem.md tabulates.
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "core/vec3.h"
#include "dem/material.h"

/// The table's pair parameters of one species with itself, for restitution e.
static bdl_contact_params pair_of(bdl_normal_law law, double e)
{
    const bdl_material m = {.youngs_modulus = 1e7,
                            .poisson_ratio = 0.3,
                            .stiffness = 1e4,
                            .tangential_stiffness = -1.0,
                            .restitution = e};
    const bdl_contact_table_def def = {
        .law = law, .damping = BDL_DAMPING_EXACT, .species_count = 1, .species = &m};
    bdl_contact_params cp;
    bdl_contact_table_build(&def, &cp, NULL);
    return cp;
}

int main(void)
{
    // e configured, c exact (Hertz), e realised by the closed forms: docs/theory-dem.md.
    static const double table[][3] = {
        {0.01, 10.749, 0.173}, {0.10, 2.780, 0.253},  {0.30, 1.112, 0.397},   {0.50, 0.571, 0.550},
        {0.70, 0.273, 0.718},  {0.90, 0.0766, 0.902}, {0.99, 0.00717, 0.990},
    };
    for (int k = 0; k < 7; ++k) {
        const double e = table[k][0];
        const bdl_contact_params hertz = pair_of(BDL_LAW_HERTZ, e),
                                 linear = pair_of(BDL_LAW_LINEAR, e);
        const double closed_zeta = bdl_linear_damping_ratio(e);
        const double closed_c = bdl_hertz_damping_closed_form(e);
        const double realised_linear = bdl_restitution_of(0, closed_zeta);
        const double realised_hertz = bdl_restitution_of(1, closed_c);
        printf("e %.2f: c exact %.4g (table %.4g), zeta exact %.4g; closed forms realise %.3f "
               "(linear) and %.3f (Hertz); duration ratios %.3f and %.3f\n",
               e, hertz.damping, table[k][1], linear.damping, realised_linear, realised_hertz,
               linear.duration_ratio, hertz.duration_ratio);
        // The exact damping realises e, to the search's tolerance.
        CHECK_CLOSE(bdl_restitution_of(1, hertz.damping), e, 1e-6);
        CHECK_CLOSE(bdl_restitution_of(0, linear.damping), e, 1e-6);
        CHECK_CLOSE(hertz.damping, table[k][1], 0.002); // the table keeps 3-4 digits
        CHECK_CLOSE(realised_hertz, table[k][2], 0.004);
        CHECK_CLOSE(realised_linear, table[k][2], 0.004);
        // The closed forms, as written: zeta = -ln e / sqrt(pi^2 + ln^2 e), c = sqrt(5) zeta.
        CHECK_CLOSE(closed_zeta, -log(e) / sqrt(BDL_PI * BDL_PI + log(e) * log(e)), 1e-14);
        CHECK_CLOSE(closed_c, sqrt(5.0) * closed_zeta, 1e-14);
        // Damping shortens a clamped contact: the force ends before the elastic half period.
        CHECK(hertz.duration_ratio > 0.0 && hertz.duration_ratio <= 1.0 + 1e-12);
        CHECK(bdl_contact_duration_ratio(1, hertz.damping) == hertz.duration_ratio);
    }
    return bdl_test_summary("test_material");
}
