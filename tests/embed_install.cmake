# ctest Install.EmbedExample: installs the build into BUILD_DIR/stage, builds examples/embed
# against it twice (find_package(graftal), then `pkg-config --cflags --libs graftal`), runs
# each build on a 3D plant with built-in leaf surfaces and checks the PNG is not blank.
# Arguments: BUILD_DIR SOURCE_DIR CXX GENERATOR PNG_CHECK.
set(stage ${BUILD_DIR}/stage)
set(work ${BUILD_DIR}/embed-test)
set(plant ${SOURCE_DIR}/examples/fig4.1-generic-plant.l)
file(REMOVE_RECURSE ${stage} ${work})
file(MAKE_DIRECTORY ${work})

function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    list(JOIN ARGN " " command)
    message(FATAL_ERROR "failed (${rc}): ${command}\n${out}\n${err}")
  endif()
  message(STATUS "${out}")
endfunction()

function(check_png png)
  if(NOT EXISTS ${png})
    message(FATAL_ERROR "${png} was not written")
  endif()
  run(${PNG_CHECK} ${png})
endfunction()

run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${stage})
foreach(installed include/graftal/pipeline/pipeline.hpp share/graftal/surfaces/leaf.s bin/graftal)
  if(NOT EXISTS ${stage}/${installed})
    message(FATAL_ERROR "the install has no ${installed}")
  endif()
endforeach()
file(GLOB_RECURSE config ${stage}/*/graftalConfig.cmake)
file(GLOB_RECURSE pc ${stage}/*/graftal.pc)
if(NOT config OR NOT pc)
  message(FATAL_ERROR "the install has no graftalConfig.cmake or graftal.pc")
endif()

# The installed program is used from the stage, with no path back to the build tree.
run(${stage}/bin/graftal render ${plant} -o ${work}/cli.png --size 160x160)
check_png(${work}/cli.png)

# find_package(graftal)
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/embed -B ${work}/cmake-build -G ${GENERATOR}
    -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_PREFIX_PATH=${stage} -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${work}/cmake-build)
run(${work}/cmake-build/embed ${plant} ${work}/find_package.png)
check_png(${work}/find_package.png)

# pkg-config
get_filename_component(pcdir ${pc} DIRECTORY)
set(ENV{PKG_CONFIG_PATH} ${pcdir})
execute_process(COMMAND pkg-config --cflags --libs graftal RESULT_VARIABLE rc
                OUTPUT_VARIABLE flags OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pkg-config --cflags --libs graftal failed")
endif()
separate_arguments(flags UNIX_COMMAND "${flags}")
get_filename_component(libdir ${pcdir} DIRECTORY)
run(${CXX} -std=c++20 ${SOURCE_DIR}/examples/embed/embed.cpp -o ${work}/embed-pc ${flags}
    -Wl,-rpath,${libdir})
run(${work}/embed-pc ${plant} ${work}/pkg-config.png)
check_png(${work}/pkg-config.png)

# A bad file: a clear error and no picture.
file(WRITE ${work}/bad.l "Lsystem: bad\naxiom: F(\n")
execute_process(COMMAND ${work}/embed-pc ${work}/bad.l ${work}/bad.png RESULT_VARIABLE rc
                ERROR_VARIABLE err)
if(rc EQUAL 0 OR EXISTS ${work}/bad.png OR NOT err MATCHES "bad.l:2")
  message(FATAL_ERROR "a bad file should fail naming bad.l:2 and write nothing: ${rc} ${err}")
endif()
