# The Python extension module gpfd._core (python/): nanobind bindings over gpfd's static libraries, linked
# into one shared module. Built by `pip install .` (scikit-build-core, see pyproject.toml); a
# developer build passes -DGPFD_BUILD_PYTHON=ON -DPython_EXECUTABLE=<venv>/bin/python.
find_package(Python 3.10 REQUIRED COMPONENTS Interpreter Development.Module)
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
nanobind_add_module(_core NOMINSIZE NB_SUPPRESS_WARNINGS ${GPFD_PYTHON_SOURCES})
target_link_libraries(_core PRIVATE gpfd::core gpfd_version)
target_compile_options(_core PRIVATE ${GPFD_WARNINGS})
if(GPFD_JIT_AVAILABLE)
  # Debian's libasmjit.a is not built for shared objects: its symbols stay inside the module, and
  # its one PC-relative read of `stderr` goes to a module-local copy
  # (python/src/asmjit_in_shared_module.cpp).
  target_link_options(_core PRIVATE -Wl,--exclude-libs,libasmjit.a -Wl,--wrap=stderr)
endif()
if(SKBUILD)
  install(TARGETS _core LIBRARY DESTINATION gpfd)
endif()
