# The Python module (docs/python.md): the bindings (src/python/, pybind11) built as
# graftal/_graftal*.so beside the package's pure-Python files (python/graftal/) in
# build/python, so that `PYTHONPATH=build/python /usr/bin/python3 -c 'import graftal'` works
# after `make`, and installed into the prefix's lib/python3/dist-packages. Built against
# Debian's python3, python3-numpy and pybind11-dev (the Makefile installs them); without
# them the rest of graftal builds and the module is left out, with a warning.
option(GRAFTAL_PYTHON "Build the Python module" ON)
if(NOT GRAFTAL_PYTHON)
  return()
endif()

# Debian's interpreter: the one whose python3-numpy and dist-packages the module is for,
# whatever other python3 comes first on PATH.
if(NOT Python_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python_EXECUTABLE /usr/bin/python3)
endif()
set(PYBIND11_FINDPYTHON ON)
find_package(Python COMPONENTS Interpreter Development.Module NumPy QUIET)
find_package(pybind11 CONFIG QUIET)
if(NOT Python_FOUND OR NOT Python_NumPy_FOUND OR NOT pybind11_FOUND)
  message(WARNING "the Python module is not built: install python3-dev, python3-numpy and "
                  "pybind11-dev (`make deps` does)")
  return()
endif()

set(GRAFTAL_PYTHON_DIR ${CMAKE_BINARY_DIR}/python)
set(GRAFTAL_PYTHON_INSTALL_DIR lib/python3/dist-packages CACHE STRING
    "Where `cmake --install` puts the Python package, relative to the prefix")

pybind11_add_module(graftal_python MODULE NO_EXTRAS
  src/python/module.cpp
  src/python/errors.cpp
  src/python/requests.cpp
  src/python/model_binding.cpp
  src/python/module_string_binding.cpp
  src/python/derivation_binding.cpp
  src/python/geometry_binding.cpp
  src/python/environment_binding.cpp
  src/python/functions_binding.cpp
  src/python/map_binding.cpp)
set_target_properties(graftal_python PROPERTIES
  OUTPUT_NAME _graftal
  LIBRARY_OUTPUT_DIRECTORY ${GRAFTAL_PYTHON_DIR}/graftal)
graftal_include_view(graftal_python pipeline music maps output turtle rewrite lang geometry core)
target_compile_options(graftal_python PRIVATE ${GRAFTAL_WARNINGS})
target_link_libraries(graftal_python PRIVATE graftal_pipeline graftal_music graftal_maps
  graftal_output graftal_turtle graftal_geometry graftal_rewrite graftal_lang graftal_core
  Python::NumPy)

# The package's Python files are linked into the build folder, so that an edit shows at once.
file(GLOB GRAFTAL_PYTHON_FILES CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/python/graftal/*.py
     ${CMAKE_CURRENT_SOURCE_DIR}/python/graftal/*.pyi
     ${CMAKE_CURRENT_SOURCE_DIR}/python/graftal/py.typed)
file(MAKE_DIRECTORY ${GRAFTAL_PYTHON_DIR}/graftal)
foreach(file ${GRAFTAL_PYTHON_FILES})
  get_filename_component(name ${file} NAME)
  if(NOT EXISTS ${GRAFTAL_PYTHON_DIR}/graftal/${name})
    file(CREATE_LINK ${file} ${GRAFTAL_PYTHON_DIR}/graftal/${name} SYMBOLIC)
  endif()
endforeach()

# graftal.show()'s viewer: the studio's three.js view (studio/src/view3d.js) bundled with
# its npm packages (build/studio-node, from the studio's lockfile) into one script the
# package embeds in a notebook's output, so that it works offline.
if(TARGET graftal_studio_page)
  set(viewer_js ${GRAFTAL_PYTHON_DIR}/graftal/viewer.js)
  add_custom_command(
    OUTPUT ${viewer_js}
    COMMAND ${CMAKE_COMMAND} -E env NODE_PATH=${GRAFTAL_STUDIO_NODE}/node_modules
            ${GRAFTAL_STUDIO_NODE}/node_modules/.bin/esbuild
            ${CMAKE_CURRENT_SOURCE_DIR}/src/python/viewer.js --bundle --minify --format=iife
            --global-name=graftalViewer --target=es2020 --log-level=warning
            --outfile=${viewer_js}
    DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/python/viewer.js
            ${CMAKE_CURRENT_SOURCE_DIR}/studio/src/view3d.js
            ${CMAKE_CURRENT_SOURCE_DIR}/studio/src/api.js ${GRAFTAL_STUDIO_NODE}/npm-ci.stamp
    COMMENT "Bundling graftal.show()'s 3D viewer with esbuild")
  add_custom_target(graftal_python_viewer ALL DEPENDS ${viewer_js})
  add_dependencies(graftal_python_viewer graftal_studio_npm)
  add_dependencies(graftal_python graftal_python_viewer)
  install(FILES ${viewer_js} DESTINATION ${GRAFTAL_PYTHON_INSTALL_DIR}/graftal)
endif()

# Installed, the module finds the layers' libraries from its own folder.
file(RELATIVE_PATH GRAFTAL_PYTHON_TO_LIB "/p/${GRAFTAL_PYTHON_INSTALL_DIR}/graftal"
     "/p/${CMAKE_INSTALL_LIBDIR}")
set_target_properties(graftal_python PROPERTIES INSTALL_RPATH "$ORIGIN/${GRAFTAL_PYTHON_TO_LIB}")
install(TARGETS graftal_python LIBRARY DESTINATION ${GRAFTAL_PYTHON_INSTALL_DIR}/graftal)
install(FILES ${GRAFTAL_PYTHON_FILES} DESTINATION ${GRAFTAL_PYTHON_INSTALL_DIR}/graftal)

# The Python tests (tests/python/, pytest) run by ctest against the module of this build, one
# ctest test per file (Python.model, Python.sweep, ...) so that `ctest -j` runs them side by
# side.
if(GRAFTAL_BUILD_TESTS)
  file(GLOB GRAFTAL_PYTHON_TESTS CONFIGURE_DEPENDS
       ${CMAKE_CURRENT_SOURCE_DIR}/tests/python/test_*.py)
  foreach(test_file ${GRAFTAL_PYTHON_TESTS})
    get_filename_component(name ${test_file} NAME_WE)
    string(REGEX REPLACE "^test_" "" name ${name})
    add_test(NAME Python.${name}
      COMMAND ${Python_EXECUTABLE} -m pytest -q -p no:cacheprovider ${test_file}
      WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR})
    set_tests_properties(Python.${name} PROPERTIES
      ENVIRONMENT "PYTHONPATH=${GRAFTAL_PYTHON_DIR};GRAFTAL_EXE=$<TARGET_FILE:graftal>;GRAFTAL_BUILD_DIR=${CMAKE_BINARY_DIR};PYTHONDONTWRITEBYTECODE=1"
      TIMEOUT 300)
  endforeach()
endif()
