# MPI (Debian's MPICH) for distributed fitness evaluation: sets GPFD_MPI_AVAILABLE when found.
# Only the C API is used, so MPICH's deprecated C++ bindings are skipped.
set(MPI_CXX_SKIP_MPICXX ON)
find_package(MPI COMPONENTS CXX)
if(MPI_CXX_FOUND AND MPIEXEC_EXECUTABLE)
  set(GPFD_MPI_AVAILABLE ON)
  message(STATUS "gpfd: MPI evaluator on (MPI ${MPI_CXX_VERSION}), ${MPIEXEC_EXECUTABLE}")
else()
  set(GPFD_MPI_AVAILABLE OFF)
  message(STATUS "gpfd: MPI not found; gpfd evolve runs on threads only")
endif()

# tests/mpi/long_*.cpp become test_mpi_long (tests/CMakeLists.txt, label "long": in the full
# suite, not in the ASan preset). They run `gpfd evolve` under mpiexec and skip themselves when
# gpfd is built without MPI. Failures are injected only by the test worker
# gpfd_test_mpi_worker (tests/mpi/worker/), never by the released tool.
function(gpfd_mpi_tests)
  if(TARGET test_mpi_long)
    add_executable(gpfd_test_mpi_worker ${PROJECT_SOURCE_DIR}/tests/mpi/worker/test_worker.cpp)
    target_link_libraries(gpfd_test_mpi_worker PRIVATE gpfd::mpi gpfd_version)
    target_compile_options(gpfd_test_mpi_worker PRIVATE ${GPFD_WARNINGS})
    add_dependencies(test_mpi_long gpfd_test_mpi_worker)
    target_compile_definitions(test_mpi_long PRIVATE GPFD_MPIEXEC="${MPIEXEC_EXECUTABLE}"
                               GPFD_MPI_TEST_WORKER="$<TARGET_FILE:gpfd_test_mpi_worker>")
  endif()
endfunction()
