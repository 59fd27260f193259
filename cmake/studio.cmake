# graftal studio: the server (src/studio/, on Debian's cpp-httplib) and its page (studio/,
# bundled by esbuild from the npm packages the committed package-lock.json pins). The page
# is built into share/graftal/studio beside the program, where `graftal studio` finds it.
pkg_check_modules(HTTPLIB IMPORTED_TARGET cpp-httplib)
if(NOT HTTPLIB_FOUND)
  message(FATAL_ERROR "graftal studio needs cpp-httplib: install Debian's libcpp-httplib-dev "
                      "(`make deps` does)")
endif()

# Static: linked into the program (and the tests), never installed on its own.
add_library(graftal_studio STATIC
  src/studio/studio_root.cpp
  src/studio/studio_model.cpp
  src/studio/studio_server.cpp
  src/studio/studio_guard.cpp
  src/studio/zip_archive.cpp
  src/studio/line_buffer.cpp)
set_target_properties(graftal_studio PROPERTIES POSITION_INDEPENDENT_CODE ON)
graftal_include_view(graftal_studio studio pipeline music maps output turtle rewrite lang geometry
  core)
target_compile_options(graftal_studio PRIVATE ${GRAFTAL_WARNINGS})
target_link_libraries(graftal_studio PUBLIC graftal_pipeline graftal_music nlohmann_json::nlohmann_json
  PRIVATE PkgConfig::HTTPLIB)

set(GRAFTAL_STUDIO_NODE ${CMAKE_BINARY_DIR}/studio-node)
set(GRAFTAL_STUDIO_PAGE ${CMAKE_BINARY_DIR}/share/graftal/studio)
find_program(GRAFTAL_NPM npm)
if(NOT GRAFTAL_NPM)
  message(WARNING "npm not found: the studio's page is not built (graftal studio serves its API "
                  "only). Install Node.js and npm (`make deps` does).")
  return()
endif()

# The packages of the lockfile, installed into the build folder (never the source tree).
set(studio_src ${CMAKE_CURRENT_SOURCE_DIR}/studio)
include(${CMAKE_CURRENT_SOURCE_DIR}/cmake/npm_install.cmake)
graftal_npm_ci(${studio_src} ${GRAFTAL_STUDIO_NODE} studio_npm_stamp)
# One target owns the install: the page and graftal.show()'s viewer both bundle from these
# packages, and two targets running one rule in parallel would race in the same folder.
add_custom_target(graftal_studio_npm DEPENDS ${studio_npm_stamp})

file(GLOB GRAFTAL_STUDIO_SOURCES CONFIGURE_DEPENDS ${studio_src}/src/*.js)
add_custom_command(
  OUTPUT ${GRAFTAL_STUDIO_PAGE}/studio.js ${GRAFTAL_STUDIO_PAGE}/index.html
         ${GRAFTAL_STUDIO_PAGE}/studio.css
  COMMAND ${CMAKE_COMMAND} -E make_directory ${GRAFTAL_STUDIO_PAGE}
  COMMAND ${CMAKE_COMMAND} -E env NODE_PATH=${GRAFTAL_STUDIO_NODE}/node_modules
          ${GRAFTAL_STUDIO_NODE}/node_modules/.bin/esbuild ${studio_src}/src/main.js --bundle
          --minify --format=esm --target=es2020 --log-level=warning
          --outfile=${GRAFTAL_STUDIO_PAGE}/studio.js
  COMMAND ${CMAKE_COMMAND} -E copy ${studio_src}/index.html ${studio_src}/studio.css
          ${GRAFTAL_STUDIO_PAGE}
  DEPENDS ${GRAFTAL_STUDIO_SOURCES} ${studio_src}/index.html ${studio_src}/studio.css
          ${studio_npm_stamp}
  COMMENT "Bundling the studio's page with esbuild")
add_custom_target(graftal_studio_page ALL
  DEPENDS ${GRAFTAL_STUDIO_PAGE}/studio.js ${GRAFTAL_STUDIO_PAGE}/index.html
          ${GRAFTAL_STUDIO_PAGE}/studio.css)
add_dependencies(graftal_studio_page graftal_studio_npm)
add_dependencies(graftal graftal_studio_page)
install(DIRECTORY ${GRAFTAL_STUDIO_PAGE}/ DESTINATION ${CMAKE_INSTALL_DATADIR}/graftal/studio)

# The browser tests: Debian's chromium driven by playwright-core (from the lockfile).
if(GRAFTAL_BUILD_TESTS)
  find_program(GRAFTAL_NODE node)
  foreach(test_file ${CMAKE_CURRENT_SOURCE_DIR}/studio/tests/studio.browser.mjs)
    add_test(NAME Studio.Browser
      COMMAND ${GRAFTAL_NODE} ${test_file}
      WORKING_DIRECTORY ${CMAKE_BINARY_DIR})
    set_tests_properties(Studio.Browser PROPERTIES
      ENVIRONMENT "GRAFTAL_EXE=$<TARGET_FILE:graftal>;GRAFTAL_STUDIO_NODE=${GRAFTAL_STUDIO_NODE};GRAFTAL_SOURCE_DIR=${CMAKE_CURRENT_SOURCE_DIR}"
      TIMEOUT 300 RUN_SERIAL TRUE SKIP_RETURN_CODE 77)
  endforeach()
endif()
