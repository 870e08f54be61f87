# ctest script: install glintlab into a scratch prefix, then configure, build and run a consumer
# project that finds it with find_package(glintlab).
include("${CMAKE_CURRENT_LIST_DIR}/install_and_build.cmake")
install_and_build("${SOURCE}" "consumer")
execute_process(COMMAND "${WORK}/build/consumer" RESULT_VARIABLE r)
if(r)
  message(FATAL_ERROR "consumer run failed: ${r}")
endif()
