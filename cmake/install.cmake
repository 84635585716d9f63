# Installs headers, library, CLI, models and a CMake package so that find_package(mjarm) works;
# with MJARM_WHEEL (`pip install .`), the Python package only: destinations in install_dirs.cmake.
include(CMakePackageConfigHelpers)
install(DIRECTORY models/ DESTINATION ${MJARM_MODELS_DESTINATION})
if(TARGET mjarm_cli)
  install(TARGETS mjarm_cli RUNTIME DESTINATION ${MJARM_CLI_DESTINATION})
endif()

if(MJARM_WHEEL)
  # the wheel's binaries find libmujoco in the mujoco package installed beside mjarm (the
  # dependency mujoco==<version>), wherever site-packages is
  foreach(target_and_destination "mjarm_cli;${MJARM_CLI_DESTINATION}"
                                  "mjarm_python;${MJARM_PACKAGE_DESTINATION}")
    list(GET target_and_destination 0 target)
    list(GET target_and_destination 1 destination)
    if(TARGET ${target})
      mjarm_install_relative(relative ${destination} ${MJARM_MUJOCO_DESTINATION})
      set_target_properties(${target} PROPERTIES INSTALL_RPATH "$ORIGIN/${relative}")
    endif()
  endforeach()
  return()
endif()

install(TARGETS mjarm EXPORT mjarmTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# the trajectory room's validation references are not part of the package (their target is not either)
install(DIRECTORY include/mjarm DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  REGEX "/trajectory/(otg|path)/validation$" EXCLUDE)
install(EXPORT mjarmTargets NAMESPACE mjarm:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mjarm)
configure_package_config_file(cmake/mjarmConfig.cmake.in ${CMAKE_CURRENT_BINARY_DIR}/mjarmConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mjarm)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/mjarmConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES cmake/mjarm_find_mujoco.cmake cmake/mujoco_version_probe.cpp
  ${CMAKE_CURRENT_BINARY_DIR}/mjarmConfig.cmake
  ${CMAKE_CURRENT_BINARY_DIR}/mjarmConfigVersion.cmake DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mjarm)
