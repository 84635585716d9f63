# Installs headers, library, CLI, models and a CMake package so that find_package(mjarm) works.
include(CMakePackageConfigHelpers)
install(TARGETS mjarm EXPORT mjarmTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY include/mjarm DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY models/ DESTINATION ${CMAKE_INSTALL_DATADIR}/mjarm/models)
if(TARGET mjarm_cli)
  install(TARGETS mjarm_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
install(EXPORT mjarmTargets NAMESPACE mjarm:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mjarm)
configure_package_config_file(cmake/mjarmConfig.cmake.in ${CMAKE_CURRENT_BINARY_DIR}/mjarmConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mjarm)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/mjarmConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES cmake/mjarm_find_mujoco.cmake cmake/mujoco_version_probe.cpp
  ${CMAKE_CURRENT_BINARY_DIR}/mjarmConfig.cmake
  ${CMAKE_CURRENT_BINARY_DIR}/mjarmConfigVersion.cmake DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mjarm)
