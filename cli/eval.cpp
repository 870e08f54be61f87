// `glintlab eval`: evaluates every microfacet term of the library for a CSV file of queries.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "cli/args.h"
#include "cli/batch_options.h"
#include "cli/commands.h"
#include "cli/eval_model.h"
#include "cli/input.h"
#include "cli/model_options.h"
#include "cli/out_csv.h"
#include "core/io/csv.h"
#include "core/maps/beckmann_map.h"
#include "core/maps/ggx_map.h"
#include "core/model_registry.h"
#include "core/ndf/microfacet.h"
#include "core/ndf/total_area.h"
#include "core/samplers/sampler_list.h"

namespace glintlab::cli {
namespace {

constexpr std::array<std::string_view, 9> kQueryColumns = {
    "ndf", "alpha_x", "alpha_y", "wi_x", "wi_y", "wi_z", "wo_x", "wo_y", "wo_z"};

// The result columns: these, then one pdf column per sampler (pdf_columns), then kTermsAfter.
constexpr std::array<std::string_view, 9> kTermsBefore = {
    "h_x", "h_y", "h_z", "D", "lambda_wi", "G1_wi", "G1_wo", "G2", "vndf_h"};
constexpr std::array<std::string_view, 6> kTermsAfter = {"brdf", "DH",       "T_x",
                                                         "T_y",  "JT_paper", "JT_true"};

// One pdf column per sampler of the list (core/samplers/sampler_list.h), named by the smooth
// models' `sampler` value and, where a sampler has several, its `bound`: pdf_<sampler>[_<bound>].
// `row` is the list's row for each NDF (-1: that NDF has no such sampler; the column is 'nan').
struct PdfColumn {
  std::string name;
  std::string_view choice, bound;
  int row[2] = {-1, -1};  // ggx, beckmann
};

int ndf_slot(NdfKind ndf) { return ndf == NdfKind::kGGX ? 0 : 1; }

const std::vector<PdfColumn>& pdf_columns() {
  static const std::vector<PdfColumn> columns = [] {
    std::vector<PdfColumn> out;
    const auto& rows = samplers::Choices<samplers::All>::kRows;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const SamplerInfo& r = rows[i];
      const std::string name =
          fmt::format("pdf_{}{}{}", r.choice, r.bound.empty() ? "" : "_", r.bound);
      auto c =
          std::find_if(out.begin(), out.end(), [&](const PdfColumn& p) { return p.name == name; });
      if (c == out.end()) c = out.insert(out.end(), PdfColumn{name, r.choice, r.bound});
      c->row[ndf_slot(r.ndf == "ggx" ? NdfKind::kGGX : NdfKind::kBeckmann)] = int(i);
    }
    return out;
  }();
  return columns;
}

std::vector<std::string_view> result_columns() {
  std::vector<std::string_view> names(kTermsBefore.begin(), kTermsBefore.end());
  for (const PdfColumn& c : pdf_columns()) names.push_back(c.name);
  names.insert(names.end(), kTermsAfter.begin(), kTermsAfter.end());
  return names;
}

struct Query {
  NdfKind ndf;
  double alpha_x, alpha_y;
  Vec3<double> wi, wo;
};

// The roughness range the registered smooth model of `ndf` takes (its alpha_x parameter): eval
// accepts what the model accepts.
void check_alpha_range(NdfKind ndf, double alpha, const std::string& where) {
  check_alpha(alpha, where);
  const ModelEntry& m = find_model(ndf == NdfKind::kGGX ? "smooth_ggx" : "smooth_beckmann");
  for (const ParamSpec& p : m.params) {
    if (p.name != "alpha_x") continue;
    const bool ok =
        (p.lo_open ? alpha > p.lo : alpha >= p.lo) && (p.hi_open ? alpha < p.hi : alpha <= p.hi);
    if (!ok) {
      throw InputError(fmt::format("{}: roughness {} is out of range (valid: {}, as model {})",
                                   where, alpha, describe_range(p), m.name));
    }
  }
}

// Reads and validates every row before anything is computed or written.
std::vector<Query> read_queries(const io::CsvTable& table) {
  // Columns: all of kQueryColumns, in any order, and no others.
  std::string missing, extra;
  for (std::string_view name : kQueryColumns) {
    if (!table.find_column(name)) missing += fmt::format("{}{}", missing.empty() ? "" : ", ", name);
  }
  for (const std::string& name : table.header()) {
    bool known = false;
    for (std::string_view q : kQueryColumns) known = known || name == q;
    if (!known) extra += fmt::format("{}'{}'", extra.empty() ? "" : ", ", name);
  }
  if (!missing.empty() || !extra.empty()) {
    std::string msg = fmt::format("--in '{}' header row:", table.source());
    if (!missing.empty()) msg += fmt::format(" missing column(s) {};", missing);
    if (!extra.empty()) msg += fmt::format(" unknown column(s) {};", extra);
    msg.back() = ' ';
    msg +=
        fmt::format("(valid: exactly the columns {}, in any order)", fmt::join(kQueryColumns, ","));
    throw InputError(msg);
  }

  std::array<std::size_t, kQueryColumns.size()> col{};
  for (std::size_t i = 0; i < kQueryColumns.size(); ++i) col[i] = table.column(kQueryColumns[i]);

  std::vector<Query> queries;
  queries.reserve(table.num_rows());
  for (std::size_t r = 0; r < table.num_rows(); ++r) {
    const auto where = [&](std::size_t c) { return "--in " + table.where(r, col[c]); };
    const auto num = [&](std::size_t c) {
      try {
        return table.number(r, col[c]);
      } catch (const io::CsvError& e) {
        throw InputError(std::string("--in ") + e.what());
      }
    };
    Query q{};
    q.ndf = parse_ndf(table.text(r, col[0]), where(0));
    q.alpha_x = num(1);
    check_alpha_range(q.ndf, q.alpha_x, where(1));
    q.alpha_y = num(2);
    check_alpha_range(q.ndf, q.alpha_y, where(2));
    q.wi = {num(3), num(4), num(5)};
    q.wo = {num(6), num(7), num(8)};
    check_unit(q.wi, fmt::format("--in {}, columns wi_x,wi_y,wi_z (wi)", table.where(r)));
    check_unit(q.wo, fmt::format("--in {}, columns wo_x,wo_y,wo_z (wo)", table.where(r)));
    queries.push_back(q);
  }
  return queries;
}

// Every result column for one query, in the order of result_columns(), into `out`.
void evaluate(const Query& q, double* out) {
  with_ndf(q.ndf, q.alpha_x, q.alpha_y, [&](const auto& ndf) {
    using Ndf = std::decay_t<decltype(ndf)>;
    const Vec3<double> wi = q.wi, wo = q.wo;
    const Vec3<double> h = half_vector(wi, wo);
    for (double v :
         {h.x, h.y, h.z, ndf.D(h), ndf.lambda(wi), smith_g1(ndf, wi, h), smith_g1(ndf, wo, h),
          smith_g2_height_correlated(ndf, wi, wo, h), vndf(ndf, wi, h)})
      *out++ = v;
    for (const PdfColumn& c : pdf_columns()) {
      const int row = c.row[ndf_slot(q.ndf)];
      *out++ = row < 0 ? std::numeric_limits<double>::quiet_NaN()
                       : samplers::with<samplers::All>(row, [&]<class S>() {
                           if constexpr (std::is_same_v<typename S::template Ndf<double>, Ndf>)
                             return S::pdf(ndf, wi, wo);
                           else
                             return std::numeric_limits<double>::quiet_NaN();  // another NDF's row
                         });
    }
    const Vec2<double> t = map_to_square(ndf, h);
    for (double v : {microfacet_brdf(ndf, wi, wo, 1.0), total_area(ndf), t.x, t.y,
                     map_jacobian_paper(ndf, h), map_jacobian_true(ndf, h)})
      *out++ = v;
  });
}

void run_eval(const std::string& in_path, const std::string& out_path,
              const std::string& threads_text) {
  BatchOptions threads{};
  threads.threads = resolve_threads(threads_text);
  check_output_file(out_path, "--out");
  io::CsvTable table = [&] {
    try {
      return io::read_csv(in_path);
    } catch (const io::CsvError& e) {
      throw InputError(std::string("--in ") + e.what());
    }
  }();
  const std::vector<Query> queries = read_queries(table);

  // Rows are independent: computed in parallel chunks, checked, then written in order.
  const std::vector<std::string_view> columns = result_columns();
  const std::size_t width = columns.size();
  std::vector<double> results(queries.size() * width);
  for_each_chunk(queries.size(), threads, [&](std::size_t begin, std::size_t count) {
    for (std::size_t i = begin; i < begin + count; ++i) evaluate(queries[i], &results[i * width]);
  });
  // An accepted query never yields NaN or Inf in an output column, but for the pdf of a sampler
  // its NDF does not have ('nan' by definition, e.g. the GGX-only samplers for beckmann).
  for (std::size_t r = 0; r < queries.size(); ++r) {
    for (std::size_t c = 0; c < width; ++c) {
      const std::size_t pdf = c - kTermsBefore.size();
      if (c >= kTermsBefore.size() && pdf < pdf_columns().size() &&
          pdf_columns()[pdf].row[ndf_slot(queries[r].ndf)] < 0)
        continue;
      if (!std::isfinite(results[r * width + c])) {
        const Query& q = queries[r];
        const bool opposite = q.wi.x + q.wo.x == 0 && q.wi.y + q.wo.y == 0 && q.wi.z + q.wo.z == 0;
        throw InputError(
            fmt::format("--in {}: the query gives {} = {} (valid: a query whose every "
                        "term is finite{})",
                        table.where(r), columns[c], results[r * width + c],
                        opposite ? "; wo = -wi has no half vector" : ""));
      }
    }
  }
  check_free_space(out_path, std::uint64_t(queries.size()) * (kQueryColumns.size() + width) * 20,
                   "--out");

  std::vector<std::string_view> header(kQueryColumns.begin(), kQueryColumns.end());
  header.insert(header.end(), columns.begin(), columns.end());

  write_out_csv(out_path, header, [&](io::CsvWriter& w) {
    for (std::size_t r = 0; r < queries.size(); ++r) {
      const Query& q = queries[r];
      w.cell(ndf_name(q.ndf)).cell(q.alpha_x).cell(q.alpha_y);
      w.cell(q.wi.x).cell(q.wi.y).cell(q.wi.z).cell(q.wo.x).cell(q.wo.y).cell(q.wo.z);
      for (std::size_t c = 0; c < width; ++c) w.cell(results[r * width + c]);
      w.end_row();
    }
  });
}

constexpr const char* kEvalFooterQueries =
    R"(INPUT (--in): a CSV file, a header row then one query per data row. Columns, in any order, and
no others:
  ndf               ggx or beckmann
  alpha_x, alpha_y  roughness along the tangent (x) and bitangent (y) axes; in [0.0001, 100] (the
                    range of the smooth_ggx and smooth_beckmann models)
  wi_x, wi_y, wi_z  the given direction wi, pointing toward the viewer; unit length (within 1e-6)
  wo_x, wo_y, wo_z  the other direction wo; unit length (within 1e-6)
Directions are in the local shading frame: x tangent, y bitangent, z the macrosurface normal.
Any unit directions are accepted, including ones at or below the surface (z <= 0): each term
then takes the value its formula gives there (D, G1, G2 and brdf are 0 where they vanish; the
VNDF and its pdfs are defined for a back-facing wi, as in Eto & Tokuyoshi 2023).
Numbers are decimal (std::from_chars) and must be finite; fields may not be empty or quoted.

OUTPUT (--out): a CSV file, one row per query, in input order. Columns: the query columns (in
the order above; the same values, reprinted), then
  h_x, h_y, h_z  half vector h = normalize(wi + wo) (a row with wo = -wi has none: refused)
  D              the NDF D(h), per steradian of microfacet normal
  lambda_wi      Smith Lambda(wi) (Heitz 2014), with Lambda(-w) = 1 + Lambda(w) below the surface
  G1_wi, G1_wo   Smith masking G1(wi, h) and G1(wo, h)
  G2             height-correlated masking-shadowing G2(wi, wo, h) (Heitz 2014 Eq. 99)
  vndf_h         visible-normal density D_wi(h) = max(0, wi.h) D(h) / A(wi) (Heitz 2018 Eq. 1)
)";

