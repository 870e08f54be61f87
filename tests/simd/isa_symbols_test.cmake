# Each per-ISA object (PREFIX<isa>.cpp.o: core/simd's isa_<isa>.cpp, or a test's per-ISA units)
# must define no weak (vague-linkage) symbol that another object could also define: the linker
# keeps one copy of such a symbol for the whole program, so an AVX-512 copy of a shared inline
# function would run on CPUs without AVX-512. Allowed: symbols whose names carry the ISA (xsimd
# arch types, the renamed xsimd helpers, core's per-ISA tables, a unit's PREFIX<isa>() getter) and
# the C++ personality reference.
# Run: cmake -DNM=nm -DOBJECTS="a.o|b.o" [-DPREFIX=isa_] -P isa_symbols_test.cmake
if(NOT DEFINED PREFIX)
  set(PREFIX "isa_")
endif()
string(REPLACE "|" ";" objects "${OBJECTS}")
set(checked 0)
foreach(obj IN LISTS objects)
  get_filename_component(name "${obj}" NAME)
  if(NOT name MATCHES "^${PREFIX}(sse42|avx2|avx512)\\.cpp\\.o$")
    continue()
  endif()
  set(isa "${CMAKE_MATCH_1}")
  execute_process(COMMAND "${NM}" -C --defined-only "${obj}" OUTPUT_VARIABLE out RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "nm failed on ${obj}")
  endif()
  string(REPLACE "\n" ";" lines "${out}")
  foreach(line IN LISTS lines)
    if(NOT line MATCHES "^[0-9a-f]+ [WVuT] (.*)$")
      continue()
    endif()
    set(sym "${CMAKE_MATCH_1}")
    if(sym MATCHES "xsimd::(sse4_2|fma3<xsimd::avx2>|avx512bw)" OR sym MATCHES "glintlab_[a-z0-9_]+_${isa}\\("
       OR sym MATCHES "^glintlab::simd::detail::table_${isa}\\(\\)$"
       OR sym MATCHES "::${PREFIX}${isa}\\(\\)$" OR sym MATCHES "__gxx_personality")
      continue()
    endif()
    message(FATAL_ERROR "${name} exports a symbol other ISAs may share: ${sym}")
  endforeach()
  math(EXPR checked "${checked} + 1")
endforeach()
if(NOT checked EQUAL 3)
  message(FATAL_ERROR "expected the three ISA objects ${PREFIX}{sse42,avx2,avx512}.cpp.o, found ${checked}")
endif()
message(STATUS "isa symbols: ${checked} ${PREFIX}* objects, no shared weak symbols")
