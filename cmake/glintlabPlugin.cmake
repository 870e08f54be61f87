# glintlab_add_model_plugin(<target> <source>...): a model plug-in (glintlab/plugin.h), built as a
# MODULE library named <target>.so (no "lib" prefix), loaded with `glintlab --plugin <path>` or
# GLINTLAB_PLUGINS. It compiles against glintlab's headers only (glintlab::headers) and links with
# --no-undefined: a plug-in that calls a compiled glintlab function (the registry, I/O) fails to
# link here instead of failing to load, since the registry it registers into is the host's.
# C++20, position-independent, hidden visibility (only the GLINTLAB_PLUGIN entry point is
# exported), -ffp-contract=off as glintlab's own kernels, -O3 when no build type is set.
function(glintlab_add_model_plugin target)
  if(NOT ARGN)
    message(FATAL_ERROR "glintlab_add_model_plugin(${target}): give at least one source file")
  endif()
  add_library(${target} MODULE ${ARGN})
  target_link_libraries(${target} PRIVATE glintlab::headers)
  target_compile_features(${target} PRIVATE cxx_std_20)
  set_target_properties(${target} PROPERTIES
    PREFIX ""
    CXX_EXTENSIONS OFF
    POSITION_INDEPENDENT_CODE ON
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
  target_compile_options(${target} PRIVATE -ffp-contract=off $<$<CONFIG:>:-O3>)
  target_link_options(${target} PRIVATE -Wl,--no-undefined)
endfunction()
