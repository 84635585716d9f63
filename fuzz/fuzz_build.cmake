# The fuzz build (MJARM_FUZZ=ON; scripts/fuzz.sh configures it in build-fuzz): one libFuzzer
# program per reader, fuzz_NAME, over a small static library of the reader sources only, all
# compiled by clang with coverage instrumentation for libFuzzer, ASan and UBSan. No tests,
# examples, bindings or CLI. Included from the top-level CMakeLists.txt (same directory scope:
# models_dir.cpp keeps its definitions from cmake/install_dirs.cmake).
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "MJARM_FUZZ needs clang and its libFuzzer (Debian: clang, libclang-rt-14-dev; "
                      "make setup installs them): configure with -DCMAKE_CXX_COMPILER=clang++")
endif()

# UBSan's object-size and pointer-overflow checks left out, as in the sanitized build: ASan reports
# what they would, and they double the compile time of optimized code
set(MJARM_FUZZ_SANITIZERS -fsanitize=address,undefined -fno-sanitize=object-size,pointer-overflow
                          -fno-sanitize-recover=all -fno-omit-frame-pointer)

# the readers and what they call (the link closure of the entry points in fuzz/*_target.cpp):
# a sixth of the library, so the fuzz build compiles in a fraction of the full one
set(MJARM_FUZZ_LIBRARY_SOURCES
  closest_names.cpp fields.cpp file_writer.cpp json_document.cpp number_text.cpp
  ik/targets.cpp
  kinematics/chain_kinematics.cpp kinematics/manipulability.cpp kinematics/workspace.cpp
  lie/coefficients.cpp lie/pose.cpp lie/pose_error.cpp lie/rotation.cpp lie/se3.cpp
  lie/se3_jacobian.cpp lie/so3.cpp
  planning/waypoint_file.cpp
  plot/csv_table.cpp plot/recording.cpp
  teleop/session_log_reader.cpp teleop/viewer_panel.cpp teleop/viewer_script.cpp)
file(GLOB MJARM_FUZZ_ROOM_SOURCES CONFIGURE_DEPENDS RELATIVE ${PROJECT_SOURCE_DIR}/src
     ${PROJECT_SOURCE_DIR}/src/model/*.cpp ${PROJECT_SOURCE_DIR}/src/scene/*.cpp)
list(APPEND MJARM_FUZZ_LIBRARY_SOURCES ${MJARM_FUZZ_ROOM_SOURCES})
list(TRANSFORM MJARM_FUZZ_LIBRARY_SOURCES PREPEND ${PROJECT_SOURCE_DIR}/src/)

add_library(mjarm_fuzz_readers STATIC ${MJARM_FUZZ_LIBRARY_SOURCES})
target_compile_options(mjarm_fuzz_readers PRIVATE ${MJARM_WARNINGS})
target_compile_options(mjarm_fuzz_readers PUBLIC -fsanitize=fuzzer-no-link ${MJARM_FUZZ_SANITIZERS})
target_include_directories(mjarm_fuzz_readers PUBLIC ${PROJECT_SOURCE_DIR}/include
                           PRIVATE ${PROJECT_SOURCE_DIR}/src)
target_link_libraries(mjarm_fuzz_readers PUBLIC mjarm::mujoco Eigen3::Eigen
                      PRIVATE tinyxml2::tinyxml2 yaml-cpp nlohmann_json::nlohmann_json)
# one translation unit per room, as the sanitized test build
set_target_properties(mjarm_fuzz_readers PROPERTIES UNITY_BUILD ON UNITY_BUILD_MODE GROUP)
foreach(source ${MJARM_FUZZ_LIBRARY_SOURCES})
  file(RELATIVE_PATH relative ${PROJECT_SOURCE_DIR}/src ${source})
  string(REGEX REPLACE "/.*" "" room ${relative})
  set_source_files_properties(${source} PROPERTIES UNITY_GROUP ${room})
endforeach()

set(MJARM_FUZZ_LIBRARY mjarm_fuzz_readers)
set(MJARM_FUZZ_PROGRAMS ON)
set(MJARM_FUZZ_LINK_OPTIONS ${MJARM_FUZZ_SANITIZERS})
include(${CMAKE_CURRENT_LIST_DIR}/fuzz_programs.cmake)
