# Every test of the build tree carries exactly one tier label, fast or slow (test_tiers.cmake and
# tests/CMakeLists.txt), every test labelled power is slow, and every entry of test_tiers.cmake's
# lists names a test. Run: cmake -DCTEST=ctest -DDIR=<build dir> [-DSTALE=<file>] -P tiers_test.cmake
function(count_tests out)
  execute_process(COMMAND "${CTEST}" -N ${ARGN} WORKING_DIRECTORY "${DIR}"
                  OUTPUT_VARIABLE text RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0 OR NOT text MATCHES "Total Tests: ([0-9]+)")
    message(FATAL_ERROR "ctest -N ${ARGN} failed in ${DIR}: ${text}")
  endif()
  set(${out} ${CMAKE_MATCH_1} PARENT_SCOPE)
endfunction()
count_tests(all)
count_tests(fast -L "^fast$")
count_tests(slow -L "^slow$")
count_tests(both -L "^fast$" -L "^slow$")
math(EXPR labelled "${fast} + ${slow}")
if(fast EQUAL 0 OR slow EQUAL 0 OR NOT labelled EQUAL all OR NOT both EQUAL 0)
  message(FATAL_ERROR "tiers: ${all} tests, ${fast} fast, ${slow} slow, ${both} both: every test "
                      "must carry exactly one of the labels fast and slow")
endif()
# A test labelled `power` (left out of the sanitized run) is a slow one.
count_tests(power -L "^power$")
count_tests(fast_power -L "^power$" -L "^fast$")
if(power EQUAL 0 OR NOT fast_power EQUAL 0)
  message(FATAL_ERROR "tiers: ${power} tests labelled power, ${fast_power} of them fast: the "
                      "power label is for slow tests (test_tiers.cmake)")
endif()
# Every entry of test_tiers.cmake's lists names a test (it writes those that do not to STALE
# each time ctest reads the test lists, which the count_tests calls above just did).
if(DEFINED STALE AND EXISTS "${STALE}")
  file(READ "${STALE}" stale)
  if(NOT stale STREQUAL "")
    message(FATAL_ERROR "tiers: entries of tests/test_tiers.cmake that name no test (remove or "
                        "rename them): ${stale}")
  endif()
endif()
message(STATUS "tiers: ${all} tests: ${fast} fast, ${slow} slow, ${power} of them power")
