# `npm ci` of the replay page's packages (web/package-lock.json) into the build tree, skipped when
# node_modules was installed from this very lock (its hash in node_modules/.mjarm-lock-sha256):
# a rebuild, offline, installs nothing. Run by cmake -P with NPM, SOURCE (web/) and DIR (the
# build tree's web/).
file(SHA256 "${SOURCE}/package-lock.json" lock_hash)
set(stamp "${DIR}/node_modules/.mjarm-lock-sha256")
if(EXISTS "${stamp}")
  file(READ "${stamp}" installed_hash)
  if(installed_hash STREQUAL lock_hash)
    return()
  endif()
endif()
file(MAKE_DIRECTORY "${DIR}")
configure_file("${SOURCE}/package.json" "${DIR}/package.json" COPYONLY)
configure_file("${SOURCE}/package-lock.json" "${DIR}/package-lock.json" COPYONLY)
# --prefer-offline: npm's cache answers before the registry; --ignore-scripts: no package runs
# code at install (esbuild's binary comes as its platform package)
execute_process(COMMAND "${NPM}" ci --prefer-offline --ignore-scripts --no-audit --no-fund
                WORKING_DIRECTORY "${DIR}" RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "npm ci of web/package-lock.json failed (${result}): the replay page's "
                      "packages come from the npm registry, or configure with -DMJARM_WEB=OFF")
endif()
file(WRITE "${stamp}" "${lock_hash}")
