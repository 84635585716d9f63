# Defines the imported target mjarm::mujoco from Debian's libmujoco-dev (MuJoCo 2.2.2).
# Debian's own mujocoConfig.cmake is not used: it requires OpenGL development files and lists
# /usr/include/libqhull_r, neither of which a headless build of mjarm needs.
if(NOT TARGET mjarm::mujoco)
  find_path(MJARM_MUJOCO_INCLUDE_DIR mujoco/mujoco.h)
  find_library(MJARM_MUJOCO_LIBRARY NAMES mujoco)
  if(NOT MJARM_MUJOCO_INCLUDE_DIR OR NOT MJARM_MUJOCO_LIBRARY)
    message(FATAL_ERROR "MuJoCo not found: install Debian's libmujoco-dev (scripts/setup.sh does)")
  endif()
  add_library(mjarm::mujoco UNKNOWN IMPORTED)
  set_target_properties(mjarm::mujoco PROPERTIES
    IMPORTED_LOCATION "${MJARM_MUJOCO_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${MJARM_MUJOCO_INCLUDE_DIR}")
endif()
