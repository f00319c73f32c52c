// bedlam — per-species time series (species.csv) and contact files (contacts/) of a run.
//
// species.csv (scenes of two or more species), one row per diagnostics row: for each species its
// particle count, mean and highest centre height above the domain's floor (along gravity) and
// mean coordination; with exactly two species also Lacey's mixing index of the first species on
// the [output] mixing_cells grid, and on its columns (horizontal mixing) and its layers
// (vertical mixing) alone.
//
// contacts/contacts_NNNNNN.csv: every contact at that instant — particle ids, species, centres,
// overlap and normal force; a wall contact has j = -1 - wall index and the contact point as the
// second position. `bedlam analyze networks` reads it.
#ifndef BDL_GRANULAR_OUT_H
#define BDL_GRANULAR_OUT_H

#include "world/world.h"

#define BDL_SPECIES_COLUMNS_MAX (1 + 4 * BDL_MAX_SPECIES + 3)
#define BDL_SPECIES_COLUMN_LEN  (BDL_NAME_LEN + 24)

/// Column names of species.csv into names[]; returns their count (0: fewer than two species).
int bdl_species_columns(const bdl_world *w, char names[][BDL_SPECIES_COLUMN_LEN]);

/// One row of species.csv for the current state.
void bdl_species_row(const bdl_world *w, double *row);

/// profile.csv (with a gas): the solids fraction 1 - voidage of each gas cell layer along
/// gravity, from the floor up; columns "time" and "phi_at_H" with H the layer centre's height [m];
/// with several solids phases then each phase's layer fractions, "phase_NAME_at_H". Returns the
/// column count into names (NULL: just the count).
int bdl_profile_columns(const bdl_world *w, char (*names)[BDL_SPECIES_COLUMN_LEN]);
void bdl_profile_row(const bdl_world *w, double *row);

/// Writes the contact file (atomically).
bdl_result bdl_contacts_write(const bdl_world *w, const char *path);

#endif
