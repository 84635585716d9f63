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
# the consumer compiles with the compiler mjarm was built with (a sanitized mjarm's objects need
# that compiler's sanitizer runtimes)
run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/build -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX_COMPILER})
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
# every installed header is one of include/mjarm's: a room's private headers (src/<room>/) are not
# installed (the install may leave a part of include/mjarm out)
get_filename_component(public_dir ${SOURCE_DIR}/../../include ABSOLUTE)
file(GLOB_RECURSE public RELATIVE ${public_dir} ${public_dir}/mjarm/*)
file(GLOB_RECURSE installed RELATIVE ${WORK_DIR}/prefix/include ${WORK_DIR}/prefix/include/*)
set(extra ${installed})
if(public)
  list(REMOVE_ITEM extra ${public})
endif()
if(extra)
  message(FATAL_ERROR "installed headers that are not in include/mjarm: ${extra}")
endif()
if(NOT installed)
  message(FATAL_ERROR "no header was installed under ${WORK_DIR}/prefix/include")
endif()
