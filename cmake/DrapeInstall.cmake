# `cmake --install` lays out headers, the framework library, the plugins, the
# drape program and a package config so that out-of-tree plugins can do
# find_package(drape) and drape_add_plugin(...).
include(CMakePackageConfigHelpers)
install(TARGETS drape_warnings EXPORT drapeTargets)
install(EXPORT drapeTargets NAMESPACE drape:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/drape)
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/drapeConfig.cmake.in
  ${CMAKE_BINARY_DIR}/drapeConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/drape
  PATH_VARS DRAPE_PLUGIN_INSTALL_DIR)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/drapeConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/drapeConfig.cmake ${CMAKE_BINARY_DIR}/drapeConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/drape)
