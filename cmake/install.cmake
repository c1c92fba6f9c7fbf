# cmake --install: the tool, the module libraries, the headers and a CMake package, so that a
# project of one's own finds gpfd with find_package(gpfd) and links gpfd::core (a program) or
# gpfd::plugin (a plug-in for the tool, see include/gpfd/run/plugin.hpp).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(GPFD_INSTALLED_MODULES gpfd_util gpfd_expr gpfd_features gpfd_jit gpfd_env gpfd_rl gpfd_gp
                           gpfd_io gpfd_run gpfd_service)
install(TARGETS ${GPFD_INSTALLED_MODULES} gpfd_core gpfd_plugin EXPORT gpfdTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS gpfd RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/gpfd DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

set(GPFD_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/gpfd)
install(EXPORT gpfdTargets NAMESPACE gpfd:: DESTINATION ${GPFD_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/gpfdConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/gpfdConfig.cmake
                              INSTALL_DESTINATION ${GPFD_CMAKE_DIR}
                              PATH_VARS CMAKE_INSTALL_BINDIR)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/gpfdConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/gpfdConfig.cmake ${CMAKE_BINARY_DIR}/gpfdConfigVersion.cmake
        DESTINATION ${GPFD_CMAKE_DIR})
