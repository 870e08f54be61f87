// reference RESULT_CSV: the example model registered in this process (as the in-tree example test
// does) evaluated on every row of `glintlab --plugin example_glints.so eval --model example_glints`
// output (defaults for the parameters); exit 0 when value, pdf and both intermediates equal the
// printed ones bit for bit, 1 otherwise (and on a row it cannot read).
#include <cstdio>
#include <exception>

#include "core/io/csv.h"
#include "core/model_registry.h"
#include "experiments/example_glint_model.h"

int main(int argc, char** argv) {
  using namespace glintlab;
  if (argc != 2) {
    std::fprintf(stderr, "usage: reference RESULT_CSV\n");
    return 2;
  }
  try {
    register_model(make_model_entry<example::ExampleGlints>());
    const ModelEntry& m = find_model("example_glints");
    const std::vector<double> values = resolve_params(m, {});
    const io::CsvTable t = io::read_csv(argv[1]);
    const auto c = [&](std::size_t row, const char* name) { return t.number(row, t.column(name)); };
    std::size_t mismatches = 0;
    for (std::size_t i = 0; i < t.num_rows(); ++i) {
      ModelQuery<double> q{};
      q.footprint.uv = {c(i, "u"), c(i, "v")};
      q.footprint.duv_dx = {c(i, "dudx"), c(i, "dvdx")};
      q.footprint.duv_dy = {c(i, "dudy"), c(i, "dvdy")};
      q.wi = {c(i, "wi_x"), c(i, "wi_y"), c(i, "wi_z")};
      q.wo = {c(i, "wo_x"), c(i, "wo_y"), c(i, "wo_z")};
      q.light = {c(i, "light_cos_half_angle"), c(i, "light_intensity")};
      const ErasedEval e = m.eval(values, q);
      const double want[4] = {e.value, e.pdf, e.intermediates[0], e.intermediates[1]};
      const char* names[4] = {"value", "pdf", "expected_facets", "p_hit"};
      for (int k = 0; k < 4; ++k) {
        const double got = c(i, names[k]);
        if (got != want[k]) {
          std::printf("row %zu %s: plug-in %.17g, in-process %.17g\n", i, names[k], got, want[k]);
          ++mismatches;
        }
      }
    }
    std::printf("reference: %zu rows, %zu mismatches\n", t.num_rows(), mismatches);
    return mismatches == 0 && t.num_rows() > 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "reference: %s\n", e.what());
    return 1;
  }
}
