// Stability maps as EXR + PNG + CSV files, one set per plane of a swept model × sampler.
#include "experiments/sweeps/stability_maps.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>

#include "core/io/atomic_file.h"
#include "core/io/csv.h"
#include "core/io/exr.h"
#include "core/io/png.h"

namespace glintlab::experiments {
namespace {

using verify::stability::CellStats;
using verify::stability::Defects;
using verify::stability::ModelSweep;
using verify::stability::SweepMap;

double frac(std::uint64_t k, std::uint64_t n) { return n ? double(k) / double(n) : 0; }

struct Channel {
  std::string name;
  std::function<double(const CellStats&)> get;
};

// The EXR channels of a quantity and the severity t ∈ [0, 1] the PNG shows (0 = clean).
struct QuantitySpec {
  std::vector<Channel> channels;
  std::function<double(const CellStats&)> severity;
  // For clean cells: the size of the quantity below its threshold in [0, 1] (blue brightness).
  std::function<double(const CellStats&)> shade = [](const CellStats&) { return 0.0; };
};

QuantitySpec defect_spec(const std::string& q, std::uint64_t Defects::*f, bool with_float) {
  QuantitySpec s;
  s.channels = {
      {q + "_value", [=](const CellStats& c) { return frac(c.value.*f, c.evals); }},
      {q + "_pdf", [=](const CellStats& c) { return frac(c.pdf.*f, c.pdf_calls); }},
      {q + "_sample", [=](const CellStats& c) { return frac(c.sample.*f, c.samples); }},
  };
  if (with_float) {
    s.channels.push_back(
        {q + "_value_float", [=](const CellStats& c) { return frac(c.value_f.*f, c.evals_f); }});
    s.channels.push_back(
        {q + "_pdf_float", [=](const CellStats& c) { return frac(c.pdf_f.*f, c.pdf_calls_f); }});
    s.channels.push_back({q + "_sample_float",
                          [=](const CellStats& c) { return frac(c.sample_f.*f, c.samples_f); }});
  }
  const auto channels = s.channels;
  s.severity = [channels](const CellStats& c) {
    double m = 0;
    for (const Channel& ch : channels) m = std::max(m, ch.get(c));
    // Any defect is visible: a single NaN in 10^4 calls still shows as yellow.
    return m > 0 ? 0.25 + 0.75 * std::min(1.0, m) : 0.0;
  };
  return s;
}

QuantitySpec quantity_spec(const std::string& q, bool with_float) {
  if (q == "nan") return defect_spec(q, &Defects::nan, with_float);
  if (q == "inf") return defect_spec(q, &Defects::inf, with_float);
  if (q == "negative") return defect_spec(q, &Defects::negative, with_float);
  QuantitySpec s;
  if (q == "energy_gain") {
    s.channels = {
        {"albedo_minus_1", [](const CellStats& c) { return c.albedo - 1; }},
        {"albedo_error", [](const CellStats& c) { return c.albedo_error; }},
        {"albedo_uniform_minus_1", [](const CellStats& c) { return c.albedo_uniform - 1; }},
        {"albedo_uniform_error", [](const CellStats& c) { return c.albedo_uniform_error; }},
        {"gain", [](const CellStats& c) { return c.gain(); }},
    };
    s.severity = [](const CellStats& c) {
      const double g = c.gain();
      return g > 0 ? 0.25 + 0.75 * std::min(1.0, g / 0.1) : 0.0;
    };
    s.shade = [](const CellStats& c) { return std::clamp(c.albedo, 0.0, 1.0); };
  } else if (q == "p_gt_1") {
    s.channels = {
        {"p_gt_1", [](const CellStats& c) { return frac(c.p_above_one, c.p_evals); }},
        {"p_max", [](const CellStats& c) { return c.p_max; }},
    };
    s.severity = [](const CellStats& c) {
      const double f = frac(c.p_above_one, c.p_evals);
      return f > 0 ? 0.25 + 0.75 * std::min(1.0, f) : 0.0;
    };
  } else {  // variance
    s.channels = {
        {"relative_variance", [](const CellStats& c) { return c.relative_variance; }},
        {"weight_max", [](const CellStats& c) { return c.weight_max; }},
        {"accepted_fraction", [](const CellStats& c) { return frac(c.accepted, c.samples); }},
    };
    s.severity = [](const CellStats& c) {
      if (!c.variance_blowup()) return 0.0;  // two decades above the threshold = full red
      return 0.25 +
             0.75 *
                 std::min(1.0,
                          std::log10(c.relative_variance / verify::stability::kVarianceBlowup) / 2);
    };
    s.shade = [](const CellStats& c) {
      return std::clamp(
          std::log1p(c.relative_variance) / std::log1p(verify::stability::kVarianceBlowup), 0.0,
          1.0);
    };
  }
  return s;
}

// Clean cells dark blue-grey brightening with `shade`, flagged ones from yellow (t = 0.25) to red
// (t = 1).
void colour(double t, double shade, double rgb[3]) {
  if (t <= 0) {
    rgb[0] = 0.03, rgb[1] = 0.05 + 0.25 * shade, rgb[2] = 0.09 + 0.6 * shade;
    return;
  }
  rgb[0] = 1, rgb[1] = std::clamp(1 - (t - 0.25) / 0.75, 0.0, 1.0), rgb[2] = 0;
}

void write_csv(const SweepMap& m, const ModelSweep& s, const std::filesystem::path& path) {
  const std::string row_col = m.plane.name;
  std::vector<std::string> header = {"model",     "sampler",     "row_index",      "column_index",
                                     row_col,     "theta_i_deg", "in_core_domain", "evals",
                                     "pdf_calls", "samples",     "accepted"};
  for (std::string q : {"nan", "inf", "negative"})
    for (std::string c : {"value", "pdf", "sample"}) {
      header.push_back(q + "_" + c + "_fraction");
      header.push_back(q + "_" + c + "_float_fraction");
    }
  for (std::string h : {"p_evals", "p_gt_1_fraction", "p_max", "albedo", "albedo_error",
                        "albedo_uniform", "albedo_uniform_error", "energy_gain",
                        "relative_variance", "variance_blowup", "weight_max", "float_swept"})
    header.push_back(h);
  std::vector<std::string_view> views(header.begin(), header.end());
  std::ostringstream text;
  {
    io::CsvWriter w(text, views);
    const std::size_t cols = m.plane.theta_deg.size();
    for (std::size_t i = 0; i < m.cells.size(); ++i) {
      const CellStats& c = m.cells[i];
      const double row = m.plane.rows[i / cols], th = m.plane.theta_deg[i % cols];
      w.cell(std::string_view(s.target.model->name)).cell(s.target.sampler);
      w.cell_int(static_cast<long long>(i / cols)).cell_int(static_cast<long long>(i % cols));
      w.cell(row).cell(th);
      w.cell_int(verify::stability::in_core_domain(m.plane, row, th) ? 1 : 0);
      w.cell_int(static_cast<long long>(c.evals)).cell_int(static_cast<long long>(c.pdf_calls));
      w.cell_int(static_cast<long long>(c.samples)).cell_int(static_cast<long long>(c.accepted));
      for (auto f : {&Defects::nan, &Defects::inf, &Defects::negative}) {
        w.cell(frac(c.value.*f, c.evals)).cell(frac(c.value_f.*f, c.evals_f));
        w.cell(frac(c.pdf.*f, c.pdf_calls)).cell(frac(c.pdf_f.*f, c.pdf_calls_f));
        w.cell(frac(c.sample.*f, c.samples)).cell(frac(c.sample_f.*f, c.samples_f));
      }
      w.cell_int(static_cast<long long>(c.p_evals)).cell(frac(c.p_above_one, c.p_evals));
      w.cell(c.p_max).cell(c.albedo).cell(c.albedo_error).cell(c.albedo_uniform);
      w.cell(c.albedo_uniform_error).cell(c.gain()).cell(c.relative_variance);
      w.cell_int(c.variance_blowup() ? 1 : 0).cell(c.weight_max).cell_int(s.has_float ? 1 : 0);
      w.end_row();
    }
    w.flush();
  }
  io::write_file_atomic(path, text.str());
}

}  // namespace

std::vector<std::string> map_quantities(const ModelSweep& s) {
  std::vector<std::string> q = {"nan", "inf", "negative", "energy_gain"};
  if (s.has_probability) q.push_back("p_gt_1");
  q.push_back("variance");
  return q;
}

std::vector<MapFile> write_stability_maps(const ModelSweep& s, const std::filesystem::path& root,
                                          const std::filesystem::path& rel) {
  std::filesystem::create_directories(root / rel);
  std::vector<MapFile> files;
  constexpr int kBlock = 16;  // PNG pixels per cell
  for (const SweepMap& m : s.maps) {
    const std::string csv = (rel / (m.plane.name + ".csv")).generic_string();
    write_csv(m, s, root / csv);
    const int w = int(m.plane.theta_deg.size()), h = int(m.plane.rows.size());
    for (const std::string& q : map_quantities(s)) {
      const QuantitySpec spec = quantity_spec(q, s.has_float);
      std::vector<std::string> names;
      for (const auto& ch : spec.channels) names.push_back(ch.name);
      Image exr(w, h, names);
      Image png(w * kBlock, h * kBlock, {"R", "G", "B"});
      for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
          const CellStats& c = m.at(std::size_t(y), std::size_t(x));
          for (std::size_t k = 0; k < spec.channels.size(); ++k)
            exr.at(x, y, k) = spec.channels[k].get(c);
          double rgb[3];
          colour(spec.severity(c), spec.shade(c), rgb);
          for (int by = 0; by < kBlock; ++by)
            for (int bx = 0; bx < kBlock; ++bx)
              for (std::size_t k = 0; k < 3; ++k) {
                // A one-pixel grid line between cells.
                const bool line = bx == 0 || by == 0;
                png.at(x * kBlock + bx, y * kBlock + by, k) = line ? 0.2 : rgb[k];
              }
        }
      const std::string stem = m.plane.name + "_" + q;
      const std::string exr_path = (rel / (stem + ".exr")).generic_string();
      const std::string png_path = (rel / (stem + ".png")).generic_string();
      std::string rows, cols;
      for (double r : m.plane.rows) rows += fmt::format("{}{:g}", rows.empty() ? "" : ",", r);
      for (double t : m.plane.theta_deg) cols += fmt::format("{}{:g}", cols.empty() ? "" : ",", t);
      io::write_exr(root / exr_path, exr,
                    {{"glintlab_model", std::string(s.target.model->name)},
                     {"glintlab_sampler", s.target.sampler},
                     {"glintlab_quantity", q},
                     {"glintlab_rows", m.plane.row_label + ": " + rows},
                     {"glintlab_columns", "theta_i_deg: " + cols}});
      io::write_png_preview(root / png_path, png);
      files.push_back({q, m.plane.name, png_path, exr_path, csv});
    }
  }
  return files;
}

}  // namespace glintlab::experiments
