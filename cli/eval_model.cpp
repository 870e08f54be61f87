// `glintlab eval --model`: evaluates a registered model (core/model_registry.h) on query rows and
// writes value, pdf and the model's intermediates.
#include "cli/eval_model.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <string_view>
#include <vector>

#include "cli/args.h"
#include "cli/batch_options.h"
#include "cli/commands.h"
#include "cli/input.h"
#include "cli/model_options.h"
#include "cli/out_csv.h"
#include "core/io/csv.h"
#include "core/model_layout.h"
#include "core/model_registry.h"
#include "core/simd/model_batch.h"

namespace glintlab::cli {
namespace {

// Query columns in output order (core/model_layout.h); which are required depends on the model's
// needs. The corner reflection vectors (QueryPart::kCorners) are read and written only for models
// that need them, as the batch API's optional trailing columns.
constexpr auto kColumns = simd::kQueryColumns;
constexpr auto kCornerColumns = simd::kCornerColumns;

bool part_needed(QueryPart part, unsigned needs) {
  switch (part) {
    case QueryPart::kDirections:
      return true;
    case QueryPart::kFootprint:
      return (needs & kNeedsFootprint) != 0;
    case QueryPart::kLight:
      return (needs & (kNeedsPointLight | kNeedsAreaLight)) != 0;
    case QueryPart::kCorners:
      return (needs & kNeedsPixelCorners) != 0;
  }
  return false;
}

// --grid: a product of angle ranges. Names in row order (outermost first).
constexpr std::array<std::string_view, 4> kGridNames = {"theta_i", "phi_i", "theta_o", "phi_o"};
constexpr std::uint64_t kMaxGridRows = 100000000;

struct GridAxis {
  double lo = 0, hi = 0;
  std::uint64_t count = 1;
  double at(std::uint64_t k) const {
    return count == 1 ? lo : lo + (hi - lo) * double(k) / double(count - 1);
  }
};

std::array<GridAxis, 4> parse_grid(const std::string& text) {
  constexpr const char* kValid =
      "comma-separated name=lo:hi:count with names theta_i, phi_i, theta_o, phi_o (degrees; "
      "theta in [0, 180], count in [1, 10000])";
  std::array<GridAxis, 4> axes{};
  std::array<bool, 4> seen{};
  for (const std::string& item : split_list(text, "--grid", kValid)) {
    const std::size_t eq = item.find('=');
    std::size_t a = 0;
    while (a < kGridNames.size() &&
           (eq == std::string::npos || item.substr(0, eq) != kGridNames[a]))
      ++a;
    if (a == kGridNames.size()) {
      throw InputError(fmt::format("--grid: '{}' is not a known axis (valid: {})", item, kValid));
    }
    if (seen[a])
      throw InputError(
          fmt::format("--grid {}: given twice (valid: each axis once)", kGridNames[a]));
    seen[a] = true;
    const std::string range = item.substr(eq + 1);
    const std::size_t c1 = range.find(':'),
                      c2 = range.find(':', c1 == std::string::npos ? 0 : c1 + 1);
    if (c1 == std::string::npos || c2 == std::string::npos) {
      throw InputError(fmt::format("--grid {}: '{}' is not lo:hi:count (valid: {})", kGridNames[a],
                                   range, kValid));
    }
    const std::string where = fmt::format("--grid {}", kGridNames[a]);
    GridAxis& g = axes[a];
    g.lo = parse_number(range.substr(0, c1), where, kValid);
    g.hi = parse_number(range.substr(c1 + 1, c2 - c1 - 1), where, kValid);
    g.count = parse_integer(range.substr(c2 + 1), where, 1, 10000);
    const bool theta = a == 0 || a == 2;
    if (theta && !(g.lo >= 0 && g.lo <= 180 && g.hi >= 0 && g.hi <= 180)) {
      throw InputError(
          fmt::format("--grid {}: '{}' is out of range (valid: {})", kGridNames[a], range, kValid));
    }
  }
  std::uint64_t rows = 1;
  for (const GridAxis& g : axes) rows *= g.count;
  if (rows > kMaxGridRows) {
    throw InputError(fmt::format("--grid: {} rows (valid: at most {})", rows, kMaxGridRows));
  }
  return axes;
}

Vec3<double> direction_deg(double theta, double phi) {
  const double t = theta * std::numbers::pi / 180, p = phi * std::numbers::pi / 180;
  // Exact poles (sin(π) is 1.2e-16, not 0): +z at 0°, −z at 180°.
  const double st = theta == 0 || theta == 180 ? 0.0 : std::sin(t);
  const double ct = theta == 0 ? 1.0 : theta == 180 ? -1.0 : theta == 90 ? 0.0 : std::cos(t);
  return {st * std::cos(p), st * std::sin(p), ct};
}

// Evaluates the model on SoA query columns in chunks (core/simd/model_batch.h).
std::vector<std::vector<double>> evaluate_columns(const ModelEntry& model,
                                                  const std::vector<double>& params,
                                                  const std::vector<std::vector<double>>& query,
                                                  std::size_t n, const BatchOptions& o) {
  std::vector<std::vector<double>> out(2 + model.intermediates.size(), std::vector<double>(n));
  const auto run = [&]<class S>(const std::vector<std::vector<S>>& q) {
    std::vector<std::vector<S>> res;
    if constexpr (std::is_same_v<S, float>) res.assign(out.size(), std::vector<float>(n));
    for_each_chunk(n, o, [&](std::size_t begin, std::size_t count) {
      std::vector<simd::Column<S>> cols;
      for (const auto& c : q) cols.push_back({c.data() + begin, 1});
      std::vector<S*> outs;
      for (std::size_t k = 0; k < out.size(); ++k) {
        if constexpr (std::is_same_v<S, float>) {
          outs.push_back(res[k].data() + begin);
        } else {
          outs.push_back(out[k].data() + begin);
        }
      }
      simd::eval_batch(model, params, cols, outs, count, o.isa, o.math);
    });
    if constexpr (std::is_same_v<S, float>)
      for (std::size_t k = 0; k < out.size(); ++k) out[k].assign(res[k].begin(), res[k].end());
  };
  if (o.float_precision) {
    std::vector<std::vector<float>> qf;
    for (const auto& c : query) qf.emplace_back(c.begin(), c.end());
    run(qf);
  } else {
    run(query);
  }
  return out;
}

// Reads and validates every row of --in into the query columns before anything is written.
void read_queries(const ModelEntry& model, const std::string& in_path,
                  std::vector<std::vector<double>>& query,
                  std::vector<std::vector<double>>& corners, std::size_t& n) {
  io::CsvTable table = [&] {
    try {
      return io::read_csv(in_path);
    } catch (const io::CsvError& e) {
      throw InputError(std::string("--in ") + e.what());
    }
  }();

  const bool need_corners = part_needed(QueryPart::kCorners, model.needs);
  // Layout columns present in the file (the corners only for models that read them).
  std::array<std::optional<std::size_t>, kQueryLayout.size()> col;
  std::string missing;
  for (std::size_t i = 0; i < kQueryLayout.size(); ++i) {
    const QueryColumn& c = kQueryLayout[i];
    if (c.part == QueryPart::kCorners && !need_corners) continue;
    col[i] = table.find_column(c.name);
    if (part_needed(c.part, model.needs) && !col[i])
      missing += fmt::format("{}{}", missing.empty() ? "" : ", ", c.name);
  }
  for (const std::string& name : table.header()) {
    bool known = false;
    for (std::string_view c : kColumns) known = known || name == c;
    for (std::string_view c : kCornerColumns) known = known || (need_corners && name == c);
    if (!known) {
      throw InputError(fmt::format(
          "--in '{}' header row: unknown column '{}' (valid: {}{}{})", table.source(), name,
          fmt::join(kColumns, ","), need_corners ? "," : "",
          need_corners ? fmt::format("{}", fmt::join(kCornerColumns, ",")) : std::string()));
    }
  }
  if (!missing.empty()) {
    throw InputError(fmt::format("--in '{}' header row: missing column(s) {} (model {}: {})",
                                 table.source(), missing, model.name, describe_needs(model.needs)));
  }

  // Read and validate every row before anything is written.
  n = table.num_rows();
  for (auto& c : query) c.assign(n, 0.0);
  corners.assign(need_corners ? kCornerColumns.size() : 0, std::vector<double>(n, 0.0));
  const auto read = [&](std::size_t r, std::size_t i) {
    if (!col[i]) return kQueryLayout[i].default_value;
    try {
      return table.number(r, *col[i]);
    } catch (const io::CsvError& e) {
      throw InputError(std::string("--in ") + e.what());
    }
  };
  for (std::size_t r = 0; r < table.num_rows(); ++r) {
    QueryRow<double> v{};
    for (std::size_t i = 0; i < kColumns.size(); ++i) v[i] = query[i][r] = read(r, i);
    if (need_corners) {
      for (std::size_t i = kColumns.size(); i < kQueryLayout.size(); ++i)
        v[i] = corners[i - kColumns.size()][r] = read(r, i);
    }
    check_query_row(model, v, [&](std::string_view column) {
      std::size_t i = 0;
      while (i < kQueryLayout.size() && kQueryLayout[i].name != column) ++i;
      return "--in " +
             (i < kQueryLayout.size() && col[i] ? table.where(r, *col[i]) : table.where(r));
    });
  }
}

}  // namespace

void check_query_row(const ModelEntry& model, const QueryRow<double>& v,
                     const std::function<std::string(std::string_view column)>& at) {
  constexpr std::size_t kCos = query_column_index("light_cos_half_angle"),
                        kIntensity = query_column_index("light_intensity");
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (kQueryLayout[i].part == QueryPart::kCorners &&
        !part_needed(QueryPart::kCorners, model.needs))
      continue;
    if (!std::isfinite(v[i])) {
      throw InputError(fmt::format("{}: {} = {} is not finite (valid: a finite number)",
                                   at(kQueryLayout[i].name), kQueryLayout[i].name, v[i]));
    }
  }
  const ModelQuery<double> row_query = from_row(v);
  // The message (and `at`) only for a direction that fails: this runs on every row of a batch.
  const auto unit = [&](const Vec3<double>& w, const auto& where) {
    if (!(std::abs(std::sqrt(w.x * w.x + w.y * w.y + w.z * w.z) - 1.0) <= kUnitTolerance))
      check_unit(w, where());
  };
  unit(row_query.wi, [&] { return at("") + ", columns wi_x,wi_y,wi_z (wi)"; });
  unit(row_query.wo, [&] { return at("") + ", columns wo_x,wo_y,wo_z (wo)"; });
  if (!(v[kCos] >= -1 && v[kCos] <= 1)) {
    throw InputError(fmt::format("{}: {} is out of range (valid: [-1, 1])",
                                 at("light_cos_half_angle"), v[kCos]));
  }
  if (!(v[kIntensity] >= 0)) {
    throw InputError(
        fmt::format("{}: {} is out of range (valid: >= 0)", at("light_intensity"), v[kIntensity]));
  }
  if (part_needed(QueryPart::kCorners, model.needs)) {
    for (std::size_t c = 0; c < row_query.footprint.corner_r.size(); ++c) {
      unit(row_query.footprint.corner_r[c], [&] {
        return fmt::format("{}, columns r{}_x,r{}_y,r{}_z (corner reflection vector)", at(""), c,
                           c, c);
      });
    }
  }
  if (!model.validate) return;
  if (const std::optional<QueryViolation> bad = model.validate(row_query)) {
    std::size_t i = 0;
    while (i < kQueryLayout.size() && kQueryLayout[i].name != bad->column) ++i;
    throw InputError(fmt::format("{}: {} = {} is out of range (valid: {})", at(bad->column),
                                 bad->column, i < v.size() ? v[i] : 0.0, bad->valid));
  }
}

