# The web build's tests (docs/web.md), run by ctest against what `make web` put in
# build/web (`make test` makes it first); each exits 77 (skipped) when it is not there.
if(NOT GRAFTAL_BUILD_TESTS)
  return()
endif()
find_program(GRAFTAL_NODE node)
set(GRAFTAL_WEB_OUTPUT ${CMAKE_BINARY_DIR}/web)
# The npm package under Node.js: strings equal to `graftal derive`'s on the examples.
add_test(NAME Web.Package
  COMMAND ${GRAFTAL_NODE} ${CMAKE_CURRENT_SOURCE_DIR}/web/tests/package.test.mjs)
# The static page in Debian's chromium, served by a plain static server.
add_test(NAME Web.Browser
  COMMAND ${GRAFTAL_NODE} ${CMAKE_CURRENT_SOURCE_DIR}/studio/tests/web.browser.mjs
  WORKING_DIRECTORY ${CMAKE_BINARY_DIR})
set_tests_properties(Web.Package Web.Browser PROPERTIES
  ENVIRONMENT "GRAFTAL_EXE=$<TARGET_FILE:graftal>;GRAFTAL_WEB=${GRAFTAL_WEB_OUTPUT};GRAFTAL_PACKAGE=${GRAFTAL_WEB_OUTPUT}/package;GRAFTAL_SOURCE_DIR=${CMAKE_CURRENT_SOURCE_DIR};GRAFTAL_TOOLS=${CMAKE_BINARY_DIR}/tools;GRAFTAL_STUDIO_NODE=${CMAKE_BINARY_DIR}/studio-node"
  TIMEOUT 600 SKIP_RETURN_CODE 77)
set_tests_properties(Web.Browser PROPERTIES RUN_SERIAL TRUE)
