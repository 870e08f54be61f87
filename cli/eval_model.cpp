// `glintlab eval --model`: evaluates a registered model (core/model_registry.h) on query rows and
// writes value, pdf and the model's intermediates.
#include "cli/eval_model.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <optional>
#include <string_view>

#include "cli/args.h"
#include "cli/commands.h"
#include "core/io/atomic_file.h"
#include "core/io/csv.h"
#include "core/model_registry.h"

namespace glintlab::cli {
namespace {

// Query columns in output order; which are required depends on the model's needs.
constexpr std::array<std::string_view, 14> kColumns = {"u",
                                                       "v",
                                                       "dudx",
                                                       "dvdx",
                                                       "dudy",
                                                       "dvdy",
                                                       "wi_x",
                                                       "wi_y",
                                                       "wi_z",
                                                       "wo_x",
                                                       "wo_y",
                                                       "wo_z",
                                                       "light_cos_half_angle",
                                                       "light_intensity"};
constexpr std::size_t kFootprintBegin = 0, kFootprintEnd = 6, kDirBegin = 6, kDirEnd = 12,
                      kLightBegin = 12, kLightEnd = 14;
constexpr std::array<double, 14> kDefaults = {0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 1, 1, 1};
// The footprint's corner reflection vectors (core/model.h FootprintQuery::corner_r): read and
// written only for models that need them (kNeedsPixelCorners).
constexpr std::array<std::string_view, 12> kCornerColumns = {
    "r0_x", "r0_y", "r0_z", "r1_x", "r1_y", "r1_z", "r2_x", "r2_y", "r2_z", "r3_x", "r3_y", "r3_z"};

std::vector<std::pair<std::string, std::string>> split_params(
    const std::vector<std::string>& texts) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const std::string& t : texts) {
    const std::size_t eq = t.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw InputError(
          fmt::format("--param: '{}' is not of the form name=value (see glintlab models)", t));
    }
    out.emplace_back(t.substr(0, eq), t.substr(eq + 1));
  }
  return out;
}

}  // namespace

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
                                       a disk of radius > 0)
and --out has every one of those columns (defaults filled in), then
  value   f(wi, wo) max(wo.z, 0): the cosine-weighted BRDF
  pdf     the density of wo (per steradian) under the model's sampler for this wi
  ...     the model's intermediates, named as 'glintlab models' lists them.)";

