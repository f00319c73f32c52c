# Runs divided between MPI ranks (builds with -DBDL_WITH_MPI=ON): the same answer on 1, 2 and 4
# ranks (4 oversubscribed on two cores) as the scene whole on one.
if(BDL_WITH_MPI)
  add_executable(test_mpi_dem test_mpi_dem.c)
  target_compile_options(test_mpi_dem PRIVATE ${BDL_WARNINGS} ${BDL_SAN_FLAGS})
  target_link_libraries(test_mpi_dem PRIVATE bedlam_run)
  target_include_directories(test_mpi_dem PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  add_dependencies(bdl_mpi_tests test_mpi_dem)
  foreach(ranks 1 2 4)
    add_test(NAME test_mpi_dem_${ranks}
             COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${ranks} --oversubscribe
                     $<TARGET_FILE:test_mpi_dem>
             WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR})
    set_tests_properties(test_mpi_dem_${ranks} PROPERTIES LABELS "mpi" TIMEOUT 600
      ENVIRONMENT "OMP_NUM_THREADS=1;OMP_WAIT_POLICY=passive")
  endforeach()
endif()

# bedlam run under mpirun: a checkpoint written on 2 ranks resumed on 1, 2 and 4.
if(BDL_WITH_MPI)
  add_test(NAME test_mpi_resume
           COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/scripts/mpi_resume.sh ${MPIEXEC_EXECUTABLE}
                   $<TARGET_FILE:bedlam> ${CMAKE_CURRENT_SOURCE_DIR}/scenes/mpi_periodic_bed.ini
                   ${CMAKE_CURRENT_BINARY_DIR}/mpi_resume)
  set_tests_properties(test_mpi_resume PROPERTIES LABELS "mpi" TIMEOUT 600)
endif()
