// The Kemppinen models' sampler, the mixture of Algorithm 2 and D cosθ, where the compensation
// carries most of the value (footprint 1, and k = 1 at grazing incidence): every sample's pdf is
// pdf() at its direction and its weight is value / pdf, for both mappings (with pdf=printed the
// weight is value over the printed pdf the sample reports). A
// few hundred samples, so that the sanitized run (scripts/test_asan.sh) covers the mixture's code;
// KemppinenSampler.* (tests/verify/conformance) tests what it estimates at the suite's power.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/math/rng.h"
#include "core/model_registry.h"
#include "verify/conformance/common.h"

namespace glintlab {
namespace {

TEST(KemppinenMixture, SamplesCarryThePdfAndWeightOfTheirDirection) {
  struct Case {
    std::vector<std::pair<std::string, std::string>> params;
    double theta_deg, side;
    bool printed = false;
  };
  const std::vector<Case> cases = {
      {{}, 30, 1},
      {{}, 80, 1},
      {{{"k", "1"}}, 80, 0.4},
      {{{"pdf", "printed"}}, 30, 1, true},
      {{{"mapping", "triplanar"}}, 30, 1},
  };
  for (const char* name : {"kemppinen_ggx", "kemppinen_beckmann"}) {
    const ModelEntry& m = find_model(name);
    for (const Case& c : cases) {
      const std::vector<double> values = resolve_params(m, c.params);
      const ModelQuery<double> q0 = verify::conformance::make_query(m, c.theta_deg, c.side);
      int accepted = 0;
      for (int i = 0; i < 300; ++i) {
        const Vec2<double> u{counter_uniform<double>(11, i, 0), counter_uniform<double>(11, i, 1)};
        const ModelSample<double> s = m.sample(values, q0, u);
        ASSERT_TRUE(std::isfinite(s.pdf) && std::isfinite(s.weight)) << name << " sample " << i;
        if (s.rejected) {
          EXPECT_EQ(s.weight, 0.0);
          continue;
        }
        ++accepted;
        ModelQuery<double> q = q0;
        q.wo = s.wo;
        const ErasedEval e = m.eval(values, q);
        // pdf=printed: sample() reports the mixture with Algorithm 2's printed density, which
        // pdf() (the density of the samples) is not; its weight is value over that pdf.
        const double pdf = c.printed ? s.pdf : m.pdf(values, q);
        EXPECT_NEAR(s.pdf, pdf, 1e-9 * pdf) << name << " θi " << c.theta_deg << " sample " << i;
        EXPECT_NEAR(s.weight, e.value / pdf, 1e-9 * s.weight) << name << " sample " << i;
      }
      EXPECT_GT(accepted, 100) << name << " θi " << c.theta_deg << " side " << c.side;
    }
  }
}

}  // namespace
}  // namespace glintlab
