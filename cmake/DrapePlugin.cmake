# drape_add_plugin(<target> SOURCES ... [LIBS ...])
# A plugin is a MODULE library loaded at run time by the framework's registry.
function(drape_add_plugin target)
  cmake_parse_arguments(P "" "" "SOURCES;LIBS" ${ARGN})
  add_library(${target} MODULE ${P_SOURCES})
  target_link_libraries(${target} PRIVATE drape::framework drape_warnings ${P_LIBS})
  set_target_properties(${target} PROPERTIES
    PREFIX "libdrape_plugin_"
    LIBRARY_OUTPUT_DIRECTORY ${DRAPE_BUILD_PLUGIN_DIR}
    CXX_VISIBILITY_PRESET hidden)
  install(TARGETS ${target} LIBRARY DESTINATION ${DRAPE_PLUGIN_INSTALL_DIR})
  if(TARGET drape_plugin_pch)  # plugins/CMakeLists.txt: the shared precompiled header
    target_precompile_headers(${target} REUSE_FROM drape_plugin_pch)
  endif()
  set_property(GLOBAL APPEND PROPERTY DRAPE_PLUGIN_TARGETS ${target})
endfunction()
