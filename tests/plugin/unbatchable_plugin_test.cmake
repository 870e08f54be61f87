# A plug-in whose kernels cannot be instantiated on the SIMD batch types (unbatchable_plugin.cpp)
# fails to compile its SIMD unit with one error, the static assertion that names the model and the
# two ways out, not an error per kernel call and batch type. The unit is the one
# glintlab_add_model_plugin generates (the scalar ISA's, whose fast-math type is a batch type;
# every ISA unit instantiates the same way), compiled with -fsyntax-only.
# Inputs: CXX, SOURCE_DIR (the repository), BINARY_DIR (the build tree), WORK (a scratch folder).
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(unit "${WORK}/unbatchable_plugin_scalar.cpp")
file(WRITE "${unit}" "#define GLINTLAB_PLUGIN_ISA scalar
#define GLINTLAB_PLUGIN_ISA_SCALAR 1
#include \"${SOURCE_DIR}/tests/plugin/unbatchable_plugin.cpp\"
")
execute_process(
  COMMAND "${CXX}" -std=c++20 -fsyntax-only -I${SOURCE_DIR} -I${SOURCE_DIR}/include
          -I${BINARY_DIR}/include "${unit}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(log "${out}${err}")
if(rc EQUAL 0)
  message(FATAL_ERROR "the unbatchable plug-in compiled; its SIMD unit must be refused")
endif()
string(REGEX MATCHALL "error:" errors "${log}")
list(LENGTH errors count)
if(NOT count EQUAL 1)
  message(FATAL_ERROR "expected one error, got ${count}:\n${log}")
endif()
foreach(needle "static assertion failed" "ScalarOnlyGlints" "select()"
               "static constexpr bool kBatched = false;")
  string(FIND "${log}" "${needle}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the compiler's message lacks '${needle}':\n${log}")
  endif()
endforeach()
message(STATUS "one error naming the model and the two ways out")
