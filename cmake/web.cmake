# The web build (docs/web.md): the engine compiled to WebAssembly by Debian's emscripten,
# configured with `emcmake cmake -DGRAFTAL_WEB=ON` (`make web` does). It compiles the
# layers that need no native library; the writers and tools that do (Cairo, Embree, giflib,
# libwebp, FFmpeg, libsmf, FluidSynth, LilyPond, meshoptimizer, mcpp, cpp-httplib) stay
# out, and their entry points are src/web/native_only.cpp, which says so in an Error. The
# export registry keeps its one table: its native rows throw that Error in this build.
if(NOT EMSCRIPTEN)
  message(FATAL_ERROR "GRAFTAL_WEB needs emscripten: configure with `emcmake cmake` "
                      "(make web does)")
endif()

# nlohmann/json is header-only: Debian's own headers, seen without the rest of /usr/include
# (whose glibc headers are not emscripten's).
set(GRAFTAL_WEB_JSON ${CMAKE_BINARY_DIR}/json-include)
file(MAKE_DIRECTORY ${GRAFTAL_WEB_JSON})
if(NOT EXISTS ${GRAFTAL_WEB_JSON}/nlohmann)
  find_path(GRAFTAL_JSON_DIR nlohmann/json.hpp PATHS /usr/include NO_CMAKE_FIND_ROOT_PATH)
  if(NOT GRAFTAL_JSON_DIR)
    message(FATAL_ERROR "nlohmann/json.hpp not found: install nlohmann-json3-dev")
  endif()
  file(CREATE_LINK ${GRAFTAL_JSON_DIR}/nlohmann ${GRAFTAL_WEB_JSON}/nlohmann SYMBOLIC)
endif()

set(GRAFTAL_WEB_SOURCES
  # core
  src/core/diagnostics.cpp src/core/module_string.cpp src/core/vec3.cpp src/core/rgb.cpp
  src/core/atomic_file.cpp src/core/destination.cpp src/core/file_format.cpp
  src/core/cancellation.cpp src/core/music_scale.cpp src/core/xml_text.cpp
  src/core/file_reading.cpp src/core/thread_pool.cpp src/core/number_chars.cpp
  src/core/freed_memory.cpp
  # lang (the limited preprocessor in place of mcpp)
  src/lang/expression_compiler.cpp src/lang/expression_vm.cpp src/lang/expression_builtins.cpp
  src/lang/expression_printf.cpp src/lang/source_text.cpp src/lang/module_lexer.cpp
  src/lang/parser.cpp src/lang/production_parser.cpp src/lang/statement_parser.cpp
  src/lang/view_parser.cpp src/lang/view_file.cpp src/lang/lsystem.cpp src/lang/model.cpp
  src/lang/model_builder.cpp src/lang/view_settings.cpp src/lang/view_setting_lookup.cpp
  src/lang/limited_preprocessor.cpp src/lang/graphical_function.cpp src/lang/vlab_specifications.cpp
  src/lang/contour_file.cpp src/lang/curve_xyz.cpp src/lang/curve_setting.cpp
  # rewrite
  src/rewrite/bracket_index.cpp src/rewrite/rewriting_engine.cpp
  src/rewrite/rewriting_generic.cpp src/rewrite/context_rewriter.cpp
  src/rewrite/derivation.cpp src/rewrite/growth_prediction.cpp src/rewrite/streaming.cpp
  src/rewrite/output_files.cpp src/rewrite/environment.cpp
  src/rewrite/environment_obstacles.cpp src/rewrite/environment_occupancy.cpp
  src/rewrite/environment_process.cpp src/rewrite/streamed_runs.cpp
  src/rewrite/parallel_stream.cpp
  # geometry
  src/geometry/scene.cpp src/geometry/kolam_dots.cpp src/geometry/mesh.cpp
  src/geometry/mesh_scene.cpp src/geometry/mesh_scene_builder.cpp
  src/geometry/surface_mesher.cpp src/geometry/polygon_instancing.cpp
  src/geometry/tube_mesher.cpp src/geometry/polygon_triangulation.cpp
  src/geometry/surface_file.cpp src/geometry/bezier_patch.cpp src/geometry/bspline.cpp
  src/geometry/color_map.cpp src/geometry/material_file.cpp src/geometry/projection.cpp
  src/geometry/round_shapes.cpp src/geometry/contour_points.cpp
  src/geometry/generalized_cylinder.cpp
  # maps
  src/maps/map_parser.cpp src/maps/map_derivation.cpp src/maps/map_relaxation.cpp
  src/maps/map_outline.cpp src/maps/map_checks.cpp src/maps/map_text.cpp
  src/maps/map_drawing.cpp
  # turtle
  src/turtle/turtle.cpp src/turtle/streamed_interpretation.cpp
  src/turtle/subtree_summaries.cpp src/turtle/planar_measure.cpp
  src/turtle/polyline_turtle.cpp src/turtle/d0l_measure.cpp
  # output: SVG, OBJ, PLY, glTF (no Cairo, Embree, encoders)
  src/output/image_transform.cpp src/output/svg_writer.cpp src/output/derivation_diagram.cpp
  src/output/obj_writer.cpp src/output/ply_writer.cpp src/output/gltf_writer.cpp
  src/output/mesh_scene_writers.cpp src/output/glb_builder.cpp
  src/output/instance_transform.cpp src/output/image_file.cpp
  src/output/string_text_writer.cpp src/output/string_json_writer.cpp
  # music: the score and its text notations
  src/music/score.cpp src/music/notation.cpp src/music/musicxml_writer.cpp
  # pipeline
  src/pipeline/stream_choice.cpp src/pipeline/stages.cpp src/pipeline/statistics.cpp
  src/pipeline/export_registry.cpp src/pipeline/render.cpp src/pipeline/module_ages.cpp
  src/pipeline/mesh_quality.cpp src/pipeline/string_export.cpp
  # the studio's computations (no server)
  src/studio/studio_model.cpp src/studio/line_buffer.cpp src/studio/zip_archive.cpp
  # the web front end
  src/web/native_only.cpp src/web/engine.cpp)

