# Closures of solids phases on the grid (solids/): the kinetic theory against published values
# and the identities it must satisfy.
bdl_add_test(test_kinetic SOURCES test_kinetic.c LABELS solids)
# The two-fluid model: dilute slip, Ergun, U_mf, a fluidised column's momentum, a bubbling bed.
bdl_add_test(test_tfm SOURCES test_tfm.c LABELS solids)
# Its verification cases (`bedlam verify tfm_cooling tfm_settling`): Haff's law and Kynch's
# settling with their orders, the sediment packing without overshoot.
bdl_add_test(test_tfm_verify SOURCES test_tfm_verify.c LABELS "solids;verification;stability")
# Goldschmidt's bubbling bed for 10 s at two velocities, with and without rotation, and on three
# grids (~20 min).
bdl_add_test(test_tfm_goldschmidt SOURCES test_tfm_goldschmidt.c LABELS "solids;slow" TIMEOUT 3600)
# Several phases: the drag between them (closed form, exact relaxation), a binary bubbling bed.
bdl_add_test(test_tfm_mixture SOURCES test_tfm_mixture.c LABELS solids)
bdl_add_test(test_tfm_energy SOURCES test_tfm_energy.c LABELS "solids;verification")