std::vector<std::string_view> needed_query_columns(const ModelEntry& model) {
  std::vector<std::string_view> out;
  for (const QueryColumn& c : kQueryLayout)
    if (c.part != QueryPart::kDirections && part_needed(c.part, model.needs)) out.push_back(c.name);
  return out;
}

QueryRow<double> parse_query_option(const ModelEntry& model, const std::string& text, bool given) {
  const std::vector<std::string_view> needed = needed_query_columns(model);
  const std::string valid = needed.empty()
                                ? std::string("no --query: the model needs only the directions")
                                : fmt::format("name=value for each of {}", fmt::join(needed, ", "));
  QueryRow<double> v{};
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = kQueryLayout[i].default_value;
  std::vector<bool> set(needed.size(), false);
  if (given) {
    for (const std::string& item : split_list(text, "--query", valid)) {
      const std::size_t eq = item.find('=');
      const std::string name = item.substr(0, std::min(eq, item.size()));
      std::size_t k = 0;
      while (k < needed.size() && needed[k] != name) ++k;
      if (eq == std::string::npos || k == needed.size()) {
        throw InputError(
            fmt::format("--query: '{}' is not a query column model {} needs (valid: {})", item,
                        model.name, valid));
      }
      if (set[k]) throw InputError(fmt::format("--query {}: given twice (valid: {})", name, valid));
      set[k] = true;
      std::string_view value(item);
      value.remove_prefix(eq + 1);
      while (!value.empty() && value.front() == ' ') value.remove_prefix(1);
      std::size_t i = 0;
      while (kQueryLayout[i].name != name) ++i;
      v[i] = parse_number(value, "--query " + name, "a finite number");
    }
  }
  std::string missing;
  for (std::size_t k = 0; k < needed.size(); ++k)
    if (!set[k]) missing += fmt::format("{}{}", missing.empty() ? "" : ", ", needed[k]);
  if (!missing.empty()) {
    throw InputError(fmt::format("--query: model {} needs {} ({}; valid: {})", model.name, missing,
                                 describe_needs(model.needs), valid));
  }
  return v;
}

