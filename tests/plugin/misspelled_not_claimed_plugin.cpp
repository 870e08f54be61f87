// The example model declaring a not-claimed property under a misspelled name ("enrgy"): the loader
// must refuse it, naming the property and the valid names, rather than silently claim "energy".
#include <glintlab/plugin.h>

#include "experiments/example_glint_model.h"

namespace glintlab::test {
struct MisspelledNotClaimed : example::ExampleGlints {
  static constexpr std::string_view kName = "misspelled_not_claimed";
  static constexpr std::array<NotClaimed, 1> kNotClaimed = {{{"enrgy", "a misspelled name"}}};
};
}  // namespace glintlab::test

GLINTLAB_PLUGIN(glintlab::test::MisspelledNotClaimed);
