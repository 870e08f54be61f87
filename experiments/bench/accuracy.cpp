// glintlab_accuracy: error of every batched kernel × ISA × math flavour (and of each printed /
// approximate formula against its exact one) relative to the scalar double exact reference, as CSV.
//
// Inputs: core/simd/inputs.h's edge-case generator (the equivalence tests' inputs), rounded once
// to float so that every variant, float or double, sees the same numbers and the error measures
// the evaluation, not the input rounding. Reference: the scalar double exact instantiation of the
// reference kernel on those inputs. Relative error of one output value y against reference r:
//   e = |y − r| / max(|r|, f),   f = kRelFloor × median{|r| : r finite, r ≠ 0} of that output
//   column (1 if the column has none),
// so values near zero are compared absolutely at a millionth of the column's typical size instead
// of dividing by ~0. Both NaN, or the same infinity, count as e = 0; any other non-finite
// disagreement is counted in nonfinite_mismatch and left out of max / RMS / p99.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/atomic_file.h"
#include "core/math/rng.h"
#include "core/simd/batch.h"
#include "core/simd/inputs.h"

namespace glintlab::simd::accuracy {
namespace {

constexpr double kRelFloor = 1e-6;

// Printed or approximate formulas and the exact formula each is measured against (same inputs).
struct Variant {
  std::string_view kernel, reference;
};
constexpr Variant kVariants[] = {
    {"beckmann.total_area_eq31_printed",
     "beckmann.total_area_eq30"},  // Kneiphof & Klein 2024 Eq. 31 as printed vs Eq. 30
    {"pdf.vndf_backfacing_eq7/ggx",
     "pdf.vndf_backfacing_stable/ggx"},  // Eto & Tokuyoshi 2023 Eq. 7 direct vs its stable form
    {"pdf.bounded_vndf_listing2_printed/ggx",
     "pdf.bounded_vndf_listing1/ggx"},  // Eto & Tokuyoshi 2023 Listing 2 as printed vs the Listing
                                        // 1 density
    {"ggx.map_jacobian_paper", "ggx.map_jacobian_true"},  // Kemppinen 2025 paper vs true Jacobian
    {"beckmann.map_jacobian_paper",
     "beckmann.map_jacobian_true"},  // Kemppinen 2025 paper vs true Jacobian
    {"ggx.g2_separable",
     "ggx.g2_height_correlated"},  // Heitz 2014 separable vs height-correlated Smith G2
    {"beckmann.g2_separable",
     "beckmann.g2_height_correlated"},  // Heitz 2014 separable vs height-correlated Smith G2
};

struct Options {
  std::size_t n = 200000;
  std::filesystem::path out = "out/bench/accuracy.csv";
  std::string filter;  // substring of the kernel name; empty = all
};

[[noreturn]] void usage_error(const std::string& msg) {
  std::fprintf(stderr, "glintlab: error: %s\n", msg.c_str());
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    const auto value = [&]() -> std::string_view {
      if (i + 1 >= argc) usage_error(std::string(a) + " needs a value");
      return argv[++i];
    };
    if (a == "--n") {
      const std::string_view v = value();
      std::size_t n = 0;
      const auto r = std::from_chars(v.data(), v.data() + v.size(), n);
      if (r.ec != std::errc() || r.ptr != v.data() + v.size() || n < 64 || n > 10000000) {
        usage_error("--n must be an integer in [64, 10000000] (got '" + std::string(v) + "')");
      }
      o.n = n;
    } else if (a == "--out") {
      o.out = std::string(value());
    } else if (a == "--kernel") {
      o.filter = std::string(value());
    } else if (a == "--help" || a == "-h") {
      std::printf(
          "usage: glintlab_accuracy [--n N] [--out FILE] [--kernel SUBSTRING]\n"
          "  N rows per kernel (64..10000000, default 200000) of core/simd/inputs.h's edge-case\n"
          "  inputs; FILE default out/bench/accuracy.csv.\n");
      std::exit(0);
    } else {
      usage_error("unknown argument '" + std::string(a) +
                  "' (valid: --n N, --out FILE, --kernel SUBSTRING)");
    }
  }
  return o;
}

using Table = std::vector<std::vector<double>>;  // [output column][row]

template <class S>
Table evaluate(int kernel, const Table& inputs, std::size_t n, Isa isa, Math math) {
  std::vector<std::vector<S>> in;
  std::vector<Column<S>> cols;
  for (const auto& c : inputs) in.emplace_back(c.begin(), c.end());
  for (const auto& c : in) cols.push_back({c.data(), 1});
  std::vector<std::vector<S>> out(kernel_info(kernel).outputs.size(), std::vector<S>(n));
  std::vector<S*> outs;
  for (auto& c : out) outs.push_back(c.data());
  eval_batch(kernel, std::span<const Column<S>>(cols), std::span<S* const>(outs), n, isa, math);
  Table r;
  for (const auto& c : out) r.emplace_back(c.begin(), c.end());
  return r;
}

struct Reference {
  Table values;
  std::vector<double> floor;  // per output column
};

Reference make_reference(int kernel, const Table& inputs, std::size_t n) {
  Reference ref{evaluate<double>(kernel, inputs, n, Isa::kScalar, Math::kExact), {}};
  for (const auto& col : ref.values) {
    std::vector<double> mags;
    for (double v : col) {
      if (std::isfinite(v) && v != 0.0) mags.push_back(std::abs(v));
    }
    double median = 1.0;
    if (!mags.empty()) {
      auto mid = mags.begin() + std::ptrdiff_t(mags.size() / 2);
      std::nth_element(mags.begin(), mid, mags.end());
      median = *mid;
    }
    ref.floor.push_back(kRelFloor * median);
  }
  return ref;
}

struct Errors {
  std::size_t compared = 0, nonfinite_mismatch = 0;
  double max_abs = 0.0, max_rel = 0.0, rms_rel = 0.0, p99_rel = 0.0;
};

Errors compare(const Table& y, const Reference& ref) {
  Errors e;
  std::vector<double> rel;
  double sum_sq = 0.0;
  for (std::size_t c = 0; c < y.size(); ++c) {
    for (std::size_t i = 0; i < y[c].size(); ++i) {
      const double a = y[c][i], r = ref.values[c][i];
      if (!std::isfinite(a) || !std::isfinite(r)) {
        const bool same = (std::isnan(a) && std::isnan(r)) || a == r;
        if (same) {
          rel.push_back(0.0);
        } else {
          ++e.nonfinite_mismatch;
        }
        continue;
      }
      const double abs_err = std::abs(a - r);
      const double rel_err = abs_err / std::max(std::abs(r), ref.floor[c]);
      e.max_abs = std::max(e.max_abs, abs_err);
      e.max_rel = std::max(e.max_rel, rel_err);
      sum_sq += rel_err * rel_err;  // summed in index order: deterministic
      rel.push_back(rel_err);
    }
  }
  e.compared = rel.size();
  if (!rel.empty()) {
    e.rms_rel = std::sqrt(sum_sq / double(rel.size()));
    const std::size_t k = std::min(rel.size() - 1, (rel.size() * 99) / 100);
    std::nth_element(rel.begin(), rel.begin() + std::ptrdiff_t(k), rel.end());
    e.p99_rel = rel[k];
  }
  return e;
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6e", v);
  return buf;
}

int run(const Options& o) {
  const std::uint64_t seed = hash_string("experiments/bench/accuracy");
  // Reference kernel of each kernel: itself, or the exact formula of kVariants.
  std::vector<std::pair<int, int>> jobs;  // (kernel, reference)
  for (int k = 0; k < kernel_count(); ++k) {
    const std::string_view name = kernel_info(k).name;
    if (!o.filter.empty() && name.find(o.filter) == std::string_view::npos) continue;
    jobs.emplace_back(k, k);
    for (const Variant& v : kVariants) {
      if (v.kernel != name) continue;
      const std::optional<int> r = find_kernel(v.reference);
      if (!r)
        throw std::logic_error("accuracy: unknown reference kernel " + std::string(v.reference));
      const auto a = kernel_info(k).inputs, b = kernel_info(*r).inputs;
      if (!std::equal(a.begin(), a.end(), b.begin(), b.end())) {
        throw std::logic_error("accuracy: " + std::string(name) + " and " +
                               std::string(v.reference) + " take different inputs");
      }
      jobs.emplace_back(k, *r);
    }
  }
  if (jobs.empty()) usage_error("--kernel '" + o.filter + "' matches no kernel");

  // An unwritable --out is bad input (exit 2), checked before any work.
  std::optional<io::AtomicFile> opened;
  try {
    if (o.out.has_parent_path()) std::filesystem::create_directories(o.out.parent_path());
    opened.emplace(o.out);
  } catch (const std::exception& e) {
    usage_error("--out: cannot write '" + o.out.string() + "': " + e.what());
  }
  io::AtomicFile& file = *opened;
  auto& csv = file.stream();
  csv << "method,kernel,isa,math,reference,n,compared,nonfinite_mismatch,max_abs_error,"
         "max_rel_error,rms_rel_error,p99_rel_error\n";
  std::map<int, Table> inputs;  // by kernel: float-rounded inputs (held as double)
  std::map<int, Reference> references;
  for (const auto& [k, r] : jobs) {
    if (!inputs.count(k)) {
      Table in = make_inputs(kernel_info(k).inputs, o.n, seed);
      for (auto& c : in) {
        for (double& v : c) v = double(float(v));
      }
      inputs.emplace(k, std::move(in));
    }
    const Table& in = inputs.at(k);
    if (!references.count(r)) references.emplace(r, make_reference(r, in, o.n));
    const Reference& ref = references.at(r);
    const std::string method(kernel_info(r).name), kernel(kernel_info(k).name);
    for (Isa isa : kAllIsas) {
      if (!isa_supported(isa)) continue;
      struct Flavour {
        const char* name;
        bool dbl;
        Math math;
      };
      for (const Flavour f :
           {Flavour{"float_exact", false, Math::kExact}, Flavour{"float_fast", false, Math::kFast},
            Flavour{"double_exact", true, Math::kExact}}) {
        const Table y = f.dbl ? evaluate<double>(k, in, o.n, isa, f.math)
                              : evaluate<float>(k, in, o.n, isa, f.math);
        const Errors e = compare(y, ref);
        csv << method << ',' << kernel << ',' << isa_name(isa) << ',' << f.name << ',' << method
            << "/scalar/double_exact," << o.n << ',' << e.compared << ',' << e.nonfinite_mismatch
            << ',' << fmt(e.max_abs) << ',' << fmt(e.max_rel) << ',' << fmt(e.rms_rel) << ','
            << fmt(e.p99_rel) << '\n';
      }
    }
  }
  file.commit();
  std::fprintf(stderr, "glintlab_accuracy: %zu kernel/reference pairs, %zu rows each -> %s\n",
               jobs.size(), o.n, o.out.string().c_str());
  return 0;
}

}  // namespace
}  // namespace glintlab::simd::accuracy

int main(int argc, char** argv) {
  using namespace glintlab::simd::accuracy;
  const Options o = parse(argc, argv);
  try {
    return run(o);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "glintlab: error: %s\n", e.what());
    return 1;
  }
}
