# Shared by the install tests: install glintlab from BUILD_DIR into WORK/prefix (WORK emptied first),
# then configure and build the project at `source` into WORK/build against that install only
# (CMAKE_PREFIX_PATH), with any extra cache arguments. Stops the test with `what` named on failure.
function(install_and_build source what)
  file(REMOVE_RECURSE "${WORK}")
  file(MAKE_DIRECTORY "${WORK}")
  execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${WORK}/prefix"
                  RESULT_VARIABLE r OUTPUT_QUIET)
  if(r)
    message(FATAL_ERROR "install failed: ${r}")
  endif()
  # The build tree's compiler launcher (the compiler cache, cmake/glintlabCcache.cmake), given
  # as LAUNCHER with | between its words: the project's own units then hit the cache of an
  # earlier run.
  # (One quoted argument: its value is a list.)
  set(launcher -UCMAKE_CXX_COMPILER_LAUNCHER)
  if(LAUNCHER)
    string(REPLACE "|" ";" words "${LAUNCHER}")
    set(launcher "-DCMAKE_CXX_COMPILER_LAUNCHER=${words}")
  endif()
  execute_process(COMMAND "${CMAKE_COMMAND}" -S "${source}" -B "${WORK}/build" -G Ninja
                          -DCMAKE_PREFIX_PATH=${WORK}/prefix "${launcher}" ${ARGN}
                  RESULT_VARIABLE r OUTPUT_QUIET)
  if(r)
    message(FATAL_ERROR "${what} configure failed: ${r}")
  endif()
  execute_process(COMMAND "${CMAKE_COMMAND}" --build "${WORK}/build" RESULT_VARIABLE r)
  if(r)
    message(FATAL_ERROR "${what} build failed: ${r}")
  endif()
endfunction()
