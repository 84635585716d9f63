# Installs the build tree into a scratch prefix, then configures, builds and runs the consumer
# project against it, and checks that the installed CLI finds the installed models. Any failing
# step fails the test.
file(REMOVE_RECURSE ${WORK_DIR})
function(run)
  execute_process(COMMAND ${ARGV} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGV}")
  endif()
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/build -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix
    -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${CMAKE_COMMAND} -E env MJARM_MODELS=${WORK_DIR}/prefix/share/mjarm/models ${WORK_DIR}/build/consumer)
# the installed CLI finds the installed models relative to itself: the scratch prefix is not the
# configured one, and the source tree's models would be found otherwise
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=MJARM_MODELS ${WORK_DIR}/prefix/bin/mjarm
                        info --list --json
                RESULT_VARIABLE rc OUTPUT_VARIABLE listing)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "failed (${rc}): the installed mjarm info --list --json")
endif()
string(JSON models_dir GET "${listing}" models_dir)
if(NOT models_dir STREQUAL "${WORK_DIR}/prefix/share/mjarm/models")
  message(FATAL_ERROR "the installed CLI's models are '${models_dir}', not the install's "
                      "'${WORK_DIR}/prefix/share/mjarm/models'")
endif()
# the installed headers are the public ones, include/mjarm, and no more: a room's private headers
# (src/<room>/) are not installed
get_filename_component(public_dir ${SOURCE_DIR}/../../include ABSOLUTE)
file(GLOB_RECURSE public RELATIVE ${public_dir} ${public_dir}/mjarm/*)
file(GLOB_RECURSE installed RELATIVE ${WORK_DIR}/prefix/include ${WORK_DIR}/prefix/include/*)
list(SORT public)
list(SORT installed)
if(NOT installed STREQUAL public)
  set(extra ${installed})
  list(REMOVE_ITEM extra ${public})
  set(missing ${public})
  list(REMOVE_ITEM missing ${installed})
  message(FATAL_ERROR "the installed headers are not include/mjarm's: installed but not public: "
                      "${extra}; public but not installed: ${missing}")
endif()
