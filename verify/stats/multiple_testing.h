// Multiple-testing control: Holm–Šidák step-down over a family of raw p-values, and the Šidák
// combination of a minimum p-value over k tests. The family-wise false-positive rate of a whole
// verification suite run is set here, in one place.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace glintlab::verify {

// Family-wise false-positive rate per suite run: the probability that a run of the whole suite
// rejects any true claim. Every statistical check's share of it is derived from this constant.
inline constexpr double kFamilyWiseRate = 1e-3;

// Šidák: the probability that the smallest of k independent uniform p-values is ≤ p_min,
// 1 − (1 − p_min)^k, computed as −expm1(k·log1p(−p_min)) so tiny p keep their precision.
// Exact for independent tests, conservative for positively dependent ones.
double sidak(double p_min, std::size_t k);

// Šidák-adjusted minimum of the given raw p-values (1 when the list is empty).
double sidak_min(std::span<const double> p);

// The per-test level that gives family-wise rate alpha over k independent tests: 1 − (1 − α)^{1/k}.
double sidak_level(double alpha, std::size_t k);

struct HolmSidakResult {
  std::vector<double> raw;       // the input p-values, in input order
  std::vector<double> adjusted;  // Holm–Šidák adjusted p-values, in input order
  std::vector<bool> reject;      // adjusted ≤ alpha
  double alpha = kFamilyWiseRate;
  std::size_t rejections = 0;
};

// Holm–Šidák step-down at family-wise rate alpha. With p sorted ascending, p_(1) ≤ … ≤ p_(m),
// adjusted p_(i) = max_{j ≤ i} [1 − (1 − p_(j))^{m − j + 1}]; ties keep input order. Rejecting
// where adjusted ≤ α is the step-down procedure (stop at the first p_(i) above its level
// 1 − (1 − α)^{1/(m − i + 1)}). NaN p-values are treated as 1 (never rejected).
HolmSidakResult holm_sidak(std::span<const double> p, double alpha = kFamilyWiseRate);

}  // namespace glintlab::verify