void run_model_eval(const std::string& model_name, const std::vector<std::string>& param_texts,
                    const std::string& in_path, const std::string& out_path) {
  const ModelEntry* model = nullptr;
  std::vector<double> params;
  try {
    model = &find_model(model_name);
    params = resolve_params(*model, split_params(param_texts));
  } catch (const ModelParamError& e) {
    throw InputError(e.what());
  }
  io::CsvTable table = [&] {
    try {
      return io::read_csv(in_path);
    } catch (const io::CsvError& e) {
      throw InputError(std::string("--in ") + e.what());
    }
  }();

  const bool need_fp = (model->needs & kNeedsFootprint) != 0;
  const bool need_light = (model->needs & (kNeedsPointLight | kNeedsAreaLight)) != 0;
  const bool need_corners = (model->needs & kNeedsPixelCorners) != 0;
  std::array<std::optional<std::size_t>, kCornerColumns.size()> corner_col;
  std::array<std::optional<std::size_t>, kColumns.size()> col;
  std::string missing;
  for (std::size_t i = 0; i < kColumns.size(); ++i) {
    col[i] = table.find_column(kColumns[i]);
    const bool required = (i >= kDirBegin && i < kDirEnd) ||
                          (need_fp && i >= kFootprintBegin && i < kFootprintEnd) ||
                          (need_light && i >= kLightBegin && i < kLightEnd);
    if (required && !col[i])
      missing += fmt::format("{}{}", missing.empty() ? "" : ", ", kColumns[i]);
  }
  for (std::size_t i = 0; i < kCornerColumns.size() && need_corners; ++i) {
    corner_col[i] = table.find_column(kCornerColumns[i]);
    if (!corner_col[i])
      missing += fmt::format("{}{}", missing.empty() ? "" : ", ", kCornerColumns[i]);
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
                                 table.source(), missing, model->name,
                                 describe_needs(model->needs)));
  }

  // Read and validate every row before anything is written.
  std::vector<std::array<double, kColumns.size()>> rows(table.num_rows());
  std::vector<std::array<double, kCornerColumns.size()>> corner_rows(table.num_rows());
  std::vector<ModelQuery<double>> queries(table.num_rows());
  for (std::size_t r = 0; r < table.num_rows(); ++r) {
    auto& v = rows[r];
    for (std::size_t i = 0; i < kColumns.size(); ++i) {
      v[i] = kDefaults[i];
      if (!col[i]) continue;
      try {
        v[i] = table.number(r, *col[i]);
      } catch (const io::CsvError& e) {
        throw InputError(std::string("--in ") + e.what());
      }
    }
    ModelQuery<double>& q = queries[r];
    q.footprint = {{v[0], v[1]}, {v[2], v[3]}, {v[4], v[5]}};
    q.wi = {v[6], v[7], v[8]};
    q.wo = {v[9], v[10], v[11]};
    q.light = {v[12], v[13]};
    check_unit(q.wi, fmt::format("--in {}, columns wi_x,wi_y,wi_z (wi)", table.where(r)));
    check_unit(q.wo, fmt::format("--in {}, columns wo_x,wo_y,wo_z (wo)", table.where(r)));
    if (!(v[12] >= -1 && v[12] <= 1)) {
      throw InputError(fmt::format("--in {}: {} is out of range (valid: [-1, 1])",
                                   table.where(r, *col[12]), v[12]));
    }
    if (!(v[13] >= 0)) {
      throw InputError(fmt::format("--in {}: {} is out of range (valid: >= 0)",
                                   table.where(r, *col[13]), v[13]));
    }
    if (!need_corners) continue;
    auto& cv = corner_rows[r];
    for (std::size_t i = 0; i < kCornerColumns.size(); ++i) {
      try {
        cv[i] = table.number(r, *corner_col[i]);
      } catch (const io::CsvError& e) {
        throw InputError(std::string("--in ") + e.what());
      }
    }
    for (std::size_t c = 0; c < 4; ++c) {
      q.footprint.corner_r[c] = {cv[3 * c], cv[3 * c + 1], cv[3 * c + 2]};
      check_unit(q.footprint.corner_r[c],
                 fmt::format("--in {}, columns r{}_x,r{}_y,r{}_z (corner reflection vector)",
                             table.where(r), c, c, c));
    }
    if (!(v[12] < 1)) {
      throw InputError(fmt::format(
          "--in {}: light_cos_half_angle = {} is out of range (valid: < 1, a disk of radius > 0)",
          table.where(r, *col[12]), v[12]));
    }
    if (!(v[11] > 0)) {
      throw InputError(fmt::format(
          "--in {}: wo_z = {} is out of range (valid: > 0, the disk's centre above the surface)",
          table.where(r, *col[11]), v[11]));
    }
  }

  std::vector<std::string_view> header(kColumns.begin(), kColumns.end());
  if (need_corners) header.insert(header.end(), kCornerColumns.begin(), kCornerColumns.end());
  header.push_back("value");
  header.push_back("pdf");
  header.insert(header.end(), model->intermediates.begin(), model->intermediates.end());
  try {
    io::AtomicFile file(out_path);
    {
      io::CsvWriter w(file.stream(), header);
      for (std::size_t r = 0; r < rows.size(); ++r) {
        for (double x : rows[r]) w.cell(x);
        if (need_corners)
          for (double x : corner_rows[r]) w.cell(x);
        const ErasedEval e = model->eval(params, queries[r]);
        w.cell(e.value).cell(e.pdf);
        for (double x : e.intermediates) w.cell(x);
        w.end_row();
      }
    }
    file.commit();
  } catch (const std::runtime_error& e) {
    throw InputError(std::string("--out: ") + e.what());
  }
}

}  // namespace glintlab::cli
