# Ahead-of-time reference functions for `gpfd bench jit` (docs/jit.md): the generator
# tools/aot/gen_aot writes C++ for the Figure 3 trees of the default seed, which is compiled with
# the project's normal flags into gpfd_jit_aot and linked into the gpfd executable only.
add_executable(gpfd_gen_aot tools/aot/gen_aot.cpp)
target_link_libraries(gpfd_gen_aot PRIVATE gpfd::jit)
target_compile_options(gpfd_gen_aot PRIVATE ${GPFD_WARNINGS})

set(GPFD_AOT_SOURCE ${CMAKE_BINARY_DIR}/generated/jit_aot_functions.cpp)
add_custom_command(
  OUTPUT ${GPFD_AOT_SOURCE}
  COMMAND ${CMAKE_COMMAND} -E make_directory ${CMAKE_BINARY_DIR}/generated
  COMMAND gpfd_gen_aot ${GPFD_AOT_SOURCE}
  DEPENDS gpfd_gen_aot
  COMMENT "Generating the AOT reference functions of gpfd bench jit"
  VERBATIM)
add_library(gpfd_jit_aot STATIC ${GPFD_AOT_SOURCE})
target_link_libraries(gpfd_jit_aot PUBLIC gpfd::jit)
target_link_libraries(gpfd PRIVATE gpfd_jit_aot)
