# `cmake --install build --prefix P` installs the library as a CMake package
# (find_package(scansurf) -> scansurf::scansurf), its public headers, the CLI and the docs.
include(CMakePackageConfigHelpers)
set(SCANSURF_CMAKE_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/scansurf")

install(TARGETS scansurf EXPORT scansurfTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY "${PROJECT_SOURCE_DIR}/engine/include/scansurf" "${PROJECT_BINARY_DIR}/engine/include/scansurf"
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")
install(EXPORT scansurfTargets NAMESPACE scansurf:: DESTINATION "${SCANSURF_CMAKE_DIR}")

if(BUILD_SHARED_LIBS)
  set(SCANSURF_CONFIG_STATIC FALSE)
else()
  set(SCANSURF_CONFIG_STATIC TRUE)
endif()
configure_package_config_file("${CMAKE_CURRENT_LIST_DIR}/scansurfConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/scansurfConfig.cmake" INSTALL_DESTINATION "${SCANSURF_CMAKE_DIR}")
write_basic_package_version_file("${PROJECT_BINARY_DIR}/scansurfConfigVersion.cmake"
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)  # 0.x: minor versions may break the API
install(FILES "${PROJECT_BINARY_DIR}/scansurfConfig.cmake" "${PROJECT_BINARY_DIR}/scansurfConfigVersion.cmake"
  "${CMAKE_CURRENT_LIST_DIR}/NiftiTargets.cmake" DESTINATION "${SCANSURF_CMAKE_DIR}")

if(SCANSURF_BUILD_CLI)
  install(TARGETS scansurf_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
install(FILES "${PROJECT_SOURCE_DIR}/README.md" "${PROJECT_SOURCE_DIR}/docs/report.schema.json" DESTINATION ${CMAKE_INSTALL_DOCDIR})
# The user's pages (README links them); the measurements stay in the source tree.
foreach(page input-format library python outputs formats limits method overlaps)
  install(FILES "${PROJECT_SOURCE_DIR}/docs/${page}.md" DESTINATION ${CMAKE_INSTALL_DOCDIR})
endforeach()
install(DIRECTORY "${PROJECT_SOURCE_DIR}/examples/" DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples)
