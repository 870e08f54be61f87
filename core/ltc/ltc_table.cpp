// The LTC tables' CSV files (core/ltc/tables/), their parser and writer, and the flat kernel layout
// (Heitz et al. 2016 Sec. 4 tables; Kneiphof & Klein 2024 Eq. 19 D_PR): see ltc_table.h.
#include "core/ltc/ltc_table.h"

#include <fmt/format.h>

#include <filesystem>
#include <sstream>

#include "core/io/atomic_file.h"
#include "core/io/csv.h"
#include "core/parameter_check.h"

namespace glintlab {

namespace detail {
// The committed CSV files, compiled in by core/CMakeLists.txt (ltc_tables_data.cpp.in).
extern const char* const kLtcBrdfCsv;
extern const char* const kLtcNdfCsv;
}  // namespace detail

namespace {

// The CSV body after the '#' provenance lines.
std::string_view strip_comments(std::string_view text) {
  while (!text.empty() && text.front() == '#') {
    const std::size_t nl = text.find('\n');
    text = nl == std::string_view::npos ? std::string_view{} : text.substr(nl + 1);
  }
  return text;
}

std::string header_block(const std::string& provenance) {
  std::string out;
  std::istringstream in(provenance);
  for (std::string line; std::getline(in, line);) out += "# " + line + "\n";
  return out;
}

std::string num(double x) { return fmt::format("{:.9g}", x); }

}  // namespace

LtcTables parse_ltc_tables(const std::string& brdf_csv, const std::string& ndf_csv) {
  LtcTables t;
  try {
    const io::CsvTable b = io::parse_csv(strip_comments(brdf_csv), "ggx_brdf.csv");
    const io::CsvTable n = io::parse_csv(strip_comments(ndf_csv), "ggx_ndf.csv");
    const std::size_t rows = b.num_rows();
    int size = 0;
    while (std::size_t(size) * size < rows) ++size;
    if (std::size_t(size) * size != rows || size < 2 || size > kLtcMaxTableSize)
      throw ParameterError(
          fmt::format("LTC tables: ggx_brdf.csv has {} rows (valid: N x N rows, 2 <= N <= {})",
                      rows, kLtcMaxTableSize));
    if (n.num_rows() != rows)
      throw ParameterError(
          fmt::format("LTC tables: ggx_ndf.csv has {} rows (valid: {}, as "
                      "ggx_brdf.csv)",
                      n.num_rows(), rows));
    t.size = size;
    const auto col = [](const io::CsvTable& c, const char* name) { return c.column(name); };
    const std::size_t b_sa = col(b, "sqrt_alpha"), b_th = col(b, "theta_o");
    const std::size_t b0 = col(b, "m00"), b1 = col(b, "m02"), b2 = col(b, "m20"),
                      b3 = col(b, "m22"), ba = col(b, "albedo"), bf = col(b, "fresnel"),
                      be = col(b, "l1_error"), bp0 = col(b, "fit_m11"), bp1 = col(b, "fit_m22"),
                      bp2 = col(b, "fit_m13"), bp3 = col(b, "fit_m31");
    const std::size_t n0 = col(n, "m00"), n1 = col(n, "m02"), n2 = col(n, "m20"),
                      n3 = col(n, "m22"), nd = col(n, "d_pr"), ne = col(n, "l1_error"),
                      np0 = col(n, "fit_m11"), np1 = col(n, "fit_m22"), np2 = col(n, "fit_m13"),
                      np3 = col(n, "fit_m31");
    for (std::size_t r = 0; r < rows; ++r) {
      const int i = int(r) / size, j = int(r) % size;
      const double sa = double(i) / (size - 1), th = double(j) / (size - 1) * 1.5707963267948966;
      if (std::abs(b.number(r, b_sa) - sa) > 1e-6 || std::abs(b.number(r, b_th) - th) > 1e-6)
        throw ParameterError(
            fmt::format("LTC tables: {} is not node ({}, {}) of the {} x {} grid "
                        "(valid: rows ordered by sqrt_alpha, then theta_o)",
                        b.where(r), i, j, size, size));
      t.brdf.push_back({b.number(r, b0), b.number(r, b1), b.number(r, b2), b.number(r, b3)});
      t.albedo.push_back(b.number(r, ba));
      t.fresnel.push_back(b.number(r, bf));
      t.brdf_error.push_back(b.number(r, be));
      t.brdf_params.push_back(
          {b.number(r, bp0), b.number(r, bp1), b.number(r, bp2), b.number(r, bp3)});
      t.ndf.push_back({n.number(r, n0), n.number(r, n1), n.number(r, n2), n.number(r, n3)});
      t.d_pr.push_back(n.number(r, nd));
      t.ndf_error.push_back(n.number(r, ne));
      t.ndf_params.push_back(
          {n.number(r, np0), n.number(r, np1), n.number(r, np2), n.number(r, np3)});
    }
  } catch (const io::CsvError& e) {
    throw ParameterError(fmt::format("LTC tables: {}", e.what()));
  }
  return t;
}

void write_ltc_tables(const std::string& dir, const LtcTables& t, const std::string& provenance) {
  const int n = t.size;
  std::string b =
      header_block(provenance +
                   "\nGGX BRDF*cos LTC lobes: M^-1 = [[m00,0,m02],[0,1,0],[m20,0,m22]] "
                   "for wo = (sin theta_o, 0, cos theta_o); albedo = int rho cos (F=1); "
                   "fresnel = int rho cos (1-<wi,h>)^5; l1_error = int |target/albedo - "
                   "D_ltc|.\nalpha = max(sqrt_alpha^2, 1e-4), cos theta_o >= 1e-3 in "
                   "the fit; angles in radians.");
  std::string d =
      header_block(provenance +
                   "\nGGX NDF LTC lobes for D(h)/(4<h,wi>) on wi in H (Kneiphof & Klein "
                   "2024 Eq. 13); d_pr = Eq. 19 by cubature; l1_error = int "
                   "|target/d_pr - D_ltc|.\nalpha = max(sqrt_alpha^2, 1e-4), cos "
                   "theta_o >= 1e-3 in the fit; angles in radians.");
  b += "sqrt_alpha,theta_o,m00,m02,m20,m22,albedo,fresnel,l1_error,fit_m11,fit_m22,fit_m13,fit_"
       "m31\n";
  d += "sqrt_alpha,theta_o,m00,m02,m20,m22,d_pr,l1_error,fit_m11,fit_m22,fit_m13,fit_m31\n";
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const std::size_t k = std::size_t(i) * n + j;
      const std::string sa = num(double(i) / (n - 1)),
                        th = num(double(j) / (n - 1) * 1.5707963267948966);
      const LtcCoefficients& cb = t.brdf[k];
      const LtcCoefficients& cn = t.ndf[k];
      const LtcFitParameters& pb = t.brdf_params[k];
      const LtcFitParameters& pn = t.ndf_params[k];
      b += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{}\n", sa, th, num(cb.m00), num(cb.m02),
                       num(cb.m20), num(cb.m22), num(t.albedo[k]), num(t.fresnel[k]),
                       num(t.brdf_error[k]), num(pb.m11), num(pb.m22), num(pb.m13), num(pb.m31));
      d += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}\n", sa, th, num(cn.m00), num(cn.m02),
                       num(cn.m20), num(cn.m22), num(t.d_pr[k]), num(t.ndf_error[k]), num(pn.m11),
                       num(pn.m22), num(pn.m13), num(pn.m31));
    }
  std::filesystem::create_directories(dir);
  // Both files are complete in memory before either is renamed into place.
  io::write_file_atomic(std::filesystem::path(dir) / "ggx_brdf.csv", b);
  io::write_file_atomic(std::filesystem::path(dir) / "ggx_ndf.csv", d);
}

LtcTableStorage flatten_ltc_tables(const LtcTables& t) {
  LtcTableStorage s;
  s.size = t.size;
  const std::size_t count = std::size_t(t.size) * t.size;
  for (std::size_t k = 0; k < count; ++k) {
    const LtcCoefficients& b = t.brdf[k];
    const LtcCoefficients& n = t.ndf[k];
    s.brdf.insert(s.brdf.end(), {b.m00, b.m02, b.m20, b.m22, t.albedo[k], t.fresnel[k]});
    s.ndf.insert(s.ndf.end(), {n.m00, n.m02, n.m20, n.m22, t.d_pr[k]});
  }
  return s;
}

const LtcTables& ltc_ggx_tables() {
  static const LtcTables tables = parse_ltc_tables(detail::kLtcBrdfCsv, detail::kLtcNdfCsv);
  return tables;
}

const LtcTableView& ltc_ggx_table_view() {
  static const LtcTableStorage storage = flatten_ltc_tables(ltc_ggx_tables());
  static const LtcTableView view = storage.view();
  return view;
}

}  // namespace glintlab