# The library's sources the web build leaves out, each for the native library it needs (or,
# for the preprocessor, mcpp: the web build has src/lang/limited_preprocessor.cpp). Every
# source of the layers is in one list or the other: scripts/web_sources.py checks it
# (ctest: Web.SourceList), so that a new source file is not forgotten here.
set(GRAFTAL_NATIVE_ONLY_SOURCES
  src/lang/preprocessor.cpp src/lang/mcpp_server.cpp src/lang/graftal_cpp_main.cpp
  src/music/lilypond_writer.cpp src/music/midi_writer.cpp src/music/music_file.cpp
  src/music/wav_writer.cpp
  src/output/animation_file.cpp src/output/cairo_writer.cpp
  src/output/derivation_diagram_writer.cpp src/output/derivation_diagram_cairo.cpp
  src/output/gif_encoder.cpp src/output/mp4_encoder.cpp
  src/output/png_frames_encoder.cpp src/output/png_encoder.cpp src/output/raytrace_camera.cpp
  src/output/raytrace_renderer.cpp src/output/raytrace_scene.cpp src/output/raytrace_shading.cpp
  src/output/streamed_picture.cpp src/output/streamed_png.cpp src/output/webp_encoder.cpp
  src/pipeline/animation.cpp)

# Speed first (-O2: the rewriting loops are 5-20 times faster than with -Oz, and the .wasm
# stays under 600 KB gzip-compressed), WebAssembly's own exceptions (emscripten's JavaScript
# ones route every call that may throw through JavaScript), SIMD and bulk memory (memcpy
# and memset as single instructions). Node.js 18+ and browsers since 2021-22 run them.
set(GRAFTAL_WEB_FLAGS -fwasm-exceptions -O2 -msimd128 -mbulk-memory)
# What runs once a call (parsing the model's text, the JSON answers, the writers, the maps'
# and the music's code) at -Os: a smaller .wasm, and a browser's optimizing compiler, which
# recompiles a function once its loops turn hot, has smaller functions to recompile (at -O2
# the preprocessor and the studio's picture were functions of 15-20 KB, each 0.2-0.4 s of
# the optimizing compiler while the page's first picture is on its way). The loops that
# carry a derivation (rewrite, turtle, geometry, the module string, expressions, the line
# buffer, and the engine's entry points, which hand strings and arrays to JavaScript) stay at
# -O2. The -O2 objects are linked first: a function that both kinds of object hold (the
# standard library's templates) is taken from the first, so that the loops never call an
# -Os copy of, say, a vector's destructor (which made releasing a string 40 times slower).
set(GRAFTAL_WEB_HOT_SOURCES
  src/core/module_string.cpp src/core/number_chars.cpp src/lang/expression_vm.cpp
  src/lang/expression_builtins.cpp src/studio/line_buffer.cpp src/web/engine.cpp)
