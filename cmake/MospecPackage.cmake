# The runtime as a CMake package (find_package(mospec) -> mospec::runtime), for
# the projects `mospec generate` writes. Two copies of the package config:
#   - the build tree (${PROJECT_BINARY_DIR}/package): usable straight from a dev
#     checkout, no install needed; the CLI has this path compiled in;
#   - the install tree (${CMAKE_INSTALL_LIBDIR}/cmake/mospec), with the headers
#     under ${MOSPEC_INSTALL_INCLUDEDIR}; an installed CLI finds it relative to
#     its own executable (../lib/cmake/mospec).
include(CMakePackageConfigHelpers)

set(_mospec_package_libs mospec_runtime mospec_robot_interface mospec_support)
# The generated controller is a shared library that links these static ones.
set_target_properties(${_mospec_package_libs} PROPERTIES POSITION_INDEPENDENT_CODE ON)
set_target_properties(mospec_runtime PROPERTIES EXPORT_NAME runtime_kernels)
set_target_properties(mospec_robot_interface PROPERTIES EXPORT_NAME robot_interface)
set_target_properties(mospec_support PROPERTIES EXPORT_NAME support)

# mospec::runtime: everything a generated controller links.
add_library(mospec_package_runtime INTERFACE)
set_target_properties(mospec_package_runtime PROPERTIES EXPORT_NAME runtime)
target_link_libraries(mospec_package_runtime INTERFACE ${_mospec_package_libs})
target_compile_features(mospec_package_runtime INTERFACE cxx_std_20)
if(MOSPEC_SANITIZE)
  # A controller loaded into a sanitized process must be built the same way.
  target_compile_options(mospec_package_runtime INTERFACE -fsanitize=address,undefined
                         -fno-omit-frame-pointer)
  target_link_options(mospec_package_runtime INTERFACE -fsanitize=address,undefined)
endif()

# The libraries link mospec_warnings privately; static libraries carry private
# dependencies into the export (as link-only, so its flags never reach a user).
set_target_properties(mospec_warnings PROPERTIES EXPORT_NAME build_warnings)
install(TARGETS ${_mospec_package_libs} mospec_package_runtime mospec_warnings EXPORT mospecTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${MOSPEC_INSTALL_INCLUDEDIR})
# Headers: the three libraries'.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/runtime ${PROJECT_SOURCE_DIR}/src/robot
                  ${PROJECT_SOURCE_DIR}/src/support
        DESTINATION ${MOSPEC_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.hpp")

set(MOSPEC_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/mospec)
install(TARGETS mospec mospec-full RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(EXPORT mospecTargets NAMESPACE mospec:: DESTINATION ${MOSPEC_INSTALL_CMAKEDIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/mospecConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/install-package/mospecConfig.cmake
                              INSTALL_DESTINATION ${MOSPEC_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/package/mospecConfigVersion.cmake
                                 COMPATIBILITY ExactVersion)
install(FILES ${PROJECT_BINARY_DIR}/install-package/mospecConfig.cmake
              ${PROJECT_BINARY_DIR}/package/mospecConfigVersion.cmake
        DESTINATION ${MOSPEC_INSTALL_CMAKEDIR})

# The build-tree copy (MOSPEC_BUILD_PACKAGE_DIR, set before src/ so the CLI
# knows it): same config, targets pointing into this build.
export(EXPORT mospecTargets NAMESPACE mospec:: FILE ${MOSPEC_BUILD_PACKAGE_DIR}/mospecTargets.cmake)
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/mospecConfig.cmake.in
                              ${MOSPEC_BUILD_PACKAGE_DIR}/mospecConfig.cmake
                              INSTALL_DESTINATION ${MOSPEC_BUILD_PACKAGE_DIR}
                              INSTALL_PREFIX ${PROJECT_BINARY_DIR})
