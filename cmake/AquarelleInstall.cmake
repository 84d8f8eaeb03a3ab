# `cmake --install`: the executable, the core library, the plugins, the plugin SDK (headers,
# GL loader, CMake helper) and a CMake package, so plugins build outside the tree with
#   find_package(Aquarelle REQUIRED)
#   aquarelle_add_plugin(myplugin SOURCES my.cpp SHADERS shaders/my.frag)
include(CMakePackageConfigHelpers)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/nodes/include/aquarelle
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY ${AQUARELLE_GLAD_DIR}/include/
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/aquarelle/gl)
install(TARGETS aquarelle_glad aquarelle_sdk EXPORT AquarelleSdkTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS aquarelle_nodes ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(EXPORT AquarelleSdkTargets NAMESPACE Aquarelle::
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Aquarelle)
install(FILES ${PROJECT_SOURCE_DIR}/cmake/AquarellePlugin.cmake
              ${PROJECT_SOURCE_DIR}/cmake/EmbedShaders.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Aquarelle)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/nodes/shaders/
        DESTINATION ${CMAKE_INSTALL_DATADIR}/aquarelle/shaders)
if(EXISTS ${PROJECT_SOURCE_DIR}/ocio)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/ocio DESTINATION ${CMAKE_INSTALL_DATADIR}/aquarelle)
endif()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/graphs DESTINATION ${CMAKE_INSTALL_DATADIR}/aquarelle)

file(WRITE ${CMAKE_BINARY_DIR}/AquarelleConfig.cmake.in [=[
@PACKAGE_INIT@
include("${CMAKE_CURRENT_LIST_DIR}/AquarelleSdkTargets.cmake")
include("${CMAKE_CURRENT_LIST_DIR}/AquarellePlugin.cmake")
set(AQUARELLE_PLUGIN_DIR "${PACKAGE_PREFIX_DIR}/@AQUARELLE_PLUGIN_INSTALL_SUBDIR@")
]=])
configure_package_config_file(${CMAKE_BINARY_DIR}/AquarelleConfig.cmake.in
  ${CMAKE_BINARY_DIR}/AquarelleConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Aquarelle)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/AquarelleConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES ${CMAKE_BINARY_DIR}/AquarelleConfig.cmake
              ${CMAKE_BINARY_DIR}/AquarelleConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Aquarelle)
