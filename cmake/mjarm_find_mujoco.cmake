# Defines the imported target mjarm::mujoco: the MuJoCo mjarm builds against and runs on.
#
# MUJOCO_ROOT is a folder holding include/mujoco/mujoco.h and libmujoco.so.<version>, either side
# by side (the official PyPI wheel's package folder, site-packages/mujoco) or under lib/ (the
# official release archive, or a MuJoCo built and installed from source). When it is not given,
# it is the mujoco package of MJARM_PYTHON_EXECUTABLE (the project's .venv, made by
# scripts/setup.sh), so that the user's `import mujoco` and mjarm share one library.
#
# The header's mjVERSION_HEADER must match the library's mj_version() (checked by compiling and
# running a probe); the library's folder goes into the run path of what is built against it, so
# nothing needs LD_LIBRARY_PATH. Sets MJARM_MUJOCO_ROOT, MJARM_MUJOCO_LIBRARY,
# MJARM_MUJOCO_LIBRARY_DIR and MJARM_MUJOCO_VERSION ("4.0.1").
if(TARGET mjarm::mujoco)
  return()
endif()

set(MUJOCO_ROOT "${MJARM_MUJOCO_ROOT_DEFAULT}" CACHE PATH
    "MuJoCo to build against: a folder with include/mujoco/mujoco.h and libmujoco.so.* (beside it or in lib/); empty: the mujoco package of the project's virtual environment")

set(MJARM_MUJOCO_ROOT "${MUJOCO_ROOT}")
if(NOT MJARM_MUJOCO_ROOT)
  if(NOT MJARM_PYTHON_EXECUTABLE OR NOT EXISTS "${MJARM_PYTHON_EXECUTABLE}")
    message(FATAL_ERROR "MuJoCo: no virtual environment at '${MJARM_PYTHON_EXECUTABLE}'. Run "
                        "`make setup` (scripts/setup.sh makes .venv with the pinned mujoco), or "
                        "pass -DMUJOCO_ROOT=<folder with include/mujoco/mujoco.h and libmujoco.so.*>")
  endif()
  # find_spec locates the package without importing it (no OpenGL or GLFW needed to configure)
  execute_process(
    COMMAND "${MJARM_PYTHON_EXECUTABLE}" -c
      "import importlib.util as u; s = u.find_spec('mujoco'); print(s.submodule_search_locations[0] if s else '')"
    OUTPUT_VARIABLE MJARM_MUJOCO_ROOT OUTPUT_STRIP_TRAILING_WHITESPACE
    RESULT_VARIABLE mjarm_probe_rc ERROR_VARIABLE mjarm_probe_err)
  if(NOT mjarm_probe_rc EQUAL 0 OR NOT MJARM_MUJOCO_ROOT)
    message(FATAL_ERROR "MuJoCo: the package mujoco is not installed for '${MJARM_PYTHON_EXECUTABLE}' "
                        "${mjarm_probe_err}. Run `make setup` (or scripts/setup_venv.sh), or pass "
                        "-DMUJOCO_ROOT=<folder>")
  endif()
endif()

find_path(MJARM_MUJOCO_INCLUDE_DIR mujoco/mujoco.h PATHS "${MJARM_MUJOCO_ROOT}/include"
          NO_DEFAULT_PATH NO_CACHE)
file(GLOB mjarm_mujoco_candidates "${MJARM_MUJOCO_ROOT}/libmujoco.so.*"
     "${MJARM_MUJOCO_ROOT}/lib/libmujoco.so.*" "${MJARM_MUJOCO_ROOT}/lib64/libmujoco.so.*")
list(SORT mjarm_mujoco_candidates)
list(LENGTH mjarm_mujoco_candidates mjarm_mujoco_count)
if(NOT MJARM_MUJOCO_INCLUDE_DIR OR mjarm_mujoco_count EQUAL 0)
  message(FATAL_ERROR "MuJoCo: '${MJARM_MUJOCO_ROOT}' holds no include/mujoco/mujoco.h or no "
                      "libmujoco.so.*; MUJOCO_ROOT must be a MuJoCo wheel's package folder or a "
                      "release archive's folder")
endif()
# a release archive has libmujoco.so.X.Y.Z and its symlink libmujoco.so.X; take the real file
list(GET mjarm_mujoco_candidates 0 MJARM_MUJOCO_LIBRARY)
get_filename_component(MJARM_MUJOCO_LIBRARY "${MJARM_MUJOCO_LIBRARY}" REALPATH)
get_filename_component(MJARM_MUJOCO_LIBRARY_DIR "${MJARM_MUJOCO_LIBRARY}" DIRECTORY)

# the header and the library must be the same release
try_run(mjarm_version_run mjarm_version_compiled
  SOURCES "${CMAKE_CURRENT_LIST_DIR}/mujoco_version_probe.cpp"
  CXX_STANDARD 20  # MuJoCo's headers need C++17; clang 14 defaults to C++14
  CMAKE_FLAGS "-DINCLUDE_DIRECTORIES=${MJARM_MUJOCO_INCLUDE_DIR}"
  LINK_LIBRARIES "${MJARM_MUJOCO_LIBRARY}"
  LINK_OPTIONS "-Wl,-rpath,${MJARM_MUJOCO_LIBRARY_DIR}"
  COMPILE_OUTPUT_VARIABLE mjarm_version_compile_output
  RUN_OUTPUT_VARIABLE mjarm_version_output)
if(NOT mjarm_version_compiled)
  message(FATAL_ERROR "MuJoCo: cannot build against '${MJARM_MUJOCO_ROOT}':\n${mjarm_version_compile_output}")
endif()
if(NOT mjarm_version_run EQUAL 0)
  message(FATAL_ERROR "MuJoCo: ${mjarm_version_output} (MUJOCO_ROOT '${MJARM_MUJOCO_ROOT}')")
endif()
string(STRIP "${mjarm_version_output}" MJARM_MUJOCO_VERSION)
if(NOT MJARM_MUJOCO_VERSION VERSION_GREATER_EQUAL 4.0)
  message(FATAL_ERROR "MuJoCo: mjarm needs MuJoCo 4.0 or later; '${MJARM_MUJOCO_ROOT}' is "
                      "${MJARM_MUJOCO_VERSION}")
endif()
message(STATUS "MuJoCo ${MJARM_MUJOCO_VERSION}: ${MJARM_MUJOCO_LIBRARY}")

# linked by its file (the wheel has no unversioned symlink), found at run time by its soname in
# the run path: CMake's build run path holds its folder, installs set theirs (install.cmake)
add_library(mjarm::mujoco SHARED IMPORTED)
set_target_properties(mjarm::mujoco PROPERTIES
  IMPORTED_LOCATION "${MJARM_MUJOCO_LIBRARY}"
  INTERFACE_INCLUDE_DIRECTORIES "${MJARM_MUJOCO_INCLUDE_DIR}")
