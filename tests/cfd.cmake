# The grid's layout, and the gas solver's verification (docs/verification-gas.md): Poiseuille
# convergence order, hydrostatic rest, plug flow, volume conservation, the pressure solver, and
# the lid-driven cavity against Ghia et al. (1982).
bdl_add_test(test_grid SOURCES test_grid.c LABELS cfd)
bdl_add_test(test_poisson SOURCES test_poisson.c LABELS cfd)
bdl_add_test(test_poisson_direct SOURCES test_poisson_direct.c LABELS cfd)
bdl_add_test(test_gas SOURCES test_gas.c LABELS "cfd;verification")
bdl_add_test(test_cavity SOURCES test_cavity.c LABELS "cfd;verification" TIMEOUT 900)
bdl_add_test(test_drag SOURCES test_drag.c LABELS cfd)
bdl_add_test(test_rod_drag SOURCES test_rod_drag.c LABELS "cfd;rods")
bdl_add_test(test_rod_coupling SOURCES test_rod_coupling.c LABELS "cfd;rods")
bdl_add_test(test_coupling SOURCES test_coupling.c LABELS "cfd;verification" TIMEOUT 900)
bdl_add_test(test_fluidized SOURCES test_fluidized.c LABELS "cfd;verification" TIMEOUT 900)
bdl_add_test(test_packed_bed SOURCES test_packed_bed.c LABELS "cfd;verification" TIMEOUT 900)
# U_mf by a velocity sweep: nine stages each way (28 s; 107 s under the sanitizers). The sanitizer
# run (.ci/run) leaves it out: what it runs, the coupled step of a bed and the swept inlet, runs
# there in test_packed_bed, test_fluidized and cli_sweep.
bdl_add_test(test_umf SOURCES test_umf.c LABELS "cfd;verification;skip_sanitizers" TIMEOUT 1800)
bdl_add_test(test_settling SOURCES test_settling.c LABELS "cfd;verification" TIMEOUT 900)
# These check numerics, not threading (test_poisson compares 1 and 2 threads itself); one
# thread each keeps them from fighting over the cores when ctest runs them side by side.
set_tests_properties(test_gas test_cavity test_coupling test_fluidized test_packed_bed test_umf test_settling PROPERTIES ENVIRONMENT "OMP_NUM_THREADS=1")
bdl_add_test(test_container SOURCES test_container.c LABELS "cfd;verification")
bdl_add_test(test_stiff_drag SOURCES test_stiff_drag.c LABELS "cfd;verification;stability")
bdl_add_test(test_density_ratio SOURCES test_density_ratio.c LABELS "cfd;stability" TIMEOUT 600)
bdl_add_test(test_close_packing SOURCES test_close_packing.c LABELS "cfd;stability" TIMEOUT 600)
bdl_add_test(test_jet_outflow SOURCES test_jet_outflow.c LABELS "cfd;stability" TIMEOUT 600)
bdl_add_test(test_parcels SOURCES test_parcels.c LABELS "cfd;verification")
target_link_libraries(test_parcels PRIVATE OpenMP::OpenMP_C)
# hypre's pressure solver against bedlam's (builds with MPI only; tests/mpi.cmake).
if(BDL_WITH_MPI)
  bdl_add_test(test_hypre SOURCES test_hypre.c LABELS "cfd;mpi")
  add_dependencies(bdl_mpi_tests test_hypre)
endif()