const char* const kModelEvalFooter =
    R"(
WITH --model NAME (any model of 'glintlab models'; --param name=value, repeatable, sets its
parameters, the others keep their defaults): --in has the columns
  wi_x, wi_y, wi_z, wo_x, wo_y, wo_z   required; unit directions in the local frame (wi toward
                                       the viewer, wo toward the light)
  u, v, dudx, dvdx, dudy, dvdy         the pixel footprint: uv and the Jacobian d(u,v)/d(pixel);
                                       required when the model needs a footprint, else optional (0)
  light_cos_half_angle, light_intensity the light around wo: cosine of the cone half-angle in
                                       [-1, 1] (1 = a delta light) and its intensity (>= 0);
                                       required when the model needs a light, else optional (1)
  r0_x, r0_y, r0_z, ..., r3_z          the reflection vectors at the pixel corners (x-,y-),
                                       (x+,y-), (x-,y+), (x+,y+), unit, local frame; only for
                                       models that need them (podee: then wo_z > 0, the disk's
                                       centre above the surface, and light_cos_half_angle < 1,
                                       a disk of radius > 0); such models need --in, not --grid
and --out has every one of those columns (defaults filled in), then
  value   f(wi, wo) max(wo.z, 0): the cosine-weighted BRDF
  pdf     the density of wo (per steradian) under the model's sampler for this wi
  ...     the model's intermediates, named as 'glintlab models' lists them.
