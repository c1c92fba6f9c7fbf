# Regenerates <build>/generated/gpfd/version.hpp at every build from `git describe`, writing it only
# when the text changes so that an unchanged revision triggers no rebuild.
set(GPFD_VERSION_HEADER ${CMAKE_BINARY_DIR}/generated/gpfd/version.hpp)
add_custom_target(gpfd_version_header
  COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DOUTPUT=${GPFD_VERSION_HEADER}
          -DVERSION=${PROJECT_VERSION} -P ${PROJECT_SOURCE_DIR}/cmake/write_version.cmake
  BYPRODUCTS ${GPFD_VERSION_HEADER}
  COMMENT "Checking the git revision")
add_library(gpfd_version INTERFACE)
target_include_directories(gpfd_version INTERFACE ${CMAKE_BINARY_DIR}/generated)
add_dependencies(gpfd_version gpfd_version_header)
