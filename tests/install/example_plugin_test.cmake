# ctest script: the example plug-in project examples/zirr_kaplanyan, as a researcher outside the
# project builds it. Install glintlab into a scratch prefix, configure and build the example
# against that install only (CMAKE_PREFIX_PATH, no path into the source or build tree), then run
# the INSTALLED glintlab with it: `models` lists it, `eval --model` gives a finite value for every
# query row, and its conformance claims run at the quick budget and give exactly the verdicts the
# model declares, exit 0 (CONFORMANCE=ON).
include("${CMAKE_CURRENT_LIST_DIR}/install_and_build.cmake")
# Built as on a machine without OpenEXR, PNG and TBB: a plug-in needs only the headers' packages.
install_and_build("${EXAMPLE}" "example" -DCMAKE_DISABLE_FIND_PACKAGE_OpenEXR=TRUE
                  -DCMAKE_DISABLE_FIND_PACKAGE_PNG=TRUE -DCMAKE_DISABLE_FIND_PACKAGE_TBB=TRUE)

set(glintlab "${WORK}/prefix/bin/glintlab")
set(plugin "${WORK}/build/zirr_kaplanyan.so")

execute_process(COMMAND "${glintlab}" --plugin "${plugin}" models
                RESULT_VARIABLE r OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(r OR NOT out MATCHES "\nzirr_kaplanyan: ")
  message(FATAL_ERROR "zirr_kaplanyan not listed (exit ${r}):\n${out}\n${err}")
endif()

# Three queries: normal incidence on the specular peak, oblique, and a tiny footprint.
file(WRITE "${WORK}/q.csv"
  "wi_x,wi_y,wi_z,wo_x,wo_y,wo_z,u,v,dudx,dvdx,dudy,dvdy,light_cos_half_angle,light_intensity\n"
  "0,0,1,0,0,1,0.5,0.5,0.01,0,0,0.01,0.99999,1\n"
  "0.6,0,0.8,-0.36,0.48,0.8,0.1,0.2,0.001,0,0,0.002,0.99999,1\n"
  "0.8,0,0.6,-0.8,0,0.6,0.3,0.7,0.00001,0,0,0.00001,1,1\n")
execute_process(COMMAND "${glintlab}" --plugin "${plugin}" eval --model zirr_kaplanyan
                        --in "${WORK}/q.csv" --out "${WORK}/r.csv"
                RESULT_VARIABLE r ERROR_VARIABLE err)
if(r)
  message(FATAL_ERROR "eval --model zirr_kaplanyan failed (${r}): ${err}")
endif()
file(STRINGS "${WORK}/r.csv" lines)
list(LENGTH lines n)
if(NOT n EQUAL 4)
  message(FATAL_ERROR "eval wrote ${n} lines, expected a header and 3 rows")
endif()
foreach(line IN LISTS lines)
  if(line MATCHES "nan|inf")
    message(FATAL_ERROR "eval wrote a non-finite value: ${line}")
  endif()
endforeach()

if(CONFORMANCE)
  execute_process(COMMAND "${glintlab}" --plugin "${plugin}" verify
                          --claims "model.zirr_kaplanyan.*" --budget quick --out "${WORK}/verify"
                  RESULT_VARIABLE r OUTPUT_VARIABLE out ERROR_VARIABLE err)
  # Exit 0: every verdict is the one the model declares (holds, and not-claimed for the property
  # in its kNotClaimed, energy) and every control is rejected; exit 1 (a verdict differs), 2 (the
  # run could not complete) or 3 (a check could not run) fails this test.
  if(NOT r EQUAL 0 OR NOT EXISTS "${WORK}/verify/claims.json" OR out MATCHES "NOT REJECTED")
    message(FATAL_ERROR "conformance claims of zirr_kaplanyan (exit ${r}):\n${out}\n${err}")
  endif()
  file(READ "${WORK}/verify/claims.json" claims)
  string(JSON rows LENGTH "${claims}")
  if(NOT rows EQUAL 10)
    message(FATAL_ERROR "expected the 10 conformance properties, got ${rows} rows")
  endif()
  math(EXPR last "${rows} - 1")
  foreach(i RANGE ${last})
    string(JSON id GET "${claims}" ${i} id)
    string(JSON verdict GET "${claims}" ${i} verdict)
    set(want "holds")
    if(id STREQUAL "model.zirr_kaplanyan.energy")
      set(want "not-claimed")
    endif()
    if(NOT verdict STREQUAL want)
      message(FATAL_ERROR "${id}: verdict ${verdict}, the example declares ${want}")
    endif()
  endforeach()
  message(STATUS "${out}")
endif()
