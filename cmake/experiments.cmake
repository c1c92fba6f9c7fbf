# Ahead-of-time reference functions for `gpfd bench jit` (docs/jit.md): the generator
# tools/aot/gen_aot writes C++ for the Figure 3 trees of the default seed, which is compiled with
# the project's normal flags into gpfd_jit_aot, part of the experiments layer. The generator
# compiles the trees' source itself: it runs before the experiments library exists.
add_executable(gpfd_gen_aot tools/aot/gen_aot.cpp src/experiments/bench_functions.cpp)
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
# The experiments layer above the service layer (docs/architecture.md): reproduce, fitness noise,
# the toy task, Figure 3 and the JIT benchmark. Built with the tool, outside gpfd::core.
gpfd_module(experiments DEPS gpfd::service)
target_link_libraries(gpfd_experiments PRIVATE gpfd_jit_aot)
target_link_libraries(gpfd PRIVATE gpfd::experiments)
