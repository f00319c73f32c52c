# Physics verification of the DEM solver (docs/verification-dem.md): restitution and its
# convergence with dt, Hertz contact duration, sliding to rolling, conservation in collisions,
# static overlaps of a column, and the oblique impact (tangential rebound, energy through the
# guards, Maw et al.'s theory). Each prints its table to stdout.
bdl_add_test(test_material SOURCES test_material.c LABELS dem)
bdl_add_test(test_rods SOURCES test_rods.c LABELS dem TIMEOUT 300)
bdl_add_test(test_rod_bed SOURCES test_rod_bed.c LABELS "dem;slow" TIMEOUT 7200)
target_link_libraries(test_rod_bed PRIVATE OpenMP::OpenMP_C)
target_link_libraries(test_rods PRIVATE OpenMP::OpenMP_C)
bdl_add_test(test_bounce SOURCES test_bounce.c LABELS dem verification TIMEOUT 600)
target_link_libraries(test_bounce PRIVATE OpenMP::OpenMP_C)
bdl_add_test(test_hertz_duration SOURCES test_hertz_duration.c LABELS dem verification TIMEOUT 300)
target_link_libraries(test_hertz_duration PRIVATE OpenMP::OpenMP_C)
bdl_add_test(test_slide_roll SOURCES test_slide_roll.c LABELS dem verification TIMEOUT 300)
target_link_libraries(test_slide_roll PRIVATE OpenMP::OpenMP_C)
bdl_add_test(test_collision SOURCES test_collision.c LABELS dem verification TIMEOUT 900)
target_link_libraries(test_collision PRIVATE OpenMP::OpenMP_C)
bdl_add_test(test_column SOURCES test_column.c LABELS dem verification TIMEOUT 300)
target_link_libraries(test_column PRIVATE OpenMP::OpenMP_C)
bdl_add_test(test_oblique SOURCES test_oblique.c LABELS dem verification TIMEOUT 300)
bdl_add_test(test_voidage SOURCES test_voidage.c)
bdl_add_test(test_restitution_limits SOURCES test_restitution_limits.c LABELS "dem;stability" TIMEOUT 600)
bdl_add_test(test_stiff_contacts SOURCES test_stiff_contacts.c LABELS "dem;stability" TIMEOUT 600)
bdl_add_test(test_size_ratio SOURCES test_size_ratio.c LABELS "dem;stability" TIMEOUT 600)
bdl_add_test(test_violent_shaking SOURCES test_violent_shaking.c LABELS "dem;stability" TIMEOUT 600)
bdl_add_test(test_particles SOURCES test_particles.c LABELS dem)
# Rods: the closest points of two segments against a brute force; mass properties, free and
# torqued rotation of rigid bodies (docs/theory-rods.md).
bdl_add_test(test_capsule SOURCES test_capsule.c LABELS dem)
bdl_add_test(test_rigid SOURCES test_rigid.c LABELS dem)
# Mesh walls: face, edge and vertex contacts against the analytic plane, line and point; rolling
# across triangles; a bed in a box of 12 triangles; the STL and OBJ reader on good and bad files.
bdl_add_test(test_mesh SOURCES test_mesh.c LABELS dem)
# A rotating drum: the dynamic angle of repose rises with friction and rate; no slip at the wall.
bdl_add_test(test_drum SOURCES test_drum.c LABELS "dem;slow" TIMEOUT 1800)
# Janssen's silo: the floor's load saturates with the fill height, as Janssen's formula says
# for the K and the wall friction the beds mobilise.
bdl_add_test(test_janssen SOURCES test_janssen.c LABELS "dem;slow" TIMEOUT 1800)
# The shear cell's boundaries: Lees-Edwards images (separations, velocities, lists against a brute
# force, the shear profile through the faces, a collision across a face) and a repeating plate.
bdl_add_test(test_shear_cell SOURCES test_shear_cell.c LABELS dem TIMEOUT 300)
