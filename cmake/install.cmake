# Installs the planner library and the simulator as a CMake package:
#   find_package(maneuvermap REQUIRED)  →  targets mm::core, mm::sim and mm::commonroad
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS mm_core mm_sim mm_commonroad EXPORT maneuvermap_targets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  FILE_SET HEADERS DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT maneuvermap_targets NAMESPACE mm:: FILE maneuvermap-targets.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/maneuvermap)
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/maneuvermap-config.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/maneuvermap-config.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/maneuvermap)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/maneuvermap-config-version.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/maneuvermap-config.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/maneuvermap-config-version.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/maneuvermap)
