# Parcels (MP-PIC, src/parcels/): model B's collisions — restitution, the pair forces against a
# brute-force sum and their momentum, a parcel settled on the floor, the step bound, one and two
# threads.
bdl_add_test(test_parcel_collisions SOURCES test_parcel_collisions.c LABELS "parcels;verification")
target_link_libraries(test_parcel_collisions PRIVATE OpenMP::OpenMP_C)
