# ctest script: install glintlab into a scratch prefix, then configure, build and run a consumer
# project that finds it with find_package(glintlab).
include("${CMAKE_CURRENT_LIST_DIR}/install_and_build.cmake")
install_and_build("${SOURCE}" "consumer")
execute_process(COMMAND "${WORK}/build/consumer" RESULT_VARIABLE r)
if(r)
  message(FATAL_ERROR "consumer run failed: ${r}")
endif()

# Without the library's dependencies (as on a machine without OpenEXR's, PNG's and TBB's
# development packages): find_package(glintlab) still succeeds with glintlab::headers alone, and
# `COMPONENTS core` fails naming what is missing.
set(no_core_deps -DCMAKE_DISABLE_FIND_PACKAGE_OpenEXR=TRUE -DCMAKE_DISABLE_FIND_PACKAGE_PNG=TRUE
                 -DCMAKE_DISABLE_FIND_PACKAGE_TBB=TRUE)
file(MAKE_DIRECTORY "${WORK}/no_core")
file(WRITE "${WORK}/no_core/CMakeLists.txt" "cmake_minimum_required(VERSION 3.25)
project(no_core LANGUAGES CXX)
find_package(glintlab REQUIRED \${COMPONENTS})
if(TARGET glintlab::core OR NOT TARGET glintlab::headers OR NOT COMMAND glintlab_add_model_plugin)
  message(FATAL_ERROR \"expected glintlab::headers and glintlab_add_model_plugin, no glintlab::core\")
endif()
")
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${WORK}/no_core" -B "${WORK}/no_core/build"
                        -DCMAKE_PREFIX_PATH=${WORK}/prefix ${no_core_deps}
                RESULT_VARIABLE r OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(r OR NOT out MATCHES "glintlab::core needs OpenEXR;PNG;TBB, not found")
  message(FATAL_ERROR "headers-only find_package failed (${r}):\n${out}\n${err}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${WORK}/no_core" -B "${WORK}/no_core/build_core"
                        -DCMAKE_PREFIX_PATH=${WORK}/prefix ${no_core_deps} -DCOMPONENTS=COMPONENTS\;core
                RESULT_VARIABLE r OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT r OR NOT err MATCHES "glintlab::core needs OpenEXR;PNG;TBB, not found")
  message(FATAL_ERROR "COMPONENTS core without its dependencies was accepted (${r}):\n${out}\n${err}")
endif()