constexpr const char* kEvalFooterTerms =
    R"(  brdf           microfacet reflection BRDF F G2 D / (4 |wi.z| |wo.z|) with F = 1, 0 unless both
                 wi and wo are above the surface
  DH             total microfacet area D_H = integral of D(m) over the hemisphere (Kneiphof &
                 Klein 2024 Eq. 29-31, with glintlab's anisotropic extension); depends on ndf
                 and alpha only
  T_x, T_y       map_to_square(ndf, h): the NDF-to-disk map T of Kemppinen et al. 2025
                 (Sec. 3.2.1) at h, stored as p = (q + 1)/2 for the paper's unit-disk point q
                 (the disk of radius 1/2 centred at (1/2, 1/2) in the unit square)
  JT_paper       |J_T| as the paper uses it in Eq. 3: D(h) / |U|, |U| = pi/4 (disk area in
                 square units)
  JT_true        the actual Jacobian |det dT/dh| of map_to_square, per steradian of h
Every number is a double printed with 17 significant digits (reads back to the same double).
Any invalid row, or a row whose terms are not all finite (the 'nan' pdfs above aside), stops
the run with an error naming the file, the 1-based data row and the column; no output file is
written then.)";

// The pdf columns' lines of the footer, one entry per sampler of the list with its papers per NDF:
// the column name, then its description from column 18, wrapped before column 100.
std::string pdf_column_help() {
  constexpr std::size_t kIndent = 17, kWidth = 100;
  std::string text;
  const auto& rows = samplers::Choices<samplers::All>::kRows;
  for (const PdfColumn& c : pdf_columns()) {
    std::vector<std::string> by_ndf;
    for (int slot : {0, 1})
      if (c.row[slot] >= 0)
        by_ndf.push_back(fmt::format("{}: {}", rows[std::size_t(c.row[slot])].ndf,
                                     rows[std::size_t(c.row[slot])].source));
    const std::string description =
        fmt::format("density of wo (per steradian) under sample --sampler {}{}{} ({}){}", c.choice,
                    c.bound.empty() ? "" : " --bound ", c.bound, fmt::join(by_ndf, "; "),
                    by_ndf.size() < 2 ? "; 'nan' for the other NDF" : "");
    std::string line = "  " + c.name;
    if (line.size() >= kIndent) text += line + "\n", line.clear();
    line.resize(kIndent, ' ');
    std::size_t words = 0;
    for (std::size_t at = 0; at < description.size();) {
      std::size_t end = description.find(' ', at);
      if (end == std::string::npos) end = description.size();
      const std::string word = description.substr(at, end - at);
      if (words > 0 && line.size() + 1 + word.size() > kWidth)
        text += line + "\n", line.assign(kIndent, ' '), words = 0;
      line += (words++ > 0 ? " " : "") + word;
      at = end + 1;
    }
    text += line + "\n";
  }
  return text;
}

}  // namespace

