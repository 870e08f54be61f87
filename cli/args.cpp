// Shared argument validation; see args.h.
#include "cli/args.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <cstdio>

#include "core/io/csv.h"

namespace glintlab::cli {
namespace {

// Quotes user text for a message, cut short and with control characters replaced.
std::string quoted(std::string_view s) {
  constexpr std::size_t kMax = 40;
  std::string out = "'";
  for (char c : s.substr(0, kMax)) {
    const auto u = static_cast<unsigned char>(c);
    out += (u < 0x20 || u == 0x7f) ? '?' : c;
  }
  if (s.size() > kMax) out += "...";
  return out + "'";
}

}  // namespace

NdfKind parse_ndf(std::string_view text, std::string_view where) {
  if (text == "ggx") return NdfKind::kGGX;
  if (text == "beckmann") return NdfKind::kBeckmann;
  throw InputError(fmt::format("{}: unknown ndf {} (valid: {})", where, quoted(text), kNdfNames));
}

std::string_view ndf_name(NdfKind kind) { return kind == NdfKind::kGGX ? "ggx" : "beckmann"; }

std::string canonical_spelling(std::string_view option, std::string_view text) {
  struct Alias {
    std::string_view option, alias, canonical;
  };
  static constexpr Alias kAliases[] = {{"--sampler", "caps", "spherical_caps"},
                                       {"--sampler", "bounded", "bounded_caps"},
                                       {"--bound", "exact-isotropic", "exact_isotropic"}};
  for (const Alias& a : kAliases) {
    if (a.option == option && a.alias == text) {
      fmt::print(stderr, "glintlab: note: {} {} is spelled {}\n", option, text, a.canonical);
      return std::string(a.canonical);
    }
  }
  return std::string(text);
}

void check_alpha(double alpha, std::string_view where) {
  if (!(std::isfinite(alpha) && alpha > 0.0)) {
    throw InputError(
        fmt::format("{}: roughness {} is out of range (valid: finite and > 0)", where, alpha));
  }
}

void check_unit(Vec3<double> w, std::string_view where) {
  const double len = std::sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
  if (!(std::abs(len - 1.0) <= kUnitTolerance)) {
    throw InputError(fmt::format(
        "{}: direction ({}, {}, {}) has length {}, not unit (valid: |length - 1| <= 1e-6)", where,
        w.x, w.y, w.z, len));
  }
}

double parse_number(std::string_view text, std::string_view where, std::string_view valid) {
  if (const auto v = io::parse_finite_double(text)) return *v;
  throw InputError(
      fmt::format("{}: {} {} (valid: {})", where, quoted(text), io::number_problem(text), valid));
}

std::vector<double> parse_number_list(std::string_view text, std::string_view where,
                                      std::string_view valid) {
  std::vector<double> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::size_t end = comma == std::string_view::npos ? text.size() : comma;
    std::string_view item = text.substr(start, end - start);
    while (!item.empty() && item.front() == ' ') item.remove_prefix(1);
    while (!item.empty() && item.back() == ' ') item.remove_suffix(1);
    out.push_back(parse_number(item, where, valid));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

Vec3<double> parse_unit_direction(std::string_view text, std::string_view where) {
  constexpr std::string_view kValid = "three comma-separated numbers x,y,z of a unit vector";
  const std::vector<double> v = parse_number_list(text, where, kValid);
  if (v.size() != 3) {
    throw InputError(
        fmt::format("{}: '{}' has {} values (valid: {})", where, text, v.size(), kValid));
  }
  const Vec3<double> w{v[0], v[1], v[2]};
  check_unit(w, where);
  return w;
}

std::uint64_t parse_integer(std::string_view text, std::string_view where, std::uint64_t lo,
                            std::uint64_t hi) {
  std::string_view digits = text;
  const bool negative = !digits.empty() && digits.front() == '-';
  if (negative) digits.remove_prefix(1);
  std::uint64_t v = 0;
  const char* first = digits.data();
  const char* last = first + digits.size();
  const auto [ptr, ec] = std::from_chars(first, last, v, 10);
  const bool syntax_ok = !digits.empty() && digits.front() != '+' && ptr == last &&
                         (ec == std::errc() || ec == std::errc::result_out_of_range);
  const bool in_range =
      syntax_ok && ec == std::errc() && (!negative || v == 0) && lo <= v && v <= hi;
  if (!in_range) {
    throw InputError(fmt::format("{}: {} is {} (valid: an integer in [{}, {}])", where,
                                 quoted(text), syntax_ok ? "out of range" : "not an integer", lo,
                                 hi));
  }
  return v;
}

}  // namespace glintlab::cli
