# The fuzz targets (fuzz/*_target.cpp and their list) as one library over MJARM_FUZZ_LIBRARY and,
# with MJARM_FUZZ_PROGRAMS on, one libFuzzer program per target: fuzz_NAME in the build folder,
# linked with MJARM_FUZZ_LINK_OPTIONS. Two builds include it: the fuzz build (fuzz_build.cmake,
# over the readers alone) and the test build (over mjarm: test_fuzz replays the targets' seeds, and
# the sanitized clang build, whose library carries libFuzzer's coverage instrumentation, makes the
# programs `make test`'s bounded fuzz run uses).
file(GLOB MJARM_FUZZ_TARGET_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/fuzz/*_target.cpp)
add_library(mjarm_fuzz_targets STATIC ${MJARM_FUZZ_TARGET_SOURCES}
            ${PROJECT_SOURCE_DIR}/fuzz/target_list.cpp)
target_compile_options(mjarm_fuzz_targets PRIVATE ${MJARM_WARNINGS} ${MJARM_DRIVER_OPTIONS})
target_include_directories(mjarm_fuzz_targets PUBLIC ${PROJECT_SOURCE_DIR}/fuzz)
target_link_libraries(mjarm_fuzz_targets PUBLIC ${MJARM_FUZZ_LIBRARY})
set_target_properties(mjarm_fuzz_targets PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 0)

if(MJARM_FUZZ_PROGRAMS)
  foreach(source ${MJARM_FUZZ_TARGET_SOURCES})
    get_filename_component(name ${source} NAME_WE)
    string(REGEX REPLACE "_target$" "" name ${name})
    add_executable(fuzz_${name} ${PROJECT_SOURCE_DIR}/fuzz/libfuzzer_entry.cpp)
    target_compile_definitions(fuzz_${name} PRIVATE MJARM_FUZZ_TARGET=fuzz_${name})
    target_compile_options(fuzz_${name} PRIVATE ${MJARM_WARNINGS})
    target_link_libraries(fuzz_${name} PRIVATE mjarm_fuzz_targets)
    target_link_options(fuzz_${name} PRIVATE -fsanitize=fuzzer ${MJARM_FUZZ_LINK_OPTIONS})
    set_target_properties(fuzz_${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR})
  endforeach()
endif()
