# ctest script: install glintlab into a scratch prefix, build the plug-in project tests/install/plugin
# against it (glintlab_add_model_plugin from the installed package), then run the INSTALLED
# glintlab with the plug-in: listed by `models` (--plugin and GLINTLAB_PLUGINS), `eval --model`
# equal bit for bit to the same model registered in-process (and the comparison fails on a
# perturbed value), the plug-in defines no registry of its own, a scalar plug-in (kBatched = false)
# is swept by model.<name>.stability and its NaN control rejected, and a missing file, a module
# without the entry point, a plug-in built against another version and a name clash are each
# refused with one line and exit 2.
include("${CMAKE_CURRENT_LIST_DIR}/install_and_build.cmake")
install_and_build("${SOURCE}" "plug-in project" -DGLINTLAB_TESTS_DIR=${TESTS_DIR})

set(glintlab "${WORK}/prefix/bin/glintlab")
set(plugin "${WORK}/build/example_glints.so")

# The registry lives in the host: the plug-in defines none of its functions.
execute_process(COMMAND nm -C --defined-only "${plugin}" OUTPUT_VARIABLE symbols RESULT_VARIABLE r)
if(r OR NOT symbols MATCHES "glintlab_plugin_v1")
  message(FATAL_ERROR "nm found no entry point in ${plugin} (${r})")
endif()
if(symbols MATCHES "registered_models|register_model|find_model")
  message(FATAL_ERROR "the plug-in carries registry code:\n${symbols}")
endif()

# SIMD batches: the four ISA units of the plug-in exist, and none defines a weak symbol another
# ISA's unit could also define (the linker would keep one copy, maybe the AVX-512 one, for all):
# only the per-ISA table function and the per-ISA renamed xsimd helpers carry vague linkage.
file(GLOB isa_objects "${WORK}/build/CMakeFiles/example_glints.dir/example_glints_isa/*.o")
list(LENGTH isa_objects n)
if(NOT n EQUAL 4)
  message(FATAL_ERROR "expected the plug-in's 4 ISA objects, found ${n}: ${isa_objects}")
endif()
foreach(obj IN LISTS isa_objects)
  string(REGEX MATCH "_(scalar|sse42|avx2|avx512)\\.cpp\\.o$" m "${obj}")
  set(isa "${CMAKE_MATCH_1}")
  execute_process(COMMAND nm -C --defined-only "${obj}" OUTPUT_VARIABLE out)
  string(REPLACE "\n" ";" lines "${out}")
  foreach(line IN LISTS lines)
    if(line MATCHES "^[0-9a-f]+ [WVuT] (.*)$")
      set(sym "${CMAKE_MATCH_1}")
      if(NOT sym MATCHES "_${isa}\\(|__gxx_personality")
        message(FATAL_ERROR "${obj} defines a symbol other ISAs may share: ${sym}")
      endif()
    endif()
  endforeach()
endforeach()

function(expect_listed what)
  if(NOT out MATCHES "example_glints: toy glint model" OR r)
    message(FATAL_ERROR "${what}: example_glints not listed (exit ${r}):\n${out}\n${err}")
  endif()
endfunction()
execute_process(COMMAND "${glintlab}" --plugin "${plugin}" models
                RESULT_VARIABLE r OUTPUT_VARIABLE out ERROR_VARIABLE err)
expect_listed("--plugin")
execute_process(COMMAND "${CMAKE_COMMAND}" -E env "GLINTLAB_PLUGINS=${plugin}" "${glintlab}" models
                RESULT_VARIABLE r OUTPUT_VARIABLE out ERROR_VARIABLE err)
expect_listed("GLINTLAB_PLUGINS")
execute_process(COMMAND "${glintlab}" models RESULT_VARIABLE r OUTPUT_VARIABLE out)
if(out MATCHES "example_glints")
  message(FATAL_ERROR "example_glints listed without its plug-in")
endif()

# eval through the plug-in against the in-process registration (scalar batches: the thunks' code
# bit for bit; the SIMD ISAs agree within tests/simd's budgets).
file(WRITE "${WORK}/q.csv"
  "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,u,v,dudx,dvdx,dudy,dvdy\n"
  "0.6,0,0.8,-0.36,0.48,0.8,0.1,0.2,0.001,0,0,0.002\n"
  "0,0,1,0.6,0,0.8,0.5,0.5,0.01,0.002,0,0.01\n"
  "0.8,0,0.6,0,0.6,0.8,0.3,0.7,0.0001,0.00002,0.00001,0.0003\n")
execute_process(COMMAND "${glintlab}" --plugin "${plugin}" eval --model example_glints --isa scalar
                        --in "${WORK}/q.csv" --out "${WORK}/r.csv"
                RESULT_VARIABLE r ERROR_VARIABLE err)