void add_eval_command(CLI::App& app) {
  CLI::App* cmd = add_command(
      app, "eval",
      "Evaluate every microfacet term (D, G1, G2, VNDF, pdfs, BRDF, maps) for CSV queries");
  auto in = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  add_text_option(cmd, "--in", *in, "query CSV file (columns described below)", "FILE");
  set_required(
      add_text_option(cmd, "--out", *out,
                      "result CSV file; written to a temporary file and renamed into place only "
                      "when every row succeeded",
                      "FILE"));
  auto model = std::make_shared<std::string>();
  auto params = std::make_shared<std::vector<std::string>>();
  add_model_options(cmd, *model, *params,
                    "Evaluate this registered model instead (see glintlab models and below)");
  auto grid = std::make_shared<std::string>();
  add_text_option(cmd, "--grid", *grid,
                  "with --model, instead of --in: 'theta_i=lo:hi:count,...' (degrees; below)",
                  "AXES");
  auto query = std::make_shared<std::string>();
  add_text_option(cmd, "--query", *query,
                  "with --model --grid: the query columns the model needs besides wi and wo, "
                  "'name=value,...' (footprint u, v, dudx, dvdx, dudy, dvdy; light "
                  "light_cos_half_angle, light_intensity), for every row; as sample --model",
                  "LIST");
  auto batch = std::make_shared<BatchOptionTexts>();
  add_batch_options(cmd, *batch);
  set_footer(cmd, std::string(kEvalFooterQueries) + pdf_column_help() + kEvalFooterTerms +
                      kModelEvalFooter + kBatchOptionsFooter);
  set_callback(cmd, [cmd, in, out, model, params, grid, query, batch] {
    if (model->empty() && !params->empty()) {
      throw InputError("--param: needs --model (see glintlab models)");
    }
    if (model->empty() && (option_count(cmd, "--grid") > 0 || option_count(cmd, "--query") > 0 ||
                           batch_options_given(cmd))) {
      const char* option = option_count(cmd, "--grid") > 0    ? "--grid"
                           : option_count(cmd, "--query") > 0 ? "--query"
                                                              : "--isa/--precision/--math";
      throw InputError(
          fmt::format("{}: needs --model (valid: a model of glintlab models)", option));
    }
    for (const char* o : {"--in", "--grid", "--model"}) {
      if (option_count(cmd, o) > 0 && (o == std::string("--in")     ? in->empty()
                                       : o == std::string("--grid") ? grid->empty()
                                                                    : model->empty()))
        throw InputError(fmt::format("{}: '' is empty (valid: see glintlab eval --help)", o));
    }
    register_staging_parent(std::filesystem::path(*out).has_parent_path()
                                ? std::filesystem::path(*out).parent_path()
                                : std::filesystem::path("."));
    if (model->empty()) {
      if (in->empty()) throw InputError("--in is required (valid: a query CSV file)");
      run_eval(*in, *out, batch->threads);
    } else {
      run_model_eval(
          {*model, *params, *in, *grid, *query, option_count(cmd, "--query") > 0, *out, *batch});
    }
  });
}

}  // namespace glintlab::cli