Instead of --in, --grid 'theta_i=lo:hi:count,phi_i=...,theta_o=...,phi_o=...' (degrees; theta in
[0, 180], count in [1, 10000], at most 1e8 rows; an axis left out is 0) evaluates the product of
the axes, theta_i outermost, phi_o innermost, wi and wo at those polar angles and azimuths;
--out then starts with the columns theta_i, phi_i, theta_o, phi_o (degrees). The other query
columns the model needs (the footprint, the light) are required in --query 'name=value,...', as
sample --model takes them (e.g. --query u=0.5,v=0.5,dudx=1e-3,dvdx=0,dudy=0,dvdy=1e-3), the
same for every row, and checked as --in rows are; the rest take their defaults.)";

void run_model_eval(const ModelEvalArgs& a) {
  const ResolvedModel resolved = resolve_model(a.model, a.params);
  const ModelEntry* model = resolved.model;
  const std::vector<double>& params = resolved.params;
  const BatchOptions opts = resolve_batch_options(a.batch);
  if (!a.grid.empty() && !a.in_path.empty()) {
    throw InputError("--grid: cannot be combined with --in (valid: one of them)");
  }
  if (a.grid.empty() && a.in_path.empty()) throw InputError("--in is required (or --grid)");
  if (a.query_given && a.grid.empty()) {
    throw InputError("--query: only with --grid (valid: with --in, the query columns of the file)");
  }

  const bool need_corners = (model->needs & kNeedsPixelCorners) != 0;
  if (need_corners && !a.grid.empty()) {
    throw InputError(fmt::format(
        "--grid: model {} needs the pixel-corner reflection vectors (valid: --in with columns "
        "r0_x..r3_z)",
        model->name));
  }
  // Query columns (SoA), and for --grid the angle columns written first.
  std::vector<std::vector<double>> query(kColumns.size());
  std::vector<std::vector<double>> angles, corners;
  std::size_t n = 0;
  const std::array<GridAxis, 4> g = a.grid.empty() ? std::array<GridAxis, 4>{} : parse_grid(a.grid);
  // A grid fills only the directions: the other columns the model needs come from --query, one
  // value each for every row (without them a footprint or light model would see the defaults, a
  // zero footprint, and return 0 everywhere). Checked once, with the directions the normal.
  QueryRow<double> fixed{};
  if (!a.grid.empty()) {
    fixed = parse_query_option(*model, a.query, a.query_given);
    check_query_row(*model, fixed, [](std::string_view column) {
      return column.empty() ? std::string("--query") : "--query " + std::string(column);
    });
  }
  check_output_file(a.out_path, "--out");
  if (!a.grid.empty()) {
    n = 1;
    for (const GridAxis& x : g) n *= std::size_t(x.count);
    // About 20 bytes per number written (17 significant digits, sign, exponent, comma).
    check_free_space(
        a.out_path, std::uint64_t(n) * (4 + kColumns.size() + 2 + model->intermediates.size()) * 20,
        "--out");
    for (std::size_t i = 0; i < kColumns.size(); ++i) query[i].assign(n, fixed[i]);
    angles.assign(4, std::vector<double>(n));
    std::size_t r = 0;
    for (std::uint64_t i0 = 0; i0 < g[0].count; ++i0)
      for (std::uint64_t i1 = 0; i1 < g[1].count; ++i1)
        for (std::uint64_t i2 = 0; i2 < g[2].count; ++i2)
          for (std::uint64_t i3 = 0; i3 < g[3].count; ++i3, ++r) {
            const double v[4] = {g[0].at(i0), g[1].at(i1), g[2].at(i2), g[3].at(i3)};
            for (int k = 0; k < 4; ++k) angles[std::size_t(k)][r] = v[k];
            ModelQuery<double> q{};
            q.wi = direction_deg(v[0], v[1]);
            q.wo = direction_deg(v[2], v[3]);
            const QueryRow<double> row = to_row(q);
            for (std::size_t c = 0; c < kColumns.size(); ++c)
              if (kQueryLayout[c].part == QueryPart::kDirections) query[c][r] = row[c];
          }
  } else {
    read_queries(*model, a.in_path, query, corners, n);
  }

  const auto with_corners = [&] {
    std::vector<std::vector<double>> q = query;
    q.insert(q.end(), corners.begin(), corners.end());
    return q;
  };
  const std::vector<std::vector<double>> results =
      corners.empty() ? evaluate_columns(*model, params, query, n, opts)
                      : evaluate_columns(*model, params, with_corners(), n, opts);

  std::vector<std::string_view> header;
  if (!angles.empty()) header.assign(kGridNames.begin(), kGridNames.end());
  header.insert(header.end(), kColumns.begin(), kColumns.end());
  header.insert(header.end(), kCornerColumns.begin(),
                kCornerColumns.begin() + std::ptrdiff_t(corners.size()));
  header.push_back("value");
  header.push_back("pdf");
  header.insert(header.end(), model->intermediates.begin(), model->intermediates.end());
  write_out_csv(a.out_path, header, [&](io::CsvWriter& w) {
    for (std::size_t r = 0; r < n; ++r) {
      for (const auto& c : angles) w.cell(c[r]);
      for (const auto& c : query) w.cell(c[r]);
      for (const auto& c : corners) w.cell(c[r]);
      for (const auto& c : results) w.cell(c[r]);
      w.end_row();
    }
  });
}

}  // namespace glintlab::cli
