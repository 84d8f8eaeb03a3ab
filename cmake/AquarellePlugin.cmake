# aquarelle_add_plugin(NAME SOURCES a.cpp ... [SHADERS shaders/x.frag ...] [OUTPUT_DIR dir])
#
# Builds a plugin as a loadable module `aquarelle_<NAME>.so`. Shaders are embedded at build time
# into a generated header `<NAME>_shaders.h` (namespace `shaders`), so a plugin is one file to
# install. Works in the source tree and, through find_package(Aquarelle), outside it.
set(_AQUARELLE_EMBED_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/EmbedShaders.cmake)

function(aquarelle_add_plugin name)
  cmake_parse_arguments(ARG "" "OUTPUT_DIR" "SOURCES;SHADERS" ${ARGN})
  set(target aquarelle_plugin_${name})
  add_library(${target} MODULE ${ARG_SOURCES})
  set(_shader_paths "")
  foreach(_s IN LISTS ARG_SHADERS)
    get_filename_component(_abs ${_s} ABSOLUTE)
    list(APPEND _shader_paths ${_abs})
  endforeach()
  set(_gen_dir ${CMAKE_CURRENT_BINARY_DIR}/${target}_generated)
  set(_header ${_gen_dir}/${name}_shaders.h)
  add_custom_command(
    OUTPUT ${_header}
    COMMAND ${CMAKE_COMMAND} -DOUTPUT=${_header} "-DSOURCES=${_shader_paths}"
            -P ${_AQUARELLE_EMBED_SCRIPT}
    DEPENDS ${_shader_paths} ${_AQUARELLE_EMBED_SCRIPT}
    COMMENT "Embedding shaders of plugin ${name}"
    VERBATIM)
  target_sources(${target} PRIVATE ${_header})
  target_include_directories(${target} PRIVATE ${_gen_dir})
  if(TARGET aquarelle_sdk)
    target_link_libraries(${target} PRIVATE aquarelle_sdk)
  else()
    target_link_libraries(${target} PRIVATE Aquarelle::sdk)
  endif()
  set(_out_dir ${ARG_OUTPUT_DIR})
  if(NOT _out_dir AND DEFINED AQUARELLE_PLUGIN_BUILD_DIR)
    set(_out_dir ${AQUARELLE_PLUGIN_BUILD_DIR})
  endif()
  if(NOT _out_dir)
    set(_out_dir ${CMAKE_BINARY_DIR}/plugins)
  endif()
  set_target_properties(${target} PROPERTIES
    PREFIX ""
    OUTPUT_NAME aquarelle_${name}
    LIBRARY_OUTPUT_DIRECTORY ${_out_dir}
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON
    CXX_STANDARD 20)
  target_link_options(${target} PRIVATE -Wl,--exclude-libs,ALL -Wl,--no-undefined)
  set_property(GLOBAL APPEND PROPERTY AQUARELLE_PLUGIN_TARGETS ${target})
  if(DEFINED AQUARELLE_PLUGIN_INSTALL_SUBDIR AND NOT ARG_OUTPUT_DIR)
    install(TARGETS ${target} LIBRARY DESTINATION ${AQUARELLE_PLUGIN_INSTALL_SUBDIR})
  endif()
endfunction()
