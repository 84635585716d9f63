# Where the install puts each part (relative to the install prefix), and what the installed
# binaries derive from it. mjarm is a static library: the CLI and the Python extension each carry
# it, and each finds the bundled models relative to its own folder (Robot::models_dir(),
# src/model/models_dir.cpp), so an install that is moved, or unpacked from a wheel, still finds them.
#
#   MJARM_CLI_DESTINATION      the CLI `mjarm`
#   MJARM_PACKAGE_DESTINATION  the Python package mjarm (with MJARM_PYTHON)
#   MJARM_MODELS_DESTINATION   the bundled models
if(MJARM_WHEEL)
  # the prefix is the wheel's site-packages: everything lives in the package, beside mujoco's
  set(MJARM_PACKAGE_DESTINATION mjarm)
  set(MJARM_CLI_DESTINATION mjarm/bin)
  set(MJARM_MODELS_DESTINATION mjarm/models)
  # the mujoco wheel's package folder, which holds libmujoco.so.<version>
  set(MJARM_MUJOCO_DESTINATION mujoco)
else()
  set(MJARM_CLI_DESTINATION ${CMAKE_INSTALL_BINDIR})
  set(MJARM_MODELS_DESTINATION ${CMAKE_INSTALL_DATADIR}/mjarm/models)
  if(MJARM_PYTHON)
    set(MJARM_PACKAGE_DESTINATION ${MJARM_PYTHON_INSTALL_DIR}/mjarm)
  endif()
endif()

# the path from destination `from` to destination `to`: the same under any prefix
function(mjarm_install_relative out from to)
  cmake_path(ABSOLUTE_PATH from BASE_DIRECTORY "${CMAKE_INSTALL_PREFIX}" NORMALIZE)
  cmake_path(ABSOLUTE_PATH to BASE_DIRECTORY "${CMAKE_INSTALL_PREFIX}" NORMALIZE)
  file(RELATIVE_PATH relative "${from}" "${to}")
  set(${out} "${relative}" PARENT_SCOPE)
endfunction()

# the models' folder as seen from each installed binary's folder (models_dir.cpp tries each)
set(MJARM_MODELS_RELATIVE_DIRS "")
foreach(destination ${MJARM_CLI_DESTINATION} ${MJARM_PACKAGE_DESTINATION})
  mjarm_install_relative(relative ${destination} ${MJARM_MODELS_DESTINATION})
  list(APPEND MJARM_MODELS_RELATIVE_DIRS ${relative})
endforeach()
list(JOIN MJARM_MODELS_RELATIVE_DIRS ":" MJARM_MODELS_RELATIVE_DIRS)
if(MJARM_WHEEL)
  # a wheel knows neither the source tree nor where it will be installed
  set(MJARM_MODELS_SOURCE_LOOKUP "")
  set(MJARM_MODELS_INSTALL_LOOKUP "")
else()
  set(MJARM_MODELS_SOURCE_LOOKUP "${MJARM_MODELS_SOURCE_DIR}")
  # for a program outside the install that links the installed library (find_package(mjarm))
  cmake_path(ABSOLUTE_PATH MJARM_MODELS_DESTINATION BASE_DIRECTORY "${CMAKE_INSTALL_PREFIX}"
             NORMALIZE OUTPUT_VARIABLE MJARM_MODELS_INSTALL_LOOKUP)
endif()
# only the file that reads them gets the folders: the rest of the library compiles the same in
# every checkout (a compiler cache shares it between work trees)
set_source_files_properties(src/model/models_dir.cpp PROPERTIES COMPILE_DEFINITIONS
  "MJARM_MODELS_SOURCE_DIR=\"${MJARM_MODELS_SOURCE_LOOKUP}\";MJARM_MODELS_RELATIVE_DIRS=\"${MJARM_MODELS_RELATIVE_DIRS}\";MJARM_MODELS_INSTALL_DIR=\"${MJARM_MODELS_INSTALL_LOOKUP}\"")