if(r)
  message(FATAL_ERROR "eval --model example_glints failed (${r}): ${err}")
endif()
execute_process(COMMAND "${WORK}/build/reference" "${WORK}/r.csv" RESULT_VARIABLE r
                OUTPUT_VARIABLE out)
if(r)
  message(FATAL_ERROR "plug-in eval differs from the in-process model (${r}):\n${out}")
endif()
message(STATUS "${out}")
# The comparison catches a wrong number: the first row's value with its third decimal digit
# changed by one (about 0.1 % off).
file(STRINGS "${WORK}/r.csv" lines)
list(GET lines 0 header)
list(GET lines 1 row)
string(REPLACE "," ";" header "${header}")
string(REPLACE "," ";" row "${row}")
list(FIND header value at)
list(GET row ${at} value)
string(SUBSTRING "${value}" 4 1 digit)
math(EXPR digit "(${digit} + 1) % 10")
string(SUBSTRING "${value}" 0 4 head)
string(SUBSTRING "${value}" 5 -1 tail)
list(REMOVE_AT row ${at})
list(INSERT row ${at} "${head}${digit}${tail}")
string(REPLACE ";" "," row "${row}")
list(REMOVE_AT lines 1)
list(INSERT lines 1 "${row}")
string(REPLACE ";" "\n" broken "${lines}")
file(WRITE "${WORK}/r_broken.csv" "${broken}\n")
execute_process(COMMAND "${WORK}/build/reference" "${WORK}/r_broken.csv" RESULT_VARIABLE r
                OUTPUT_VARIABLE out)
if(NOT r EQUAL 1 OR NOT out MATCHES "row 0 value")
  message(FATAL_ERROR "the comparison did not catch a changed value (exit ${r}):\n${out}")
endif()

# Refusals: exit 2, one line "glintlab: error: --plugin PATH: …" naming the reason.
function(expect_refused what needle)
  execute_process(COMMAND "${glintlab}" ${ARGN} models
                  RESULT_VARIABLE r OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT r EQUAL 2 OR NOT out STREQUAL "" OR NOT err MATCHES "^glintlab: error: --plugin [^\n]*${needle}[^\n]*\n$")
    message(FATAL_ERROR "${what}: not refused as expected (exit ${r}):\n${out}\n${err}")
  endif()
endfunction()
expect_refused("missing file" "no such file" --plugin "${WORK}/build/missing.so")
expect_refused("module without entry point" "not a glintlab plug-in"
               --plugin "${WORK}/build/not_a_plugin.so")
expect_refused("other version" "built against glintlab 0.0.1, this is glintlab"
               --plugin "${WORK}/build/example_glints_wrong_version.so")
expect_refused("name clash" "model 'example_glints' clashes"
               --plugin "${plugin}" --plugin "${plugin}")

# A scalar plug-in (kBatched = false, its roughness under a name of its own) is swept like a built-in
# model: its stability check measures cells and the NaN control is rejected.
execute_process(COMMAND "${glintlab}" --plugin "${WORK}/build/scalar_glints.so" verify
                        --claims "model.scalar_glints.stability" --budget quick
                        --out "${WORK}/verify_scalar"
                RESULT_VARIABLE r OUTPUT_VARIABLE out ERROR_VARIABLE err)
file(READ "${WORK}/verify_scalar/claims.json" claims)
string(REGEX MATCH "target\\(s\\) swept, ([0-9]+) cells" swept "${claims}")
if(r EQUAL 2 OR NOT swept OR CMAKE_MATCH_1 EQUAL 0 OR out MATCHES "NOT REJECTED"
   OR NOT out MATCHES "scalar_glints.stability")
  message(FATAL_ERROR "scalar plug-in not swept (exit ${r}, '${swept}'):\n${out}\n${err}")
endif()
message(STATUS "scalar plug-in: ${swept}")

# The installed glintlab draws its charts with the report scripts installed beside it
# (<prefix>/share/glintlab/reports), not with a source tree that may have moved or gone.
if(NOT EXISTS "${WORK}/prefix/share/glintlab/reports/figure_charts.py")
  message(FATAL_ERROR "the report scripts are not installed under ${WORK}/prefix/share/glintlab")
endif()
file(REMOVE_RECURSE "${WORK}/fig6")
execute_process(COMMAND "${CMAKE_COMMAND}" -E env --unset=GLINTLAB_REPORTS_DIR "${glintlab}" figure
                        kneiphof2024-fig6 --budget quick --out "${WORK}/fig6"
                RESULT_VARIABLE r OUTPUT_VARIABLE out ERROR_VARIABLE err)
file(GLOB_RECURSE charts "${WORK}/fig6/*.png")
if(r OR NOT charts)
  message(FATAL_ERROR "the installed glintlab could not draw a figure's charts (exit ${r}):\n${out}\n${err}")
endif()