set(GRAFTAL_WEB_COLD_SOURCES ${GRAFTAL_WEB_SOURCES})
list(FILTER GRAFTAL_WEB_COLD_SOURCES INCLUDE REGEX
     "^src/(core|lang|maps|music|output|pipeline|studio|web)/")
list(REMOVE_ITEM GRAFTAL_WEB_COLD_SOURCES ${GRAFTAL_WEB_HOT_SOURCES})
set_property(SOURCE ${GRAFTAL_WEB_COLD_SOURCES} APPEND PROPERTY COMPILE_OPTIONS -Os)
set(GRAFTAL_WEB_LINK_ORDER ${GRAFTAL_WEB_SOURCES})
list(REMOVE_ITEM GRAFTAL_WEB_LINK_ORDER ${GRAFTAL_WEB_COLD_SOURCES})
add_executable(graftal_engine ${GRAFTAL_WEB_LINK_ORDER} ${GRAFTAL_WEB_COLD_SOURCES})
target_include_directories(graftal_engine PRIVATE include src)
target_include_directories(graftal_engine SYSTEM PRIVATE ${GRAFTAL_WEB_JSON})
target_compile_definitions(graftal_engine PRIVATE GRAFTAL_NO_MCPP GRAFTAL_NO_MESHOPTIMIZER
  GRAFTAL_SURFACES_FROM_LIBDIR="" GRAFTAL_SURFACES_FROM_BINDIR="")
set_source_files_properties(src/geometry/surface_file.cpp PROPERTIES
  COMPILE_DEFINITIONS GRAFTAL_BUILTIN_SURFACES_DIR="/graftal/surfaces")
target_compile_options(graftal_engine PRIVATE ${GRAFTAL_WARNINGS} ${GRAFTAL_WEB_FLAGS})
set_target_properties(graftal_engine PROPERTIES OUTPUT_NAME graftal-engine SUFFIX ".js"
  RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/engine)
# An ES module exporting a factory; the package and the page hand it the .wasm's bytes
# (web/src/load.js), so the same file loads in Node.js and in a browser's worker.
target_link_options(graftal_engine PRIVATE ${GRAFTAL_WEB_FLAGS} --bind
  -sMODULARIZE=1 -sEXPORT_ES6=1 -sEXPORT_NAME=createGraftalEngine
  -sENVIRONMENT=web,worker -sALLOW_MEMORY_GROWTH=1 -sMAXIMUM_MEMORY=4GB
  -sINITIAL_MEMORY=32MB -sFILESYSTEM=1
  # The built-in surfaces (leaf, petal), in the module's memory file system.
  --embed-file ${CMAKE_CURRENT_SOURCE_DIR}/surfaces@/graftal/surfaces)

# ---- the npm package and the static page ----------------------------------------------
# GRAFTAL_WEB_OUTPUT (build/web from `make web`): the page, and the package in package/.
if(NOT GRAFTAL_WEB_OUTPUT)
  set(GRAFTAL_WEB_OUTPUT ${CMAKE_BINARY_DIR}/web)
endif()
find_program(GRAFTAL_NODE node NO_CMAKE_FIND_ROOT_PATH)
find_program(GRAFTAL_NPM npm NO_CMAKE_FIND_ROOT_PATH)
if(NOT GRAFTAL_NODE OR NOT GRAFTAL_NPM)
  message(FATAL_ERROR "the web build's page needs Node.js and npm (`make deps` installs them)")
