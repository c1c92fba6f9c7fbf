# The Python extension module gpfd._core (python/): nanobind bindings over gpfd's static libraries,
# linked into one shared module, with type stubs. Built by `pip install .` (scikit-build-core, see
# pyproject.toml); a developer build passes -DGPFD_BUILD_PYTHON=ON
# -DPython_EXECUTABLE=<venv>/bin/python.
find_package(Python 3.10 REQUIRED COMPONENTS Interpreter Development.Module)
if(Python_VERSION VERSION_GREATER_EQUAL 3.12)
  # The stable ABI (STABLE_ABI below) needs the limited API's module (CMake 3.26 or later).
  find_package(Python REQUIRED COMPONENTS Interpreter Development.Module Development.SABIModule)
endif()
execute_process(
  COMMAND "${Python_EXECUTABLE}" -m nanobind --cmake_dir
  OUTPUT_STRIP_TRAILING_WHITESPACE
  OUTPUT_VARIABLE nanobind_ROOT
  RESULT_VARIABLE nanobind_found)
if(NOT nanobind_found EQUAL 0)
  message(FATAL_ERROR "gpfd: nanobind is not installed for ${Python_EXECUTABLE} "
                      "(pip install it, or build with `pip install .`)")
endif()
find_package(nanobind CONFIG REQUIRED)

file(GLOB GPFD_PYTHON_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/python/src/*.cpp)
# STABLE_ABI: built for CPython 3.12 or later, the module uses only the limited API (abi3), so that
# one wheel serves 3.12 and every later version; older Pythons get a module of their own version.
nanobind_add_module(_core STABLE_ABI NOMINSIZE NB_SUPPRESS_WARNINGS ${GPFD_PYTHON_SOURCES})
target_link_libraries(_core PRIVATE gpfd::core gpfd::fibers gpfd_version)
target_compile_options(_core PRIVATE ${GPFD_WARNINGS})
if(GPFD_JIT_AVAILABLE)
  # Debian's libasmjit.a is not built for shared objects: its symbols stay inside the module, and
  # its one PC-relative read of `stderr` goes to a module-local copy
  # (python/src/asmjit_in_shared_module.cpp).
  target_link_options(_core PRIVATE -Wl,--exclude-libs,libasmjit.a -Wl,--wrap=stderr)
endif()

# Type stubs (_core.pyi), written by nanobind's stubgen after each build of the module. stubgen
# imports it as gpfd._core, so the module is built into a package of its own (an empty
# __init__.py: no NumPy or Gymnasium needed) and the stubs name their types as users see them.
set(GPFD_STUBGEN_PATH ${CMAKE_CURRENT_BINARY_DIR}/python_stubgen)
file(CONFIGURE OUTPUT ${GPFD_STUBGEN_PATH}/gpfd/__init__.py CONTENT "")
set_target_properties(_core PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${GPFD_STUBGEN_PATH}/gpfd)
# python/stubgen_patterns.txt completes what the bindings' signatures leave open.
set(GPFD_STUBGEN_PATTERNS ${PROJECT_SOURCE_DIR}/python/stubgen_patterns.txt)
# Not in a sanitizer build (scripts/check-lockstep-memory), whose module imports only into a
# Python that has the sanitizer's runtime preloaded.
if(NOT GPFD_SANITIZE)
  nanobind_add_stub(_core_stub MODULE gpfd._core PYTHON_PATH ${GPFD_STUBGEN_PATH}
                    PATTERN_FILE ${GPFD_STUBGEN_PATTERNS} DEPENDS _core
                    OUTPUT ${GPFD_STUBGEN_PATH}/gpfd/_core.pyi)
endif()

# The wheel (pyproject.toml installs the component gpfd_wheel only, not cmake/install.cmake's C++
# package): the module with its stubs in gpfd/, and the command-line tool as the script `gpfd`.
if(SKBUILD)
  install(TARGETS _core LIBRARY DESTINATION gpfd COMPONENT gpfd_wheel)
  install(FILES ${GPFD_STUBGEN_PATH}/gpfd/_core.pyi DESTINATION gpfd COMPONENT gpfd_wheel)
  if(TARGET gpfd)
    install(TARGETS gpfd RUNTIME DESTINATION ${SKBUILD_SCRIPTS_DIR} COMPONENT gpfd_wheel)
  endif()
endif()
