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

# tests/mpi/multihost_test.py: gpfd evolve across hosts made of network namespaces
# (scripts/multihost), label "multihost". They need root; elsewhere they report themselves
# skipped. scripts/test leaves them out; .ci/run runs them in a stage of their own.
# Multihost.<Name> runs the scenario <name>; the threads-only reference runs are fixtures.
function(gpfd_multihost_tests)
  find_package(Python3 REQUIRED COMPONENTS Interpreter)
  set(run ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/tests/mpi/multihost_test.py
      --gpfd $<TARGET_FILE:gpfd> --plugin $<TARGET_FILE:gpfd_test_plugin>
      --tmp ${CMAKE_BINARY_DIR}/test-tmp/multihost)
  set(references ReferenceCartpole ReferenceSleep)
  set(scenarios Identical WorkerKilled WorkerStopped LinkDown MasterKilled Slurm)
  foreach(name ${references} ${scenarios})
    # CamelCase test name -> kebab-case scenario: ReferenceCartpole -> reference-cartpole.
    string(REGEX REPLACE "([a-z0-9])([A-Z])" "\\1-\\2" scenario ${name})
    string(TOLOWER ${scenario} scenario)
    add_test(NAME Multihost.${name} COMMAND ${run} ${scenario})
    # One at a time: each makes its own namespaces, but they share two cores.
    set_tests_properties(Multihost.${name} PROPERTIES LABELS multihost SKIP_RETURN_CODE 77
                         TIMEOUT 150 RESOURCE_LOCK multihost)
  endforeach()
  set_tests_properties(Multihost.ReferenceCartpole PROPERTIES FIXTURES_SETUP multihost_cartpole)
  set_tests_properties(Multihost.Identical PROPERTIES FIXTURES_REQUIRED multihost_cartpole)
  set_tests_properties(Multihost.ReferenceSleep PROPERTIES FIXTURES_SETUP multihost_sleep)
  set_tests_properties(Multihost.WorkerKilled Multihost.WorkerStopped Multihost.LinkDown
                       Multihost.MasterKilled Multihost.Slurm
                       PROPERTIES FIXTURES_REQUIRED multihost_sleep)
endfunction()
