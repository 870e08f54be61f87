// The model registry: an entry per built-in model (core/model_list.h) and those added at run
// time, and parameter parsing/validation.
#include "core/model_registry.h"

#include <fmt/format.h>

#include <cmath>

#include "core/io/csv.h"
#include "core/model_list.h"

namespace glintlab {

namespace {

// A built-in model's misspelled not-claimed property is a compile error here; the instantiation
// context names the model.
template <class M>
struct CheckedNotClaimed {
  static_assert(detail::not_claimed_are_properties<M>(),
                "a built-in model's kNotClaimed names a property that is not a conformance "
                "property (valid: kConformanceProperties, core/model.h) or a choice that is not "
                "one of its parameters' (param=choice)");
  static constexpr bool kChecked = true;
};

template <class... Ms>
void append_entries(std::vector<ModelEntry>& m, ModelList<Ms...>) {
  static_assert((CheckedNotClaimed<Ms>::kChecked && ...));
  (m.push_back(make_model_entry<Ms>()), ...);
}

// The built-in models followed by those added with register_model.
std::vector<ModelEntry>& model_list() {
  static std::vector<ModelEntry> kModels = [] {
    std::vector<ModelEntry> m;
    m.reserve(kMaxModels);  // register_model never reallocates: references stay valid
    append_entries(m, BuiltinModels{});
    return m;
  }();
  return kModels;
}

}  // namespace

const std::vector<ModelEntry>& registered_models() { return model_list(); }

void register_model(ModelEntry entry) {
  if (entry.name.empty()) throw ModelParamError("register_model: the model has no name");
  if (!entry.eval || !entry.pdf || !entry.sample) {
    throw ModelParamError(
        fmt::format("register_model: model {} lacks eval, pdf or sample", entry.name));
  }
  std::vector<ModelEntry>& list = model_list();
  for (const ModelEntry& e : list) {
    if (e.name == entry.name) {
      throw ModelParamError(
          fmt::format("register_model: a model named {} is already registered", entry.name));
    }
  }
  check_not_claimed(entry);
  if (list.size() >= kMaxModels) {
    throw ModelParamError(
        fmt::format("register_model: at most {} models can be registered", kMaxModels));
  }
  list.push_back(std::move(entry));
}

void check_not_claimed(const ModelEntry& entry) {
  for (const NotClaimed& n : entry.not_claimed) {
    if (!is_conformance_property(n.property)) {
      throw ModelParamError(fmt::format(
          "model '{}' declares '{}' not claimed (kNotClaimed), which is not a conformance property "
          "(valid: {})",
          entry.name, n.property, fmt::join(kConformanceProperties, ", ")));
    }
    if (!n.choice.empty() && !is_declared_choice(entry.params, n.choice))
      throw ModelParamError(fmt::format(
          "model '{}' declares '{}' not claimed for '{}' (kNotClaimed), which is not one of its "
          "parameters' choices (param=choice)",
          entry.name, n.property, n.choice));
  }
}

const ModelEntry& find_model(std::string_view name) {
  std::string names;
  for (const ModelEntry& e : registered_models()) {
    if (e.name == name) return e;
    names += fmt::format("{}{}", names.empty() ? "" : ", ", e.name);
  }
  throw ModelParamError(fmt::format("--model: unknown model '{}' (valid: {})", name, names));
}

std::string describe_range(const ParamSpec& p) {
  if (!p.choices.empty()) return fmt::format("one of: {}", fmt::join(p.choices, ", "));
  const std::string range =
      fmt::format("{}{}, {}{}", p.lo_open ? '(' : '[', p.lo, p.hi, p.hi_open ? ')' : ']');
  return p.integral ? "an integer in " + range : range;
}

std::string format_param_value(const ParamSpec& p, double value) {
  if (!p.choices.empty()) return std::string(p.choices[static_cast<std::size_t>(value)]);
  return fmt::format("{}", value);
}

std::string describe_needs(unsigned needs) {
  std::vector<std::string_view> parts;
  if (needs & kNeedsFootprint) parts.push_back("footprint");
  if (needs & kNeedsPointLight) parts.push_back("point light");
  if (needs & kNeedsAreaLight) parts.push_back("area light");
  if (needs & kNeedsPixelCorners) parts.push_back("pixel corner reflection vectors");
  if (parts.empty()) return "needs: directions only";
  return fmt::format("needs: {}", fmt::join(parts, ", "));
}

std::vector<double> resolve_params(
    const ModelEntry& model, const std::vector<std::pair<std::string, std::string>>& assignments) {
  std::vector<double> values;
  std::vector<bool> set(model.params.size(), false);
  for (const ParamSpec& p : model.params) values.push_back(p.default_value);
  for (const auto& [name, text] : assignments) {
    std::size_t i = 0;
    while (i < model.params.size() && model.params[i].name != name) ++i;
    if (i == model.params.size()) {
      std::string names;
      for (const ParamSpec& p : model.params) {
        names += fmt::format("{}{}", names.empty() ? "" : ", ", p.name);
      }
      throw ModelParamError(fmt::format("--param: model {} has no parameter '{}' (valid: {})",
                                        model.name, name, names));
    }
    const ParamSpec& p = model.params[i];
    if (set[i]) throw ModelParamError(fmt::format("--param {}: given twice", p.name));
    set[i] = true;
    if (!p.choices.empty()) {
      std::size_t c = 0;
      while (c < p.choices.size() && p.choices[c] != text) ++c;
      if (c == p.choices.size()) {
        throw ModelParamError(fmt::format("--param {}: unknown value '{}' (valid: {})", p.name,
                                          text, describe_range(p)));
      }
      values[i] = static_cast<double>(c);
      continue;
    }
    const auto v = io::parse_finite_double(text);
    const bool in_range =
        v && (p.lo_open ? *v > p.lo : *v >= p.lo) && (p.hi_open ? *v < p.hi : *v <= p.hi);
    const bool whole = v && (!p.integral || std::floor(*v) == *v);
    if (!in_range || !whole) {
      const std::string_view problem = !v          ? io::number_problem(text)
                                       : !in_range ? "is out of range"
                                                   : "is not an integer";
      throw ModelParamError(
          fmt::format("--param {}: '{}' {} (valid: {})", p.name, text, problem, describe_range(p)));
    }
    values[i] = *v;
  }
  return values;
}

}  // namespace glintlab