endif()

# The studio's npm packages (its lockfile), for esbuild and the page's libraries.
set(GRAFTAL_WEB_NODE ${CMAKE_BINARY_DIR}/studio-node)
set(studio_src ${CMAKE_CURRENT_SOURCE_DIR}/studio)
include(${CMAKE_CURRENT_SOURCE_DIR}/cmake/npm_install.cmake)
graftal_npm_ci(${studio_src} ${GRAFTAL_WEB_NODE} web_npm_stamp)

# The worker imports the package by its name: `graftal` is the assembled package.
set(GRAFTAL_WEB_MODULES ${CMAKE_BINARY_DIR}/web-modules)
file(MAKE_DIRECTORY ${GRAFTAL_WEB_MODULES} ${GRAFTAL_WEB_OUTPUT}/package)
file(REMOVE ${GRAFTAL_WEB_MODULES}/graftal)
file(CREATE_LINK ${GRAFTAL_WEB_OUTPUT}/package ${GRAFTAL_WEB_MODULES}/graftal SYMBOLIC)

file(GLOB GRAFTAL_STUDIO_SOURCES CONFIGURE_DEPENDS ${studio_src}/src/*.js)
file(GLOB GRAFTAL_EXAMPLES CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/examples/*.l)
set(esbuild ${CMAKE_COMMAND} -E env
  NODE_PATH=${GRAFTAL_WEB_NODE}/node_modules:${GRAFTAL_WEB_MODULES}
  ${GRAFTAL_WEB_NODE}/node_modules/.bin/esbuild --bundle --minify --format=esm
  --log-level=warning)
add_custom_command(
  OUTPUT ${GRAFTAL_WEB_OUTPUT}/index.html ${GRAFTAL_WEB_OUTPUT}/studio.js
         ${GRAFTAL_WEB_OUTPUT}/worker.js ${GRAFTAL_WEB_OUTPUT}/package/index.js
  COMMAND ${GRAFTAL_NODE} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/web_page.mjs
          ${CMAKE_CURRENT_SOURCE_DIR} $<TARGET_FILE_DIR:graftal_engine> ${GRAFTAL_WEB_OUTPUT}
  # The 3D view (three.js) in a chunk of its own, loaded when it is first shown.
  COMMAND ${CMAKE_COMMAND} -E rm -rf ${GRAFTAL_WEB_OUTPUT}/chunks
  COMMAND ${esbuild} studio=${studio_src}/src/main.js --target=es2020 --splitting
          --chunk-names=chunks/[name]-[hash] --outdir=${GRAFTAL_WEB_OUTPUT}
  COMMAND ${GRAFTAL_NODE} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/web_page.mjs --preload
          ${GRAFTAL_WEB_OUTPUT}
  # The worker awaits the engine at its top level (ES2022).
  # (its Node.js branch, which reads the .wasm from disk, is left to Node.js)
  COMMAND ${esbuild} ${studio_src}/src/worker.js --target=es2022 --external:node:*
          --outfile=${GRAFTAL_WEB_OUTPUT}/worker.js
  DEPENDS graftal_engine ${GRAFTAL_STUDIO_SOURCES} ${studio_src}/index.html
          ${studio_src}/studio.css ${GRAFTAL_EXAMPLES} ${web_npm_stamp}
          ${CMAKE_CURRENT_SOURCE_DIR}/scripts/web_page.mjs
          ${CMAKE_CURRENT_SOURCE_DIR}/web/index.js ${CMAKE_CURRENT_SOURCE_DIR}/web/engine.js
          ${CMAKE_CURRENT_SOURCE_DIR}/web/index.d.ts
          ${CMAKE_CURRENT_SOURCE_DIR}/web/package.json ${CMAKE_CURRENT_SOURCE_DIR}/web/README.md
  COMMENT "Assembling the npm package and the static studio page in ${GRAFTAL_WEB_OUTPUT}")
add_custom_target(graftal_web_page ALL DEPENDS ${GRAFTAL_WEB_OUTPUT}/index.html)
