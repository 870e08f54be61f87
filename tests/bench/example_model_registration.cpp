// docs/adding_a_model.md: registers the example glint model before main(), linked first into a
// copy of the model benchmarks (experiments/bench/bench_models.cpp), so that they find it in the
// registry like any built-in model and run model/example_glints/<isa>.
#include "core/model_registry.h"
#include "experiments/example_glint_model.h"

namespace {

const bool kRegistered = [] {
  glintlab::register_model(glintlab::make_model_entry<glintlab::example::ExampleGlints>());
  return true;
}();

}  // namespace
