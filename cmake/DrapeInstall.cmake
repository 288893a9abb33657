# `cmake --install <build> --prefix P` lays out
#   P/include/drape/...                 public headers (installed by framework/)
#   P/lib/libdrape_framework.so*        the framework library
#   P/lib/drape/plugins/*.so            every shipped plugin (the registry looks
#                                       there, relative to the framework library)
#   P/bin/drape                         the program (RUNPATH $ORIGIN/../lib)
#   P/lib/cmake/drape/                  package config: find_package(drape) gives
#                                       drape::framework and drape_add_plugin()
include(CMakePackageConfigHelpers)

# Out-of-tree code compiles our public headers, which are C++20.
target_compile_features(drape_framework PUBLIC cxx_std_20)

# A plugin finds the framework two levels up (lib/drape/plugins -> lib) when
# something other than the drape program dlopens it.
get_property(drape_plugin_targets GLOBAL PROPERTY DRAPE_PLUGIN_TARGETS)
foreach(plugin ${drape_plugin_targets})
  set_target_properties(${plugin} PROPERTIES INSTALL_RPATH "$ORIGIN/../..")
endforeach()

# The warning flags are exported as drape::warnings so out-of-tree plugins can
# opt in to the same bar; the framework links them privately, so nothing else sees them.
set_target_properties(drape_warnings PROPERTIES EXPORT_NAME warnings)
install(TARGETS drape_warnings EXPORT drapeTargets)
install(EXPORT drapeTargets NAMESPACE drape:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/drape)

# The config only asks for OpenMP when the framework was built with it (its
# imported target is then part of drape::framework's link interface).
if(OpenMP_CXX_FOUND)
  set(DRAPE_WITH_OPENMP ON)
else()
  set(DRAPE_WITH_OPENMP OFF)
endif()
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/drapeConfig.cmake.in
  ${CMAKE_BINARY_DIR}/drapeConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/drape
  PATH_VARS DRAPE_PLUGIN_INSTALL_DIR CMAKE_INSTALL_INCLUDEDIR)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/drapeConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/drapeConfig.cmake ${CMAKE_BINARY_DIR}/drapeConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/drape)
