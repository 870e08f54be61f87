// Failure regions of a stability sweep, in words, from the measured maps.
#include "verify/stability/failure_region.h"

#include <fmt/format.h>

#include <algorithm>
#include <functional>

namespace glintlab::verify::stability {
namespace {

// Three significant digits for parameters; up to six for angles (89.999° must not read as 90°).
std::string format_value(double v, bool angle) {
  return angle ? fmt::format("{:.6g}", v) : fmt::format("{:.3g}", v);
}

// The flagged indices of one axis in words: every value, one side of the range, an interval, or
// the list of values.
std::string describe_axis(const std::vector<double>& values, const std::vector<bool>& flagged,
                          const std::string& symbol, const std::string& unit) {
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < flagged.size(); ++i)
    if (flagged[i]) idx.push_back(i);
  if (idx.size() == values.size()) return fmt::format("every {}", symbol);
  const bool contiguous = idx.back() - idx.front() + 1 == idx.size();
  auto v = [&](std::size_t i) { return format_value(values[i], !unit.empty()) + unit; };
  if (idx.size() == 1) return fmt::format("{} = {}", symbol, v(idx[0]));
  if (contiguous && idx.front() == 0) return fmt::format("{} ≤ {}", symbol, v(idx.back()));
  if (contiguous && idx.back() == values.size() - 1)
    return fmt::format("{} ≥ {}", symbol, v(idx.front()));
  if (contiguous) return fmt::format("{} in [{}, {}]", symbol, v(idx.front()), v(idx.back()));
  std::string list;
  for (std::size_t k = 0; k < idx.size(); ++k) list += (k ? ", " : "") + v(idx[k]);
  return fmt::format("{} ∈ {{{}}}", symbol, list);
}

struct Probe {
  std::string defect;
  DefectClass kind;
  bool breaks;
  bool is_float;
  bool percent;  // worst is a fraction shown in %
  // For a cell: the measure (0 = not flagged) and the components it concerns.
  std::function<double(const CellStats&, std::string&)> measure;
};

double frac(std::uint64_t k, std::uint64_t n) { return n ? double(k) / double(n) : 0; }

// NaN / Inf / negative of one precision, as a fraction of the worst component.
Probe defect_probe(const std::string& name, std::uint64_t Defects::*field, bool use_float) {
  return {name,
          DefectClass::kBreaks,
          true,
          use_float,
          true,
          [=](const CellStats& c, std::string& comp) {
            const Defects& v = use_float ? c.value_f : c.value;
            const Defects& p = use_float ? c.pdf_f : c.pdf;
            const Defects& s = use_float ? c.sample_f : c.sample;
            const double fv = frac(v.*field, use_float ? c.evals_f : c.evals);
            const double fp = frac(p.*field, use_float ? c.pdf_calls_f : c.pdf_calls);
            const double fs = frac(s.*field, use_float ? c.samples_f : c.samples);
            comp.clear();
            if (fv > 0) comp += "value";
            if (fp > 0) comp += std::string(comp.empty() ? "" : ", ") + "pdf";
            if (fs > 0) comp += std::string(comp.empty() ? "" : ", ") + "sample";
            return std::max({fv, fp, fs});
          }};
}

}  // namespace

std::string Finding::text() const {
  std::string what = defect;
  if (!components.empty()) what += " in " + components;
  if (float_only) what += " (float only)";
  std::string how;
  if (defect == "energy gain > 1")
    how = fmt::format("albedo up to 1 + {:.3g}", worst);
  else if (defect == "p > 1")
    how = fmt::format("up to {:.3g} % of probabilities", 100 * worst);
  else if (defect == "variance blow-up")
    how = fmt::format("Var(w)/E(w)² at a fixed position up to {:.3g}", worst);
  else
    how = fmt::format("up to {:.3g} % of calls", 100 * worst);
  return fmt::format("{} for {} ({} of {} cells of the {} sweep, {})", what, region, cells,
                     plane_cells, plane, how);
}

