# gpfd_module(NAME DEPS dep...) defines the library gpfd_NAME (alias gpfd::NAME) from
# src/NAME/*.cpp with the public headers in include/gpfd/NAME. A module without sources yet is an
# interface library, so that every module name exists from the start.
function(gpfd_module name)
  cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/${name}/*.cpp)
  if(sources)
    add_library(gpfd_${name} STATIC ${sources})
    target_include_directories(gpfd_${name} PUBLIC ${PROJECT_SOURCE_DIR}/include)
    target_link_libraries(gpfd_${name} PUBLIC ${ARG_DEPS})
    target_compile_options(gpfd_${name} PRIVATE ${GPFD_WARNINGS})
  else()
    add_library(gpfd_${name} INTERFACE)
    target_include_directories(gpfd_${name} INTERFACE ${PROJECT_SOURCE_DIR}/include)
    target_link_libraries(gpfd_${name} INTERFACE ${ARG_DEPS})
  endif()
  add_library(gpfd::${name} ALIAS gpfd_${name})
endfunction()
