#include "experiments/adequacy/adequacy_shards.h"

#include <fmt/format.h>

#include <bit>
#include <cstdint>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "core/io/atomic_file.h"

namespace glintlab::experiments {
namespace {

using nlohmann::json;
using verify::adequacy::CellResult;
using verify::adequacy::ChermainCellResult;
using verify::adequacy::KemppinenCellResult;
using verify::adequacy::LevelStats;

constexpr const char* kFormat = "glintlab adequacy cells 4";  // 2: the area family, 3: Chermain,
                                                             // 4: the binomial axes
// A level's fields, in the order of its array in the file.
constexpr const char* kLevelFields =
    "mean cv p_zero mean_diff mean_diff_ucb mean_diff_lcb cv_diff cv_diff_ucb cv_diff_lcb "
    "adequate undecided ns_per_eval";

// A double as the 16 hexadecimal digits of its bits: exact, NaN and infinities included.
std::string bits(double x) { return fmt::format("{:016x}", std::bit_cast<std::uint64_t>(x)); }
double from_bits(const json& j) {
  const std::string s = j.get<std::string>();
  if (s.size() != 16 || s.find_first_not_of("0123456789abcdef") != std::string::npos)
    throw std::invalid_argument(fmt::format("'{}' is not the 16 hex digits of a double", s));
  return std::bit_cast<double>(std::uint64_t(std::stoull(s, nullptr, 16)));
}
json bits_of(const std::vector<double>& v) {
  json a = json::array();
  for (double x : v) a.push_back(bits(x));
  return a;
}
std::vector<double> doubles_of(const json& a) {
  std::vector<double> v;
  for (const json& x : a) v.push_back(from_bits(x));
  return v;
}

// Each family's grid axes as a part file holds them (the binomial and the area family: GridAxes).
json grid_axes_to_json(const verify::adequacy::GridAxes& a) {
  return {{"facets", bits_of(a.facets)},
          {"alpha", bits_of(a.alpha)},
          {"light_half_angle_deg", bits_of(a.light_half_angle_deg)},
          {"theta_i_deg", bits_of(a.theta_i_deg)},
          {"theta_h_count", a.theta_h_count},
          {"samples", a.samples}};
}
verify::adequacy::GridAxes grid_axes_from_json(const json& j) {
  verify::adequacy::GridAxes a;
  a.facets = doubles_of(j.at("facets"));
  a.alpha = doubles_of(j.at("alpha"));
  a.light_half_angle_deg = doubles_of(j.at("light_half_angle_deg"));
  a.theta_i_deg = doubles_of(j.at("theta_i_deg"));
  a.theta_h_count = j.at("theta_h_count").get<int>();
  a.samples = j.at("samples").get<int>();
  return a;
}
json kemppinen_axes_to_json(const verify::adequacy::KemppinenGridAxes& k) {
  return {{"points", bits_of(k.points)},
          {"alpha", bits_of(k.alpha)},
          {"theta_i_deg", bits_of(k.theta_i_deg)},
          {"theta_h_count", k.theta_h_count},
          {"samples", k.samples}};
}
verify::adequacy::KemppinenGridAxes kemppinen_axes_from_json(const json& j) {
  verify::adequacy::KemppinenGridAxes k;
  k.points = doubles_of(j.at("points"));
  k.alpha = doubles_of(j.at("alpha"));
  k.theta_i_deg = doubles_of(j.at("theta_i_deg"));
  k.theta_h_count = j.at("theta_h_count").get<int>();
  k.samples = j.at("samples").get<int>();
  return k;
}
json chermain_axes_to_json(const verify::adequacy::ChermainGridAxes& c) {
  return {{"facets", bits_of(c.facets)},
          {"alpha", bits_of(c.alpha)},
          {"theta_i_deg", bits_of(c.theta_i_deg)},
          {"dh", bits_of(c.dh)},
          {"theta_h_count", c.theta_h_count},
          {"samples", c.samples}};
}
verify::adequacy::ChermainGridAxes chermain_axes_from_json(const json& j) {
  verify::adequacy::ChermainGridAxes c;
  c.facets = doubles_of(j.at("facets"));
  c.alpha = doubles_of(j.at("alpha"));
  c.theta_i_deg = doubles_of(j.at("theta_i_deg"));
  c.dh = doubles_of(j.at("dh"));
  c.theta_h_count = j.at("theta_h_count").get<int>();
  c.samples = j.at("samples").get<int>();
  return c;
}

json level_to_json(const LevelStats& s) {
  return json::array({bits(s.mean), bits(s.cv), bits(s.p_zero), bits(s.mean_diff),
                      bits(s.mean_diff_ucb), bits(s.mean_diff_lcb), bits(s.cv_diff),
                      bits(s.cv_diff_ucb), bits(s.cv_diff_lcb), s.adequate, s.undecided,
                      bits(s.ns_per_eval)});
}
LevelStats level_from_json(const json& a) {
  if (!a.is_array() || a.size() != 12) throw std::invalid_argument("a level is not 12 fields");
  LevelStats s;
  s.mean = from_bits(a[0]);
  s.cv = from_bits(a[1]);
  s.p_zero = from_bits(a[2]);
  s.mean_diff = from_bits(a[3]);
  s.mean_diff_ucb = from_bits(a[4]);
  s.mean_diff_lcb = from_bits(a[5]);
  s.cv_diff = from_bits(a[6]);
  s.cv_diff_ucb = from_bits(a[7]);
  s.cv_diff_lcb = from_bits(a[8]);
  s.adequate = a[9].get<bool>();
  s.undecided = a[10].get<bool>();
  s.ns_per_eval = from_bits(a[11]);
  return s;
}
template <std::size_t N>
json levels_to_json(const std::array<LevelStats, N>& levels) {
  json a = json::array();
  for (const LevelStats& s : levels) a.push_back(level_to_json(s));
  return a;
}
template <std::size_t N>
std::array<LevelStats, N> levels_from_json(const json& a) {
  if (!a.is_array() || a.size() != N)
    throw std::invalid_argument(fmt::format("a cell has {} levels, not {}", a.size(), N));
  std::array<LevelStats, N> out{};
  for (std::size_t l = 0; l < N; ++l) out[l] = level_from_json(a[l]);
  return out;
}

json binomial_to_json(std::size_t position, const CellResult& r) {
  return {{"position", position},
          {"p", bits(r.p)},
          {"smooth", bits(r.smooth)},
          {"levels", levels_to_json(r.levels)},
          {"chosen", r.chosen},
          {"cheapest_measured", r.cheapest_measured},
          {"cv_predicted", bits(r.cv_predicted)},
          {"p_zero_predicted", bits(r.p_zero_predicted)},
          {"chooser", r.chooser},
          {"chooser_refuted", r.chooser_refuted}};
}
CellResult binomial_from_json(const json& j) {
  CellResult r;
  r.p = from_bits(j.at("p"));
  r.smooth = from_bits(j.at("smooth"));
  r.levels = levels_from_json<kBinomialLevels>(j.at("levels"));
  r.chosen = j.at("chosen").get<int>();
  r.cheapest_measured = j.at("cheapest_measured").get<int>();
  r.cv_predicted = from_bits(j.at("cv_predicted"));
  r.p_zero_predicted = from_bits(j.at("p_zero_predicted"));
  r.chooser = j.at("chooser").get<int>();
  r.chooser_refuted = j.at("chooser_refuted").get<bool>();
  return r;
}

json kemppinen_to_json(std::size_t position, const KemppinenCellResult& r) {
  return {{"position", position},        {"smooth", bits(r.smooth)},
          {"lambda", bits(r.lambda)},    {"levels", levels_to_json(r.levels)},
          {"chosen", r.chosen},          {"cheapest_measured", r.cheapest_measured},
          {"chooser", r.chooser},        {"chooser_refuted", r.chooser_refuted},
          {"cv_bound", bits(r.cv_bound)}};
}
KemppinenCellResult kemppinen_from_json(const json& j) {
  KemppinenCellResult r;
  r.smooth = from_bits(j.at("smooth"));
  r.lambda = from_bits(j.at("lambda"));
  r.levels = levels_from_json<kKemppinenLevels>(j.at("levels"));
  r.chosen = j.at("chosen").get<int>();
  r.cheapest_measured = j.at("cheapest_measured").get<int>();
  r.chooser = j.at("chooser").get<int>();
  r.chooser_refuted = j.at("chooser_refuted").get<bool>();
  r.cv_bound = from_bits(j.at("cv_bound"));
  return r;
}

json chermain_to_json(std::size_t position, const ChermainCellResult& r) {
  return {{"position", position},
          {"smooth", bits(r.smooth)},
          {"lod", bits(r.lod)},
          {"levels", levels_to_json(r.levels)},
          {"chosen", r.chosen},
          {"cheapest_measured", r.cheapest_measured},
          {"construction", r.construction},
          {"construction_refuted", r.construction_refuted},
          {"chooser", r.chooser},
          {"chooser_refuted", r.chooser_refuted},
          {"cv_predicted", bits(r.cv_predicted)}};
}
ChermainCellResult chermain_from_json(const json& j) {
  ChermainCellResult r;
  r.smooth = from_bits(j.at("smooth"));
  r.lod = from_bits(j.at("lod"));
  r.levels = levels_from_json<verify::adequacy::kChermainLevels>(j.at("levels"));
  r.chosen = j.at("chosen").get<int>();
  r.cheapest_measured = j.at("cheapest_measured").get<int>();
  r.construction = j.at("construction").get<int>();
  r.construction_refuted = j.at("construction_refuted").get<bool>();
  r.chooser = j.at("chooser").get<int>();
  r.chooser_refuted = j.at("chooser_refuted").get<bool>();
  r.cv_predicted = from_bits(j.at("cv_predicted"));
  return r;
}

std::vector<verify::adequacy::Cell> binomial_grid(const AdequacyOptions& o) {
  return verify::adequacy::make_grid(binomial_models(o.models),
                                     binomial_axes_of(o));
}
std::vector<verify::adequacy::KemppinenCell> kemppinen_grid(const AdequacyOptions& o) {
  return verify::adequacy::make_kemppinen_grid(kemppinen_models(o.models), kemppinen_axes_of(o));
}
std::vector<verify::adequacy::Cell> area_grid(const AdequacyOptions& o) {
  return verify::adequacy::make_grid(area_models(o.models), area_axes_of(o));
}
std::vector<verify::adequacy::ChermainCell> chermain_grid(const AdequacyOptions& o) {
  return verify::adequacy::make_chermain_grid(chermain_models(o.models), chermain_axes_of(o));
}

// Each position once and inside the grid; the cell of each.
template <typename Cells, typename Results>
void place(const std::vector<std::size_t>& positions, const Cells& grid, Results& results,
           const char* family) {
  for (std::size_t j = 0; j < positions.size(); ++j) {
    if (positions[j] >= grid.size())
      throw std::invalid_argument(fmt::format("{}/{} is outside the run's grid of {} cells", family,
                                              positions[j], grid.size()));
    results[j].cell = grid[positions[j]];
  }
}

}  // namespace

AdequacyPart adequacy_shard_part(const AdequacyOptions& o, std::size_t k, std::size_t n) {
  AdequacyPart part;
  for (std::size_t i = k - 1; i < binomial_grid(o).size(); i += n) part.binomial.push_back(i);
  for (std::size_t i = k - 1; i < kemppinen_grid(o).size(); i += n) part.kemppinen.push_back(i);
  for (std::size_t i = k - 1; i < area_grid(o).size(); i += n) part.area.push_back(i);
  for (std::size_t i = k - 1; i < chermain_grid(o).size(); i += n) part.chermain.push_back(i);
  return part;
}

std::vector<std::string> adequacy_part_ids(const AdequacyPart& part) {
  std::vector<std::string> ids;
  for (std::size_t i : part.binomial) ids.push_back(fmt::format("binomial/{}", i));
  for (std::size_t i : part.kemppinen) ids.push_back(fmt::format("kemppinen/{}", i));
  for (std::size_t i : part.area) ids.push_back(fmt::format("area/{}", i));
  for (std::size_t i : part.chermain) ids.push_back(fmt::format("chermain/{}", i));
  return ids;
}

std::vector<std::string> adequacy_cell_ids(const AdequacyOptions& o) {
  return adequacy_part_ids(adequacy_shard_part(o, 1, 1));
}

std::string adequacy_run_text(const AdequacyOptions& o) {
  std::string t = fmt::format("budget {}\nTAU {}\nmodels {}\n",
                              o.budget == verify::Budget::kQuick ? "quick" : "full",
                              bits(o.threshold), fmt::join(o.models, ","));
  if (o.costs) {
    t += fmt::format("costs {} {}\n", o.costs->source, o.costs->isa);
    for (const auto& [model, ns] : o.costs->ns) {
      std::vector<std::string> b;
      for (double x : ns) b.push_back(bits(x));
      t += fmt::format("  {} {}\n", model, fmt::join(b, " "));
    }
  }
  t += fmt::format("binomial samples {}\n", binomial_axes_of(o).samples);
  for (const auto& c : binomial_grid(o))
    t += fmt::format("{} {} {} {} {} {} {}\n", c.model, bits(c.facets), bits(c.alpha),
                     bits(c.light_half_angle_deg), bits(c.theta_i_deg), bits(c.theta_h_deg),
                     c.theta_h_index);
  t += fmt::format("kemppinen samples {}\n", kemppinen_axes_of(o).samples);
  for (const auto& c : kemppinen_grid(o))
    t += fmt::format("{} {} {} {} {} {}\n", c.model, bits(c.points), bits(c.alpha),
                     bits(c.theta_i_deg), bits(c.theta_h_deg), c.theta_h_index);
  t += fmt::format("area samples {}\n", area_axes_of(o).samples);
  for (const auto& c : area_grid(o))
    t += fmt::format("{} {} {} {} {} {} {}\n", c.model, bits(c.facets), bits(c.alpha),
                     bits(c.light_half_angle_deg), bits(c.theta_i_deg), bits(c.theta_h_deg),
                     c.theta_h_index);
  t += fmt::format("chermain samples {}\n", chermain_axes_of(o).samples);
  for (const auto& c : chermain_grid(o))
    t += fmt::format("{} {} {} {} {} {} {}\n", c.model, bits(c.facets), bits(c.alpha),
                     bits(c.theta_i_deg), bits(c.theta_h_deg), c.theta_h_index, bits(c.dh));
  return t;
}

AdequacyCells measure_adequacy_part(const AdequacyOptions& o, const AdequacyPart& part) {
  const auto decision = table_decision(o);
  AdequacyCells cells;
  cells.binomial = verify::adequacy::measure_grid_at(binomial_grid(o), part.binomial,
                                                     binomial_axes_of(o).samples,
                                                     decision, o.progress);
  cells.kemppinen = verify::adequacy::measure_kemppinen_grid_at(
      kemppinen_grid(o), part.kemppinen, kemppinen_axes_of(o).samples, decision, o.progress);
  cells.area = verify::adequacy::measure_area_grid_at(area_grid(o), part.area,
                                                      area_axes_of(o).samples, decision, o.progress);
  cells.chermain = verify::adequacy::measure_chermain_grid_at(
      chermain_grid(o), part.chermain, chermain_axes_of(o).samples, decision, o.progress);
  return cells;
}

void write_adequacy_part(const std::filesystem::path& file, const AdequacyOptions& o,
                         const AdequacyPart& part, const AdequacyCells& cells) {
  if (cells.binomial.size() != part.binomial.size() ||
      cells.kemppinen.size() != part.kemppinen.size() || cells.area.size() != part.area.size() ||
      cells.chermain.size() != part.chermain.size())
    throw std::logic_error("write_adequacy_part: cells and part differ in size");
  json doc;
  doc["format"] = kFormat;
  doc["budget"] = o.budget == verify::Budget::kQuick ? "quick" : "full";
  doc["models"] = o.models;
  doc["threshold"] = bits(o.threshold);
  doc["binomial_axes"] = grid_axes_to_json(binomial_axes_of(o));
  doc["kemppinen_axes"] = kemppinen_axes_to_json(kemppinen_axes_of(o));
  doc["area_axes"] = grid_axes_to_json(area_axes_of(o));
  doc["chermain_axes"] = chermain_axes_to_json(chermain_axes_of(o));
  if (o.costs) {
    json ns = json::object();
    for (const auto& [model, v] : o.costs->ns)
      ns[model] = bits_of(std::vector<double>(v.begin(), v.end()));
    doc["costs"] = {{"source", o.costs->source}, {"isa", o.costs->isa}, {"ns", ns}};
  } else {
    doc["costs"] = nullptr;
  }
  doc["level_fields"] = kLevelFields;
  json binomial = json::array(), kemppinen = json::array(), area = json::array(),
       chermain = json::array();
  for (std::size_t j = 0; j < part.binomial.size(); ++j)
    binomial.push_back(binomial_to_json(part.binomial[j], cells.binomial[j]));
  for (std::size_t j = 0; j < part.kemppinen.size(); ++j)
    kemppinen.push_back(kemppinen_to_json(part.kemppinen[j], cells.kemppinen[j]));
  for (std::size_t j = 0; j < part.area.size(); ++j)
    area.push_back(binomial_to_json(part.area[j], cells.area[j]));
  for (std::size_t j = 0; j < part.chermain.size(); ++j)
    chermain.push_back(chermain_to_json(part.chermain[j], cells.chermain[j]));
  doc["binomial"] = binomial;
  doc["kemppinen"] = kemppinen;
  doc["area"] = area;
  doc["chermain"] = chermain;
  io::write_file_atomic(file, doc.dump() + "\n");
}

AdequacyPartFile read_adequacy_part(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::invalid_argument(fmt::format("cannot read {}", file.string()));
  std::stringstream text;
  text << in.rdbuf();
  try {
    const json doc = json::parse(text.str());
    if (doc.at("format") != kFormat || doc.at("level_fields") != kLevelFields)
      throw std::invalid_argument(fmt::format("not '{}' with levels '{}'", kFormat, kLevelFields));
    AdequacyPartFile f;
    AdequacyOptions& o = f.options;
    const std::string budget = doc.at("budget").get<std::string>();
    if (budget != "quick" && budget != "full")
      throw std::invalid_argument(fmt::format("budget '{}'", budget));
    o.budget = budget == "quick" ? verify::Budget::kQuick : verify::Budget::kFull;
    o.models = doc.at("models").get<std::vector<std::string>>();
    o.threshold = from_bits(doc.at("threshold"));
    o.binomial_axes = grid_axes_from_json(doc.at("binomial_axes"));
    o.kemppinen_axes = kemppinen_axes_from_json(doc.at("kemppinen_axes"));
    o.area_axes = grid_axes_from_json(doc.at("area_axes"));
    o.chermain_axes = chermain_axes_from_json(doc.at("chermain_axes"));
    if (!doc.at("costs").is_null()) {
      const json& c = doc.at("costs");
      LevelCosts costs;
      costs.source = c.at("source").get<std::string>();
      costs.isa = c.at("isa").get<std::string>();
      for (const auto& [model, v] : c.at("ns").items()) {
        const std::vector<double> ns = doubles_of(v);
        if (ns.size() != adequacy_level_names(model).size())
          throw std::invalid_argument(fmt::format("costs of {}: {} levels", model, ns.size()));
        costs.ns[model] = ns;
      }
      o.costs = costs;
    }
    for (const json& j : doc.at("binomial")) {
      f.part.binomial.push_back(j.at("position").get<std::size_t>());
      f.cells.binomial.push_back(binomial_from_json(j));
    }
    for (const json& j : doc.at("kemppinen")) {
      f.part.kemppinen.push_back(j.at("position").get<std::size_t>());
      f.cells.kemppinen.push_back(kemppinen_from_json(j));
    }
    for (const json& j : doc.at("area")) {
      f.part.area.push_back(j.at("position").get<std::size_t>());
      f.cells.area.push_back(binomial_from_json(j));
    }
    place(f.part.binomial, binomial_grid(o), f.cells.binomial, "binomial");
    place(f.part.kemppinen, kemppinen_grid(o), f.cells.kemppinen, "kemppinen");
    for (const json& j : doc.at("chermain")) {
      f.part.chermain.push_back(j.at("position").get<std::size_t>());
      f.cells.chermain.push_back(chermain_from_json(j));
    }
    place(f.part.area, area_grid(o), f.cells.area, "area");
    place(f.part.chermain, chermain_grid(o), f.cells.chermain, "chermain");
    return f;
  } catch (const json::exception& e) {
    throw std::invalid_argument(
        fmt::format("{} is not a file of adequacy cells ({})", file.string(), e.what()));
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(
        fmt::format("{} is not a file of adequacy cells ({})", file.string(), e.what()));
  }
}

AdequacyCells join_adequacy_parts(const AdequacyOptions& o,
                                  const std::vector<AdequacyPartFile>& parts) {
  const auto binomial = binomial_grid(o);
  const auto kemppinen = kemppinen_grid(o);
  const auto area = area_grid(o);
  const auto chermain = chermain_grid(o);
  std::vector<std::optional<CellResult>> b(binomial.size()), a(area.size());
  std::vector<std::optional<KemppinenCellResult>> k(kemppinen.size());
  std::vector<std::optional<ChermainCellResult>> c(chermain.size());
  const auto put = [](auto& slots, std::size_t position, const auto& cell, const char* family) {
    if (position >= slots.size())
      throw std::invalid_argument(fmt::format("{}/{} is outside the run's grid of {} cells", family,
                                              position, slots.size()));
    if (slots[position])
      throw std::invalid_argument(fmt::format("{}/{} is in two shards", family, position));
    slots[position] = cell;
  };
  for (const AdequacyPartFile& f : parts) {
    for (std::size_t j = 0; j < f.part.binomial.size(); ++j)
      put(b, f.part.binomial[j], f.cells.binomial[j], "binomial");
    for (std::size_t j = 0; j < f.part.kemppinen.size(); ++j)
      put(k, f.part.kemppinen[j], f.cells.kemppinen[j], "kemppinen");
    for (std::size_t j = 0; j < f.part.area.size(); ++j)
      put(a, f.part.area[j], f.cells.area[j], "area");
    for (std::size_t j = 0; j < f.part.chermain.size(); ++j)
      put(c, f.part.chermain[j], f.cells.chermain[j], "chermain");
  }
  AdequacyCells cells;
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (!b[i]) throw std::invalid_argument(fmt::format("no shard holds binomial/{}", i));
    cells.binomial.push_back(*b[i]);
  }
  for (std::size_t i = 0; i < k.size(); ++i) {
    if (!k[i]) throw std::invalid_argument(fmt::format("no shard holds kemppinen/{}", i));
    cells.kemppinen.push_back(*k[i]);
  }
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!a[i]) throw std::invalid_argument(fmt::format("no shard holds area/{}", i));
    cells.area.push_back(*a[i]);
  }
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (!c[i]) throw std::invalid_argument(fmt::format("no shard holds chermain/{}", i));
    cells.chermain.push_back(*c[i]);
  }
  return cells;
}

}  // namespace glintlab::experiments
