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
# gpfd is built without MPI.
function(gpfd_mpi_tests)
  if(TARGET test_mpi_long)
    target_compile_definitions(test_mpi_long PRIVATE GPFD_MPIEXEC="${MPIEXEC_EXECUTABLE}")
  endif()
endfunction()
