// The equivalence criterion of batched against scalar kernels, and the per-kernel budgets.
#include "tests/simd/equivalence.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

#include "tests/simd/simd_test_util.h"

namespace glintlab::simd::test {

// Budgets, each with its reason; measured maxima (SSE4.2 and AVX2, this machine) in brackets.
Budget budget(std::string_view k, bool dbl) {
  const auto is = [&](std::string_view name) { return k == name; };
  const auto has = [&](std::string_view part) { return k.find(part) != std::string_view::npos; };
  constexpr double kFlags = 1e-4;
  // Samplers: directions in machine epsilons (absolute); the pdf is the pdf kernel's budget.
  if (is("sample.heitz_vndf/ggx")) {
    return {0, dbl ? 65536.0 : 16384.0, kFlags,
            "the disk lift √(1 − p1² − p2²) near the rim turns 1-ulp differences of sin/cos into "
            "~√ε (float ~5√ε) [float 1.05e4 eps, double 1.7e4 eps]"};
  }
  if (is("sample.beckmann_vndf/beckmann")) {
    return {0, dbl ? 4096.0 : 64.0, kFlags,
            "the visible-slope quantile is a Newton solve: its last step's rounding differs "
            "[float 21 eps, double 1859 eps]"};
  }
  if (has("sample.spherical_caps") || has("sample.bounded_vndf")) {
    return {0, 512.0, kFlags, "cap sampling + unstretch at α = 1e-3 [float 125, double 139 eps]"};
  }
  if (has("sample.walter")) {
    return {0, 16.0, kFlags, "sin/cos/log1p differences through normalize [7 eps]"};
  }
  // Beckmann terms below the horizon: ½|ωz| erfc(a) and σ e^{−a²}/(2√π) cancel, with condition
  // ~2a² (a = |ωz|/σ up to ~1e5 at α = 1e-3): an ulp of erfc becomes 1e10 ulps of the result.
  // The scalar value carries the same error; the comparison can only bound the difference.
  if (is("beckmann.lambda") || is("beckmann.projected_area") || is("beckmann.vndf") ||
      is("pdf.beckmann_vndf/beckmann")) {
    return {dbl ? 68719476736.0 : 8192.0, 0, 0,
            "below-horizon cancellation, see above [float 5324 ulp, double 3.6e10 ulp]"};
  }
  if (is("beckmann.total_area") || is("beckmann.total_area_eq30")) {
    return {dbl ? 4096.0 : 16.0, 0, 0,
            "erfcx(1/α) = e^{x²}(1 + e) erfc(x) up to x = 8: xsimd's double erfc is ~4e-13 "
            "relative that far in the tail [float 7 ulp, double 1719 ulp]"};
  }
  if (k.starts_with("beckmann.map")) {
    return {16.0, 4.0, 0, "expm1/log1p/exp [7 ulp, 1.5 eps]"};
  }
  if (k.starts_with("beckmann.") || is("pdf.walter/beckmann")) {
    return {dbl ? 128.0 : 16.0, 0, 0,
            "exp/erfc of xsimd vs glibc, a few ulp each [float 8, double 66]"};
  }
  if (is("ggx.total_area") || is("ggx.total_area_eq29")) {
    return {16.0, 0, 0, "log/log1p/atan/sincos/exp of xsimd vs glibc [6 ulp]"};
  }
  // GGX terms, GGX pdfs and maps, the Eq. 31 polynomial: IEEE +, −, ×, ÷, √ and fused fma only,
  // evaluated in the same order: bit-identical.
  return {0, 0, 0, "IEEE ops and fma only: bit-identical [0]"};
}

std::size_t rows_for(std::string_view kernel) {
  return kernel.find("total_area") != std::string_view::npos &&
                 kernel.find("_eq") == std::string_view::npos
             ? std::size_t(1) << 16
             : kRows;
}

template <class S>
const std::vector<std::vector<S>>& inputs() {
  if constexpr (sizeof(S) == 4) {
    return shared_inputs_float();
  } else {
    return shared_inputs_double();
  }
}

// Evaluates rows [0, n) in two halves on two threads (results do not depend on the split).
template <class S>
std::vector<std::vector<S>> evaluate_columns(int kernel, const std::vector<const S*>& in_cols,
                                             Isa isa, Math math, std::size_t n) {
  const KernelInfo info = kernel_info(kernel);
  std::vector<std::vector<S>> out(info.outputs.size(), std::vector<S>(n));
  const auto part = [&](std::size_t begin, std::size_t end) {
    std::vector<Column<S>> in;
    for (const S* c : in_cols) in.push_back({c + begin, 1});
    std::vector<S*> o;
    for (auto& c : out) o.push_back(c.data() + begin);
    eval_batch(kernel, std::span<const Column<S>>(in), std::span<S* const>(o), end - begin, isa,
               math);
  };
  const std::size_t mid = n / 2;
  std::thread t(part, 0, mid);
  part(mid, n);
  t.join();
  return out;
}

template <class S>
std::vector<std::vector<S>> evaluate(int kernel, Isa isa, Math math, std::size_t n) {
  std::vector<const S*> in;
  for (int d : kernel_info(kernel).inputs) in.push_back(inputs<S>()[d].data());
  return evaluate_columns<S>(kernel, in, isa, math, n);
}

namespace {

template <class S>
bool value_ok(S ref, S got, double ulp_budget, double* ulp_out) {
  const double tiny = std::sqrt(double(std::numeric_limits<S>::min()));
  const double u = ulp_distance(ref, got);
  const bool both_tiny = std::fabs(double(ref)) <= tiny && std::fabs(double(got)) <= tiny;
  *ulp_out = both_tiny ? 0.0 : u;
  return u <= ulp_budget || both_tiny;
}

bool is_direction_output(std::string_view name) {
  return name.starts_with("wo_") || name.starts_with("m_") || name.starts_with("w_") ||
         name.starts_with("p_");
}

}  // namespace

template <class S>
Comparison compare_outputs(int kernel, const std::vector<std::vector<S>>& ref,
                           const std::vector<std::vector<S>>& got, std::string label) {
  const KernelInfo info = kernel_info(kernel);
  const std::size_t n = got.empty() ? 0 : got[0].size();
  const bool dbl = sizeof(S) == 8;
  const Budget b = budget(info.name, dbl);
  const double eps = double(std::numeric_limits<S>::epsilon());
  const bool sampler = info.outputs.size() == 8 && info.outputs[7] == "rejected";

  double max_ulp = 0, max_abs_eps = 0;
  std::size_t fails = 0, flag_mismatch = 0, compared = 0;
  std::vector<std::vector<S>> pdf_at_wo;
  Budget pdf_budget = b;
  if (sampler) {
    // The standalone pdf at the batch's own wo, scalar: the value the sampler must report.
    const std::string pdf_name = "pdf." + std::string(info.name.substr(7));
    const int pdf = *find_kernel(pdf_name);
    std::vector<const S*> in;
    for (int j = 0; j < 5; ++j) in.push_back(inputs<S>()[kernel_info(kernel).inputs[j]].data());
    for (int j = 0; j < 3; ++j) in.push_back(got[j].data());
    pdf_at_wo = evaluate_columns<S>(pdf, in, Isa::kScalar, Math::kExact, n);
    pdf_budget = budget(pdf_name, dbl);
  }
  // Each output's kind, decided once (not per row).
  enum class Kind { kSkipped, kDirection, kSampledPdf, kValue };
  std::vector<Kind> kinds;
  for (const std::string_view name : info.outputs) {
    kinds.push_back(name == "rejected"          ? Kind::kSkipped
                    : is_direction_output(name) ? Kind::kDirection
                    : sampler && name == "pdf"  ? Kind::kSampledPdf
                                                : Kind::kValue);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (sampler) {
      const bool rr = ref[7][i] != S(0), rg = got[7][i] != S(0);
      if (rr != rg) ++flag_mismatch;
      if (rr || rg) continue;
    }
    ++compared;
    bool ok = true;
    for (std::size_t o = 0; o < info.outputs.size(); ++o) {
      const Kind kind = kinds[o];
      if (kind == Kind::kSkipped) continue;
      if (kind == Kind::kDirection) {
        const double a = std::fabs(double(ref[o][i]) - double(got[o][i])) / eps;
        max_abs_eps = std::max(max_abs_eps, std::isnan(a) ? 1e300 : a);
        if (!(a <= b.abs_eps)) ok = false;
      } else if (kind == Kind::kSampledPdf) {
        double u = 0;
        if (!value_ok(pdf_at_wo[0][i], got[o][i], pdf_budget.ulp, &u)) ok = false;
        max_ulp = std::max(max_ulp, u);
      } else {
        double u = 0;
        if (!value_ok(ref[o][i], got[o][i], b.ulp, &u)) ok = false;
        max_ulp = std::max(max_ulp, u);
      }
    }
    if (!ok) ++fails;
  }
  const double flag_frac = n ? double(flag_mismatch) / double(n) : 0.0;
  const bool pass = fails == 0 && flag_frac <= b.flag_fraction;
  Comparison c;
  c.pass = pass;
  c.summary = fmt::format(
      "{:<6} {:<7} {:<42} rows {:>7}  max {:>9.4g} ulp (budget {:g})  max {:>9.4g} eps abs "
      "(budget {:g})  flags differ {:.2g} (budget {:g})  failing rows {}  [{}]",
      dbl ? "double" : "float", label, info.name, compared, max_ulp,
      sampler ? pdf_budget.ulp : b.ulp, max_abs_eps, b.abs_eps, flag_frac, b.flag_fraction, fails,
      pass ? "ok" : "FAIL");
  return c;
}

template std::vector<std::vector<float>> evaluate<float>(int, Isa, Math, std::size_t);
template std::vector<std::vector<double>> evaluate<double>(int, Isa, Math, std::size_t);
template Comparison compare_outputs<float>(int, const std::vector<std::vector<float>>&,
                                           const std::vector<std::vector<float>>&, std::string);
template Comparison compare_outputs<double>(int, const std::vector<std::vector<double>>&,
                                            const std::vector<std::vector<double>>&, std::string);

}  // namespace glintlab::simd::test
