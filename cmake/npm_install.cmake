# One rule that installs the npm packages of a committed lockfile into a folder of the build
# tree (never the source tree), shared by the studio's build (cmake/studio.cmake) and the
# web build (cmake/web.cmake), which are separate CMake projects.
#
#   graftal_npm_ci(SOURCE_DIR INTO_DIR STAMP_VAR)
#
# copies SOURCE_DIR's package.json and package-lock.json into INTO_DIR, runs `npm ci` there
# when either changes, and sets STAMP_VAR in the caller to the stamp file that rule makes:
# whatever needs the packages depends on that file. Only one target may depend on it
# directly if several could build in parallel (two runs of one rule would race in INTO_DIR).
function(graftal_npm_ci source_dir into_dir stamp_var)
  if(NOT GRAFTAL_NPM)
    message(FATAL_ERROR "graftal_npm_ci: GRAFTAL_NPM (the npm program) is not set")
  endif()
  # The command runs inside this folder, so it must exist before the first build.
  file(MAKE_DIRECTORY ${into_dir})
  add_custom_command(
    OUTPUT ${into_dir}/npm-ci.stamp
    COMMAND ${CMAKE_COMMAND} -E copy ${source_dir}/package.json ${source_dir}/package-lock.json
            ${into_dir}
    COMMAND ${GRAFTAL_NPM} ci --no-audit --no-fund --loglevel=error
    COMMAND ${CMAKE_COMMAND} -E touch ${into_dir}/npm-ci.stamp
    WORKING_DIRECTORY ${into_dir}
    DEPENDS ${source_dir}/package.json ${source_dir}/package-lock.json
    COMMENT "Installing the npm packages of ${source_dir}/package-lock.json")
  set(${stamp_var} ${into_dir}/npm-ci.stamp PARENT_SCOPE)
endfunction()
