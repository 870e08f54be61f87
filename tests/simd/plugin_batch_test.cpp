// SIMD batches of a plug-in model (glintlab/plugin.h, ModelEntry::plugin_batches): the built-in
// smooth_ggx compiled into a plug-in under another name (tests/plugin/renamed_builtin_plugin.cpp)
// and loaded with load_plugin runs its own per-ISA instantiations, and they give the built-in
// model's batch results bit for bit on every ISA this CPU has (float exact and fast, double; eval
// and sample; every sampler), within GLINTLAB_MAX_ISA's cap.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/model_registry.h"
#include "core/plugin_loader.h"
#include "core/simd/batch.h"
#include "core/simd/model_batch.h"
#include "core/simd/table.h"

#ifndef GLINTLAB_TEST_PLUGIN_RENAMED_BUILTIN
#error "GLINTLAB_TEST_PLUGIN_RENAMED_BUILTIN (the plug-in's path) must be defined by the build"
#endif

namespace glintlab::simd::test {
namespace {

const ModelEntry& plugin_model() {
  static const bool loaded = [] {
    load_plugin(GLINTLAB_TEST_PLUGIN_RENAMED_BUILTIN);
    return true;
  }();
  (void)loaded;
  return find_model("plugin_smooth_ggx");
}

constexpr std::size_t kRows = 1003;  // not a multiple of any lane count: the tail batch is run

// kRows queries: wi and wo uniform on the sphere (below the surface too), from a fixed seed.
template <class S>
std::vector<std::vector<S>> queries() {
  std::vector<std::vector<S>> q(kQueryColumns.size());
  for (std::size_t j = 0; j < q.size(); ++j) q[j].assign(kRows, static_cast<S>(kQueryDefaults[j]));
  std::mt19937_64 rng(20261202);
  std::normal_distribution<double> normal;
  const auto column = [](std::string_view name) {
    for (std::size_t j = 0; j < kQueryColumns.size(); ++j)
      if (kQueryColumns[j] == name) return j;
    throw std::logic_error("no query column " + std::string(name));
  };
  for (const char* dir : {"wi", "wo"}) {
    for (std::size_t i = 0; i < kRows; ++i) {
      double v[3] = {normal(rng), normal(rng), normal(rng)};
      const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      for (int k = 0; k < 3; ++k) {
        const std::string name = std::string(dir) + "_" + "xyz"[k];
        q[column(name)][i] = static_cast<S>(v[k] / len);
      }
    }
  }
  return q;
}

template <class S>
std::vector<Column<S>> columns(const std::vector<std::vector<S>>& q) {
  std::vector<Column<S>> c;
  for (const auto& v : q) c.push_back({v.data(), 1});
  return c;
}

// Output k of model m's eval (or sample) at `params` over the queries.
template <class S>
std::vector<std::vector<S>> run_batch(const ModelEntry& m, const std::vector<double>& params,
                                      bool sample, Isa isa, Math math) {
  const auto q = queries<S>();
  const auto qc = columns(q);
  const std::size_t n_out = sample ? kSampleColumns.size() : 2 + m.intermediates.size();
  std::vector<std::vector<S>> out(n_out, std::vector<S>(kRows));
  std::vector<S*> o;
  for (auto& v : out) o.push_back(v.data());
  if (sample) {
    std::vector<S> u1(kRows), u2(kRows);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> uniform;
    for (std::size_t i = 0; i < kRows; ++i) {
      u1[i] = static_cast<S>(uniform(rng));
      u2[i] = static_cast<S>(uniform(rng));
    }
    sample_batch(m, params, qc, Column<S>{u1.data(), 1}, Column<S>{u2.data(), 1}, o, kRows, isa,
                 math);
  } else {
    eval_batch(m, params, qc, o, kRows, isa, math);
  }
  return out;
}

// Rows whose bits differ between two runs (NaN equal to NaN of the same bits).
template <class S>
std::size_t differing_rows(const std::vector<std::vector<S>>& a,
                           const std::vector<std::vector<S>>& b) {
  std::size_t rows = 0;
  for (std::size_t i = 0; i < kRows; ++i) {
    bool differs = false;
    for (std::size_t k = 0; k < a.size(); ++k)
      differs |= std::memcmp(&a[k][i], &b[k][i], sizeof(S)) != 0;
    rows += differs ? 1 : 0;
  }
  return rows;
}

TEST(PluginBatches, EveryIsaHasThePluginsOwnInstantiations) {
  const ModelEntry& m = plugin_model();
  ASSERT_NE(m.plugin_batches, nullptr);
  EXPECT_TRUE(is_batched(m));
  for (Isa isa : kAllIsas) {
    EXPECT_NE(m.plugin_batches->eval[static_cast<std::size_t>(isa)], nullptr) << isa_name(isa);
    EXPECT_NE(m.plugin_batches->sample[static_cast<std::size_t>(isa)], nullptr) << isa_name(isa);
  }
}

TEST(PluginBatches, EqualTheBuiltInModelsBitForBitOnEveryIsa) {
  const ModelEntry& plugin = plugin_model();
  const ModelEntry& builtin = find_model("smooth_ggx");
  std::size_t compared = 0;
  for (Isa isa : kAllIsas) {
    if (!isa_supported(isa)) continue;
    for (const std::string_view sampler : {"ndf", "vndf", "spherical_caps", "bounded_caps"}) {
      const std::vector<std::pair<std::string, std::string>> a = {
          {"alpha_x", "0.13"}, {"alpha_y", "0.71"}, {"sampler", std::string(sampler)}};
      const std::vector<double> params = resolve_params(builtin, a);
      for (bool sample : {false, true}) {
        const std::string what = std::string(isa_name(isa)) + " " + std::string(sampler) +
                                 (sample ? " sample" : " eval");
        EXPECT_EQ(differing_rows(run_batch<float>(plugin, params, sample, isa, Math::kExact),
                                 run_batch<float>(builtin, params, sample, isa, Math::kExact)),
                  0u)
            << what << " float";
        EXPECT_EQ(differing_rows(run_batch<float>(plugin, params, sample, isa, Math::kFast),
                                 run_batch<float>(builtin, params, sample, isa, Math::kFast)),
                  0u)
            << what << " float fast";
        EXPECT_EQ(differing_rows(run_batch<double>(plugin, params, sample, isa, Math::kExact),
                                 run_batch<double>(builtin, params, sample, isa, Math::kExact)),
                  0u)
            << what << " double";
        compared += 3;
      }
    }
  }
  EXPECT_GE(compared, 24u);  // at least the scalar tables
}

// The comparison above sees a difference where there is one: the plug-in's float batches against
// its own scalar double thunk loop (what a plug-in without batches would run), and against the
// built-in model at a roughness 1 % off.
TEST(PluginBatches, ComparisonDetectsOtherResults) {
  const ModelEntry& plugin = plugin_model();
  const ModelEntry& builtin = find_model("smooth_ggx");
  const std::vector<double> params = resolve_params(builtin, {{"alpha_x", "0.13"}});
  const std::vector<double> nearby = resolve_params(builtin, {{"alpha_x", "0.1313"}});
  const Isa isa = best_isa();
  EXPECT_GT(differing_rows(run_batch<double>(plugin, params, false, isa, Math::kExact),
                           run_batch<double>(builtin, nearby, false, isa, Math::kExact)),
            kRows / 2);
  ModelEntry unbatched = plugin;
  unbatched.plugin_batches = nullptr;
  EXPECT_FALSE(is_batched(unbatched));
  EXPECT_GT(differing_rows(run_batch<float>(plugin, params, false, isa, Math::kFast),
                           run_batch<float>(unbatched, params, false, isa, Math::kFast)),
            0u);
}

TEST(PluginBatches, MaxIsaCapAppliesToPluginModels) {
  const ModelEntry& plugin = plugin_model();
  const std::vector<double> params = resolve_params(plugin, {});
  setenv("GLINTLAB_MAX_ISA", "scalar", 1);
  EXPECT_THROW(run_batch<double>(plugin, params, false, Isa::kSse42, Math::kExact),
               std::invalid_argument);
  EXPECT_NO_THROW(run_batch<double>(plugin, params, false, Isa::kScalar, Math::kExact));
  unsetenv("GLINTLAB_MAX_ISA");
}

}  // namespace
}  // namespace glintlab::simd::test
