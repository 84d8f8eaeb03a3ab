# Generates the OpenGL 4.5 core loader with glad2 (Debian's python3-glad) at build time and
# wraps it in a static library. Its symbols are hidden so that every plugin holds its own
# copy, loaded from the host's get_proc_address, and none interposes another's.
set(AQUARELLE_GLAD_DIR ${CMAKE_BINARY_DIR}/glad)
set(_glad_python /usr/bin/python3)
if(NOT EXISTS ${_glad_python})
  set(_glad_python ${Python3_EXECUTABLE})
endif()
add_custom_command(
  OUTPUT ${AQUARELLE_GLAD_DIR}/src/gl.c ${AQUARELLE_GLAD_DIR}/include/glad/gl.h
  COMMAND ${_glad_python} -m glad --api gl:core=4.5 --out-path ${AQUARELLE_GLAD_DIR}
          --quiet --reproducible c
  COMMENT "Generating the OpenGL 4.5 core loader with glad2"
  VERBATIM)
add_library(aquarelle_glad STATIC ${AQUARELLE_GLAD_DIR}/src/gl.c)
set_target_properties(aquarelle_glad PROPERTIES C_VISIBILITY_PRESET hidden
                                                POSITION_INDEPENDENT_CODE ON)
target_include_directories(aquarelle_glad PUBLIC
  $<BUILD_INTERFACE:${AQUARELLE_GLAD_DIR}/include>
  $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/aquarelle/gl>)
add_library(Aquarelle::glad ALIAS aquarelle_glad)
set_target_properties(aquarelle_glad PROPERTIES EXPORT_NAME glad)
