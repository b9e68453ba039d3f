# Installs web/node_modules from the committed package-lock.json with
# `npm ci`, only when node_modules is missing or older than the lock file.
# Usage: cmake -DWEB_DIR=<web> -DNPM=<npm> -DSTAMP=<file> -P npm_ci.cmake
set(installed "${WEB_DIR}/node_modules/.package-lock.json")
if(NOT EXISTS "${installed}" OR "${WEB_DIR}/package-lock.json" IS_NEWER_THAN "${installed}")
  message(STATUS "web: npm ci (installing three.js, esbuild, playwright-core into web/node_modules)")
  execute_process(COMMAND "${NPM}" ci --no-audit --no-fund --ignore-scripts WORKING_DIRECTORY "${WEB_DIR}" RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "web: 'npm ci' failed in ${WEB_DIR} (exit ${rc}); the npm registry must be reachable")
  endif()
endif()
file(TOUCH "${STAMP}")