std::vector<Finding> find_failures(const ModelSweep& s) {
  std::vector<Probe> probes;
  for (bool f : {false, true}) {
    if (f && !s.has_float) continue;
    probes.push_back(defect_probe("NaN", &Defects::nan, f));
    probes.push_back(defect_probe("Inf", &Defects::inf, f));
    probes.push_back(defect_probe("negative", &Defects::negative, f));
  }
  probes.push_back({"energy gain > 1", DefectClass::kEnergyGain, false, false, false,
                    [](const CellStats& c, std::string&) { return c.gain(); }});
  probes.push_back(
      {"p > 1", DefectClass::kProbabilityAboveOne, false, false, true,
       [](const CellStats& c, std::string&) { return frac(c.p_above_one, c.p_evals); }});
  if (s.has_variance)
    probes.push_back({"variance blow-up", DefectClass::kHugeVariance, false, false, false,
                      [](const CellStats& c, std::string&) {
                        return c.variance_blowup() ? c.relative_variance : 0.0;
                      }});

  std::vector<Finding> out;
  for (const SweepMap& m : s.maps) {
    const std::size_t rows = m.plane.rows.size(), cols = m.plane.theta_deg.size();
    for (std::size_t k = 0; k < probes.size(); ++k) {
      const bool is_float = probes[k].is_float;
      std::vector<bool> fr(rows, false), fc(cols, false);
      Finding f;
      f.defect = probes[k].defect;
      f.kind = probes[k].kind;
      f.breaks = probes[k].breaks;
      f.float_only = is_float;
      f.plane = m.plane.name;
      f.plane_cells = rows * cols;
      std::vector<std::string> comps;
      for (std::size_t r = 0; r < rows; ++r)
        for (std::size_t c = 0; c < cols; ++c) {
          const CellStats& cell = m.at(r, c);
          // A float defect counts only where the double instantiation is clean in that cell.
          if (is_float && cell.double_defect()) continue;
          std::string comp;
          const double v = probes[k].measure(cell, comp);
          if (!(v > 0)) continue;
          fr[r] = fc[c] = true;
          ++f.cells;
          f.worst = std::max(f.worst, v);
          f.in_core |= in_core_domain(m.plane, m.plane.rows[r], m.plane.theta_deg[c]);
          if (!comp.empty() && std::find(comps.begin(), comps.end(), comp) == comps.end())
            comps.push_back(comp);
        }
      if (f.cells == 0) continue;
      for (std::size_t i = 0; i < comps.size(); ++i) f.components += (i ? "; " : "") + comps[i];
      f.region = describe_axis(m.plane.rows, fr, m.plane.row_symbol, "") + " at " +
                 describe_axis(m.plane.theta_deg, fc, "θi", "°");
      out.push_back(std::move(f));
    }
  }
  return out;
}

std::string describe_failure_region(const ModelSweep& s) {
  const auto f = find_failures(s);
  if (f.empty()) {
    const std::string variance =
        s.has_variance
            ? fmt::format("relative weight variance at a fixed position ≤ {:g}", kVarianceBlowup)
            : std::string("(the fixed-position variance not measured)");
    return fmt::format(
        "none found: no NaN, Inf or negative value, pdf or sample{}, no significant energy gain, "
        "{}{} in every cell swept",
        s.has_float ? " (double and float)" : " (double; no float instantiation)",
        s.has_probability ? "no p > 1, " : "", variance);
  }
  std::string text;
  for (std::size_t i = 0; i < f.size(); ++i) text += (i ? "; " : "") + f[i].text();
  return text;
}

Verdict stability_verdict(const ModelSweep& s, DefectClass kind) {
  if (kind == DefectClass::kHugeVariance && !s.has_variance) return Verdict::kInconclusive;
  bool any = false, core = false;
  for (const Finding& f : find_failures(s)) {
    if (f.kind != kind) continue;
    any = true;
    core |= f.in_core && !f.float_only;
  }
  return !any ? Verdict::kHolds : core ? Verdict::kFails : Verdict::kHoldsInRegime;
}

}  // namespace glintlab::verify::stability
