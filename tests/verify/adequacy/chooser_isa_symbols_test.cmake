# The per-ISA chooser objects (chooser_isa_<isa>.cpp) must define no weak (vague-linkage) symbol
# that another object of the test binary could also define: the linker keeps one copy of such a
# symbol, so an AVX-512 copy of a shared inline function would run in every test on CPUs without
# AVX-512 (the rule core/simd's ISA units keep, tests/simd/isa_symbols_test.cmake). Allowed:
# symbols whose names carry the ISA (xsimd arch types, the renamed xsimd helpers, the getter) and
# the C++ personality reference. Run: cmake -DNM=nm -DOBJECTS="a.o|b.o" -P chooser_isa_symbols_test.cmake
string(REPLACE "|" ";" objects "${OBJECTS}")
set(checked 0)
foreach(obj IN LISTS objects)
  get_filename_component(name "${obj}" NAME)
  if(NOT name MATCHES "^chooser_isa_(sse42|avx2|avx512)\\.cpp\\.o$")
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
    if(sym MATCHES "xsimd::(sse4_2|fma3<xsimd::avx2>|avx512bw)"
       OR sym MATCHES "glintlab_[a-z0-9_]+_chooser_isa_${isa}\\("
       OR sym MATCHES "isa_test::chooser_isa_${isa}\\(\\)$" OR sym MATCHES "__gxx_personality")
      continue()
    endif()
    message(FATAL_ERROR "${name} exports a symbol other objects may share: ${sym}")
  endforeach()
  math(EXPR checked "${checked} + 1")
endforeach()
if(NOT checked EQUAL 3)
  message(FATAL_ERROR "expected the three objects chooser_isa_{sse42,avx2,avx512}.cpp.o, found ${checked}")
endif()
message(STATUS "chooser isa symbols: ${checked} ISA objects, no shared weak symbols")
