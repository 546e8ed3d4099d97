# cmake --install: the static libraries of every layer, their headers under
# include/obscura/, the data files under share/obscura/, the tool, and the
# CMake package (lib/cmake/obscura) for find_package(obscura).
include(CMakePackageConfigHelpers)

set(OBSCURA_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/obscura)
set(OBSCURA_INSTALL_DATADIR ${CMAKE_INSTALL_DATADIR}/obscura)

set(layer_targets)
foreach(layer IN LISTS OBSCURA_LAYERS)
  list(APPEND layer_targets obscura_${layer})
endforeach()
install(TARGETS ${layer_targets} obscura EXPORT obscuraTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS obscura_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# Public headers; cairo_canvas.h is report's own (it includes cairo.h).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/obscura/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/obscura
  FILES_MATCHING PATTERN "*.h" PATTERN "cairo_canvas.h" EXCLUDE)
install(FILES ${PROJECT_BINARY_DIR}/src/obscura/generated/obscura/core/version.h
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/obscura/core)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/data/ DESTINATION ${OBSCURA_INSTALL_DATADIR})
install(EXPORT obscuraTargets NAMESPACE obscura:: DESTINATION ${OBSCURA_INSTALL_CMAKEDIR})

set(OBSCURA_OPENVDB_MODULE_DIR /usr/lib/x86_64-linux-gnu/cmake/OpenVDB)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/obscuraConfig.cmake.in
  ${PROJECT_BINARY_DIR}/obscuraConfig.cmake
  INSTALL_DESTINATION ${OBSCURA_INSTALL_CMAKEDIR}
  PATH_VARS OBSCURA_INSTALL_DATADIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/obscuraConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/obscuraConfig.cmake
  ${PROJECT_BINARY_DIR}/obscuraConfigVersion.cmake DESTINATION ${OBSCURA_INSTALL_CMAKEDIR})
