# nimbus_add_plugin(<target> SOURCES <files...> [OUTPUT_DIRECTORY <dir>] [NO_INSTALL])
#
# Builds a Nimbus plugin as a MODULE library that exports only `nimbus_plugin_entry`: hidden visibility,
# a version script, and --no-undefined so that a missing symbol fails at link time, not at load time; and
# compiled without SLP vectorisation (below).
# Plugins never link host libraries; only C crosses the boundary.

function(nimbus_add_plugin target)
  cmake_parse_arguments(ARG "NO_INSTALL" "OUTPUT_DIRECTORY" "SOURCES" ${ARGN})
  # The version script sits next to this file, wherever the SDK is (source tree or install prefix).
  set(_NIMBUS_PLUGIN_MAP ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/nimbus_plugin.map)
  add_library(${target} MODULE ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE Nimbus::sdk)
  set_target_properties(${target} PROPERTIES
    PREFIX "lib"
    C_VISIBILITY_PRESET hidden
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
  target_link_options(${target} PRIVATE
    "LINKER:--version-script=${_NIMBUS_PLUGIN_MAP}" "LINKER:--no-undefined")
  # Without SLP vectorisation: it reads neighbouring floats of the records the host fills (hits, BSDF
  # samples) with wider loads that straddle the host's stores, and each such load waits for those stores
  # to reach the cache, at every vertex (docs/performance.md §1: 2-4 % of a render).
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" OR CMAKE_C_COMPILER_ID STREQUAL "GNU")
    target_compile_options(${target} PRIVATE -fno-tree-slp-vectorize)
  elseif(CMAKE_CXX_COMPILER_ID MATCHES "Clang" OR CMAKE_C_COMPILER_ID MATCHES "Clang")
    target_compile_options(${target} PRIVATE -fno-slp-vectorize)
  endif()
  # Sanitizer runtimes are provided by the host executable; allow their symbols to stay undefined. GCC
  # links its runtime library into the module as well; Clang never does (its runtime is static in the
  # executable), so there the module's own references to it stay undefined too (-z undefs).
  if(NIMBUS_SANITIZE OR NIMBUS_TSAN)
    target_link_options(${target} PRIVATE "LINKER:--allow-shlib-undefined")
    if(CMAKE_CXX_COMPILER_ID MATCHES "Clang")
      target_link_options(${target} PRIVATE "LINKER:-z,undefs")
    endif()
  endif()
  if(ARG_OUTPUT_DIRECTORY)
    set_target_properties(${target} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${ARG_OUTPUT_DIRECTORY})
  elseif(DEFINED NIMBUS_PLUGIN_OUTPUT_DIR)
    set_target_properties(${target} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${NIMBUS_PLUGIN_OUTPUT_DIR})
  endif()
  if(NOT ARG_NO_INSTALL)
    # In the Nimbus tree NIMBUS_INSTALL_PLUGIN_DIR is set; out of tree the plugin goes to the same
    # relative place under the plugin's own prefix (point NIMBUS_PLUGIN_PATH there, or install with
    # --prefix set to the Nimbus prefix).
    if(DEFINED NIMBUS_INSTALL_PLUGIN_DIR)
      set(_NIMBUS_PLUGIN_DEST ${NIMBUS_INSTALL_PLUGIN_DIR})
    elseif(DEFINED CMAKE_INSTALL_LIBDIR)
      set(_NIMBUS_PLUGIN_DEST ${CMAKE_INSTALL_LIBDIR}/nimbus/plugins)
    else()
      set(_NIMBUS_PLUGIN_DEST lib/nimbus/plugins)
    endif()
    # Nimbus's own build sets NIMBUS_PLUGIN_INSTALL_COMPONENT (runtime); a third-party project may set it
    # to package its plugins as a component of its own, else they go to CMake's default component.
    set(_NIMBUS_PLUGIN_COMPONENT)
    if(NIMBUS_PLUGIN_INSTALL_COMPONENT)
      set(_NIMBUS_PLUGIN_COMPONENT COMPONENT ${NIMBUS_PLUGIN_INSTALL_COMPONENT})
    endif()
    install(TARGETS ${target} LIBRARY DESTINATION ${_NIMBUS_PLUGIN_DEST} ${_NIMBUS_PLUGIN_COMPONENT})
  endif()
endfunction()
