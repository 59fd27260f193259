# `cmake --install build --prefix P`: the layers' libraries, the public headers, the
# built-in surfaces, the graftal program, a CMake package (find_package(graftal) ->
# graftal::graftal) and a pkg-config file (graftal.pc).
include(CMakePackageConfigHelpers)

set(GRAFTAL_LAYERS graftal_core graftal_lang graftal_rewrite graftal_geometry graftal_turtle
    graftal_output graftal_pipeline graftal_music graftal_maps)

install(TARGETS ${GRAFTAL_LAYERS} graftal_lib
        EXPORT graftalTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS graftal RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# One folder per layer; the studio's headers serve the program only.
install(DIRECTORY include/graftal DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.hpp" PATTERN "studio" EXCLUDE)
install(DIRECTORY surfaces/ DESTINATION ${CMAKE_INSTALL_DATADIR}/graftal/surfaces
        FILES_MATCHING PATTERN "*.s")

set(GRAFTAL_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/graftal)
install(EXPORT graftalTargets NAMESPACE graftal:: DESTINATION ${GRAFTAL_CMAKE_DIR})
# Static layers carry their private dependencies into the program that links them.
get_target_property(GRAFTAL_OUTPUT_TYPE graftal_output TYPE)
if(GRAFTAL_OUTPUT_TYPE STREQUAL "STATIC_LIBRARY")
  set(GRAFTAL_STATIC ON)
else()
  set(GRAFTAL_STATIC OFF)
endif()
configure_package_config_file(cmake/graftalConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/graftalConfig.cmake INSTALL_DESTINATION ${GRAFTAL_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/graftalConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/graftalConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/graftalConfigVersion.cmake
        DESTINATION ${GRAFTAL_CMAKE_DIR})

# graftal.pc: prefix-relative paths, so that a staged or moved install still works.
file(RELATIVE_PATH GRAFTAL_PC_TO_PREFIX "/p/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/p")
string(REGEX REPLACE "/$" "" GRAFTAL_PC_TO_PREFIX "${GRAFTAL_PC_TO_PREFIX}")
set(GRAFTAL_PC_LIBS "")
foreach(layer graftal_maps graftal_music graftal_pipeline graftal_output graftal_turtle
        graftal_rewrite graftal_geometry graftal_lang graftal_core)
  string(APPEND GRAFTAL_PC_LIBS " -l${layer}")
endforeach()
if(GRAFTAL_STATIC)
  set(GRAFTAL_PC_REQUIRES_PRIVATE "cairo smf fluidsynth")
  set(GRAFTAL_PC_LIBS_PRIVATE "-lembree3 -lmcpp ${CMAKE_DL_LIBS}")
else()
  set(GRAFTAL_PC_REQUIRES_PRIVATE "")
  set(GRAFTAL_PC_LIBS_PRIVATE "")
endif()
configure_file(cmake/graftal.pc.in ${CMAKE_CURRENT_BINARY_DIR}/graftal.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/graftal.pc
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
