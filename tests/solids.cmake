# Closures of solids phases on the grid (solids/): the kinetic theory against published values
# and the identities it must satisfy.
bdl_add_test(test_kinetic SOURCES test_kinetic.c LABELS solids)
