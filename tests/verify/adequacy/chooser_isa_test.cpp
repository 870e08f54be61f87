// Every engine chooser compiled per ISA (chooser_isa_<isa>.cpp, each with its ISA's flags) against
// the scalar double chooser on the measured tables' cells, quick and full grids, at TAU and
// TAU × 10: every lane's level equal to the scalar level bit for bit. The binomial chooser runs on
// the binomial family's (N_P, p) and on the area family's (the model's LTC p: the area chooser,
// core/glints/area_chooser.h, is scalar, its binomial step on lanes), by GPU order and by a
// measured cost order; deliot_belcour's and kneiphof_klein's wrappers, the Kemppinen family's
// (kemppinen_ggx, kemppinen_beckmann) and the Chermain family's on each cell's parameters and
// query, and those two families' choosers for given costs (core/glints/cost_chooser.h). An ISA
// this CPU lacks is skipped with the reason (GLINTLAB_MAX_ISA caps it too). The comparison can
// fail: a lane path whose selects take the other arm in the batch's last lane
// disagrees with the scalar chooser on every ISA. The float batches of the same choosers
// (`ChooserIsaFloat`) against the scalar double chooser: the rows where float chooses otherwise
// counted, each explained by a boundary within a stated move, the counts stated; so are the
// choosers for given costs on float.
#include "verify/adequacy/chooser_isa.h"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "core/glints/adequacy.h"
#include "core/glints/chermain_chooser.h"
#include "core/glints/cost_chooser.h"
#include "core/models/kemppinen_beckmann.h"
#include "core/models/kemppinen_ggx.h"
#include "core/simd/batch.h"
#include "verify/adequacy/area_adequacy.h"
#include "verify/adequacy/binomial_adequacy.h"
#include "verify/adequacy/chermain_adequacy.h"
#include "verify/adequacy/kemppinen_adequacy.h"

namespace glintlab::verify::adequacy::isa_test {
namespace {

using simd::Isa;
using simd::isa_name;
using simd::isa_supported;

constexpr std::array<double, 2> kTaus = {kDefaultThreshold, 10 * kDefaultThreshold};
constexpr std::array<Budget, 2> kBudgets = {Budget::kQuick, Budget::kFull};

struct IsaCase {
  Isa isa;
  const char* name;  // in the test's output
  ChooserIsaUnit (*unit)();
};
constexpr IsaCase kCases[] = {{Isa::kScalar, "scalar", chooser_isa_scalar},
                              {Isa::kSse42, "sse42", chooser_isa_sse42},
                              {Isa::kAvx2, "avx2", chooser_isa_avx2},
                              {Isa::kAvx512, "avx512", chooser_isa_avx512}};

// Rows of one chooser call: parameters shared, a query and a TAU per row, the scalar level.
struct Rows {
  std::vector<double> facets, p;      // the binomial chooser's inputs
  std::vector<ModelQuery<double>> q;  // the model wrappers' queries
  std::vector<double> tau, scalar;
};

// Rows whose level differs from the scalar one, bit for bit (the first few printed).
std::size_t differing(const std::vector<double>& got, const std::vector<double>& want,
                      const std::string& what) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < got.size(); ++i)
    if (std::bit_cast<std::uint64_t>(got[i]) != std::bit_cast<std::uint64_t>(want[i])) {
      if (n < 3)
        ADD_FAILURE() << what << " row " << i << ": lanes " << got[i] << ", scalar " << want[i];
      ++n;
    }
  return n;
}
std::size_t count_differing(const std::vector<double>& got, const std::vector<double>& want) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < got.size(); ++i)
    n += std::bit_cast<std::uint64_t>(got[i]) != std::bit_cast<std::uint64_t>(want[i]) ? 1 : 0;
  return n;
}

// The binomial chooser's rows: every cell of the binomial and area tables (quick and full), its
// clamped p as the table computes it, at both TAUs.
const Rows& binomial_rows() {
  static const Rows rows = [] {
    Rows r;
    for (Budget b : kBudgets) {
      std::vector<Cell> cells = make_grid({"deliot_belcour", "kneiphof_klein"}, grid_axes(b));
      const std::vector<Cell> area = make_grid({"kneiphof_klein_area"}, area_grid_axes(b));
      cells.insert(cells.end(), area.begin(), area.end());
      for (const Cell& c : cells) {
        const double p = cell_probability_and_smooth(c).first;
        for (double tau : kTaus) {
          r.facets.push_back(c.facets);
          r.p.push_back(p);
          r.tau.push_back(tau);
          r.scalar.push_back(choose_binomial_level(c.facets, p, tau));
        }
      }
    }
    return r;
  }();
  return rows;
}

// A model's table as groups of consecutive cells with the same parameters (the grids vary the
// footprint fastest): one chooser call per group.
struct Group {
  std::vector<double> params;              // the model's parameter values (binomial, Kemppinen)
  const ChermainCell* chermain = nullptr;  // the group's first cell (Chermain)
  Rows rows;
  // A query's rows at both TAUs, with the scalar chooser's levels.
  template <class Scalar>
  void add(const ModelQuery<double>& q, Scalar&& scalar) {
    for (double tau : kTaus) {
      rows.q.push_back(q);
      rows.tau.push_back(tau);
      rows.scalar.push_back(scalar(q, tau));
    }
  }
};

template <class M>
std::vector<Group> binomial_model_groups(const std::vector<Cell>& cells) {
  std::vector<Group> groups;
  for (const Cell& c : cells) {
    const std::vector<double> v = level_param_values(c, BinomialLevel::kExact, 0);
    if (groups.empty() || groups.back().params != v) groups.push_back({v, nullptr, {}});
    const auto ps = M::template params<double>(v);
    groups.back().add(cell_query(c, 0.5, 0.5), [&](const ModelQuery<double>& q, double tau) {
      if constexpr (std::is_same_v<M, DeliotBelcour>)
        return choose_deliot_belcour_level(ps, q, tau);
      else
        return choose_kneiphof_klein_level(ps, q, tau);
    });
  }
  return groups;
}

// The Kemppinen and Chermain tables at two surface positions per cell.
template <class M>
std::vector<Group> kemppinen_groups(const std::vector<KemppinenCell>& cells) {
  std::vector<Group> groups;
  for (const KemppinenCell& c : cells) {
    const std::vector<double> v = kemppinen_level_param_values(c, KemppinenLevel::kK16Exact, 0);
    if (groups.empty() || groups.back().params != v) groups.push_back({v, nullptr, {}});
    const auto ps = M::template params<double>(v);
    for (int i = 0; i < 2; ++i)
      groups.back().add(kemppinen_cell_query(c, kemppinen_surface_position(c, i)),
                        [&](const ModelQuery<double>& q, double tau) {
                          return choose_kemppinen_model_level(ps, q, tau);
                        });
  }
  return groups;
}

// The Chermain table's cells grouped by (roughness, dh), which make its parameters.
std::vector<Group> chermain_groups(const std::vector<ChermainCell>& cells) {
  std::vector<Group> groups;
  Chermain::Params<double> ps{};
  for (const ChermainCell& c : cells) {
    if (groups.empty() || groups.back().chermain->alpha != c.alpha ||
        groups.back().chermain->dh != c.dh) {
      groups.push_back({{}, &c, {}});
      ps = chermain_level_params(c, kChermainMostComplete, 0);
    }
    for (int i = 0; i < 2; ++i)
      groups.back().add(chermain_cell_query(c, chermain_surface_position(c, i)),
                        [&](const ModelQuery<double>& q, double tau) {
                          return choose_chermain_model_level(ps, q, tau);
                        });
  }
  return groups;
}

// Every family's groups over its quick and full grids, each built once (the cells outlive them).
template <class CellT, class Make>
std::vector<CellT> both_budgets(Make&& make) {
  std::vector<CellT> cells;
  for (Budget b : kBudgets) {
    const std::vector<CellT> part = make(b);
    cells.insert(cells.end(), part.begin(), part.end());
  }
  return cells;
}
const std::vector<Group>& db_groups() {
  static const std::vector<Cell> cells =
      both_budgets<Cell>([](Budget b) { return make_grid({"deliot_belcour"}, grid_axes(b)); });
  static const std::vector<Group> groups = binomial_model_groups<DeliotBelcour>(cells);
  return groups;
}
const std::vector<Group>& kk_groups() {
  static const std::vector<Cell> cells =
      both_budgets<Cell>([](Budget b) { return make_grid({"kneiphof_klein"}, grid_axes(b)); });
  static const std::vector<Group> groups = binomial_model_groups<KneiphofKlein>(cells);
  return groups;
}
template <class M>
const std::vector<Group>& kemppinen_model_groups() {
  static const std::vector<KemppinenCell> cells = both_budgets<KemppinenCell>([](Budget b) {
    return make_kemppinen_grid({std::string(M::kName)}, kemppinen_grid_axes(b));
  });
  static const std::vector<Group> groups = kemppinen_groups<M>(cells);
  return groups;
}
const std::vector<Group>& chermain_model_groups() {
  static const std::vector<ChermainCell> cells = both_budgets<ChermainCell>(
      [](Budget b) { return make_chermain_grid({"chermain"}, chermain_grid_axes(b)); });
  static const std::vector<Group> groups = chermain_groups(cells);
  return groups;
}

// A family's levels on one ISA (`call` runs one group), concatenated over its groups, with the
// scalar levels in the same order.
template <class F>
std::pair<std::vector<double>, std::vector<double>> run_groups(const std::vector<Group>& groups,
                                                               F&& call) {
  std::vector<double> got, want;
  for (const Group& g : groups) {
    std::vector<double> out(g.rows.q.size());
    call(g, out.data());
    got.insert(got.end(), out.begin(), out.end());
    want.insert(want.end(), g.rows.scalar.begin(), g.rows.scalar.end());
  }
  return {got, want};
}

// Each test runs its comparisons on every ISA case in turn, in one process: the tables and the
// Chermain dictionary they read are built once for the four (one process per ISA built them four
// times). A case this CPU lacks is said in one line and not compared.
template <bool kFloat>
class EveryIsa : public ::testing::Test {
 protected:
  template <class Body>
  void for_each_isa(Body&& body) {
    int compared = 0;
    for (const IsaCase& c : kCases) {
      if (!isa_supported(c.isa)) {
        std::printf("%s: this CPU lacks it; its choosers are compiled, not compared\n",
                    std::string(isa_name(c.isa)).c_str());
        continue;
      }
      SCOPED_TRACE(c.name);
      case_ = &c;
      fns_ = kFloat ? c.unit().f32 : c.unit().f64;
      body();
      ++compared;
    }
    EXPECT_GT(compared, 0);
  }
  const IsaCase& param() const { return *case_; }
  const IsaCase* case_ = nullptr;
  ChooserIsaFns fns_{};
};

class ChooserIsa : public EveryIsa<false> {
 protected:
  std::pair<std::vector<double>, std::vector<double>> binomial_model(const std::vector<Group>& g,
                                                                     bool db, LanePath path) {
    return run_groups(g, [&](const Group& x, double* out) {
      (db ? fns_.deliot_belcour : fns_.kneiphof_klein)(x.params, x.rows.q.data(), x.rows.tau.data(),
                                                       out, x.rows.q.size(), path);
    });
  }
  std::pair<std::vector<double>, std::vector<double>> chermain(LanePath path) {
    return run_groups(chermain_model_groups(), [&](const Group& x, double* out) {
      const auto ps = chermain_level_params(*x.chermain, kChermainMostComplete, 0);
      fns_.chermain(ps.sdf, ps.d, x.rows.q.data(), x.rows.tau.data(), out, x.rows.q.size(), path);
    });
  }
};

TEST_F(ChooserIsa, BinomialLanesMatchScalarOnTheBinomialAndAreaTables) {
  for_each_isa([&] {
    const Rows& r = binomial_rows();
    const std::size_t n = r.tau.size();
    std::vector<double> out(n);
    fns_.binomial(r.facets.data(), r.p.data(), r.tau.data(), out.data(), n, LanePath::kLibrary);
    EXPECT_EQ(differing(out, r.scalar, "binomial"), 0u) << n << " rows";
    // The rows reach every level.
    std::array<int, kBinomialLevels> seen{};
    for (double l : r.scalar) ++seen[std::size_t(l)];
    for (int s : seen) EXPECT_GT(s, 0);
    // By a measured cost order (this CPU's order of the benchmark rows, exact cheaper than two
    // counting levels).
    const std::array<double, kBinomialLevels> cost = {25, 85, 90, 50};
    std::vector<double> want(n);
    for (std::size_t i = 0; i < n; ++i)
      want[i] = choose_binomial_level_by_cost(r.facets[i], r.p[i], r.tau[i], cost);
    fns_.binomial_by_cost(r.facets.data(), r.p.data(), r.tau.data(), cost, out.data(), n,
                          LanePath::kLibrary);
    EXPECT_EQ(differing(out, want, "binomial by cost"), 0u) << n << " rows";
    // The control: the same chooser with the last lane's selects swapped is caught.
    fns_.binomial_by_cost(r.facets.data(), r.p.data(), r.tau.data(), cost, out.data(), n,
                          LanePath::kLastLaneSwapped);
    const std::size_t broken = count_differing(out, want);
    EXPECT_GT(broken, 0u);
    std::printf("%s (%zu lanes), last lane swapped: binomial by cost %zu of %zu rows differ\n",
                param().name, fns_.lanes, broken, n);
  });
}

TEST_F(ChooserIsa, BinomialModelWrappersMatchScalarOnTheirTables) {
  for_each_isa([&] {
    const auto [db, db_want] = binomial_model(db_groups(), true, LanePath::kLibrary);
    EXPECT_EQ(differing(db, db_want, "deliot_belcour"), 0u) << db.size() << " rows";
    const auto [kk, kk_want] = binomial_model(kk_groups(), false, LanePath::kLibrary);
    EXPECT_EQ(differing(kk, kk_want, "kneiphof_klein"), 0u) << kk.size() << " rows";
  });
}

TEST_F(ChooserIsa, KemppinenLanesMatchScalarOnItsTable) {
  for_each_isa([&] {
    for (const bool ggx : {true, false}) {
      const auto [got, want] =
          run_groups(ggx ? kemppinen_model_groups<KemppinenGGX>()
                         : kemppinen_model_groups<KemppinenBeckmann>(),
                     [&](const Group& x, double* out) {
                       (ggx ? fns_.kemppinen_ggx : fns_.kemppinen_beckmann)(
                           x.params, x.rows.q.data(), x.rows.tau.data(), out, x.rows.q.size());
                     });
      EXPECT_EQ(differing(got, want, ggx ? "kemppinen_ggx" : "kemppinen_beckmann"), 0u)
          << got.size() << " rows";
      // The rows reach the smooth level and a counting one.
      std::size_t smooth = 0;
      for (double l : want) smooth += l == 0 ? 1 : 0;
      EXPECT_GT(smooth, 0u);
      EXPECT_LT(smooth, want.size());
    }
  });
}

// The choosers for given costs on every ISA, by a measured order (docs/adequacy.md "Cost from the
// benchmarks", AVX-512: k16_exact below k16_rational, dict12 below dict4_ggaa), against the scalar.
constexpr std::array<double, 9> kKemppinenMeasuredOrder = {15,    1094,  1120,  3555, 3581,
                                                           15181, 15419, 51471, 50879};
constexpr std::array<double, 9> kChermainMeasuredOrder = {34, 246, 534, 425, 991,
                                                          530, 1357, 709, 1877};

TEST_F(ChooserIsa, CostChoosersLanesMatchScalarOnTheirTablesAndASwappedLaneIsCaught) {
  for_each_isa([&] {
    for (const bool ggx : {true, false}) {
      const std::vector<Group>& groups = ggx ? kemppinen_model_groups<KemppinenGGX>()
                                             : kemppinen_model_groups<KemppinenBeckmann>();
      const auto by_cost = ggx ? fns_.kemppinen_ggx_by_cost : fns_.kemppinen_beckmann_by_cost;
      std::vector<double> got, want, broken;
      for (const Group& g : groups) {
        std::vector<double> out(g.rows.q.size());
        by_cost(g.params, g.rows.q.data(), g.rows.tau.data(), kKemppinenMeasuredOrder, out.data(),
                out.size(), LanePath::kLibrary);
        got.insert(got.end(), out.begin(), out.end());
        by_cost(g.params, g.rows.q.data(), g.rows.tau.data(), kKemppinenMeasuredOrder, out.data(),
                out.size(), LanePath::kLastLaneSwapped);
        broken.insert(broken.end(), out.begin(), out.end());
        for (std::size_t i = 0; i < out.size(); ++i) {
          if (ggx)
            want.push_back(choose_kemppinen_model_level_by_cost(
                KemppinenGGX::params<double>(g.params), g.rows.q[i], g.rows.tau[i],
                kKemppinenMeasuredOrder));
          else
            want.push_back(choose_kemppinen_model_level_by_cost(
                KemppinenBeckmann::params<double>(g.params), g.rows.q[i], g.rows.tau[i],
                kKemppinenMeasuredOrder));
        }
      }
      const char* family = ggx ? "kemppinen_ggx by cost" : "kemppinen_beckmann by cost";
      EXPECT_EQ(differing(got, want, family), 0u) << got.size() << " rows";
      // The control: the level composed by cost with the last lane's selects swapped is caught.
      const std::size_t differ = count_differing(broken, want);
      EXPECT_GT(differ, 0u) << family;
      std::printf("%s (%zu lanes), last lane swapped: %s %zu of %zu rows differ\n", param().name,
                  fns_.lanes, family, differ, broken.size());
    }
    std::vector<double> got, want, broken;
    for (const Group& g : chermain_model_groups()) {
      const auto ps = chermain_level_params(*g.chermain, kChermainMostComplete, 0);
      std::vector<double> out(g.rows.q.size());
      fns_.chermain_by_cost(ps.sdf, ps.d, g.rows.q.data(), g.rows.tau.data(),
                            kChermainMeasuredOrder, out.data(), out.size(), LanePath::kLibrary);
      got.insert(got.end(), out.begin(), out.end());
      fns_.chermain_by_cost(ps.sdf, ps.d, g.rows.q.data(), g.rows.tau.data(),
                            kChermainMeasuredOrder, out.data(), out.size(),
                            LanePath::kLastLaneSwapped);
      broken.insert(broken.end(), out.begin(), out.end());
      for (std::size_t i = 0; i < out.size(); ++i)
        want.push_back(choose_chermain_model_level_by_cost(ps, g.rows.q[i], g.rows.tau[i],
                                                           kChermainMeasuredOrder));
    }
    EXPECT_EQ(differing(got, want, "chermain by cost"), 0u) << got.size() << " rows";
    // The control: the same chooser with the last lane's selects swapped is caught.
    const std::size_t differ = count_differing(broken, want);
    EXPECT_GT(differ, 0u);
    std::printf("%s (%zu lanes), last lane swapped: chermain by cost %zu of %zu rows differ\n",
                param().name, fns_.lanes, differ, broken.size());
  });
}

// (With its control: the default dictionary's construction, about 1.5 s, is the cost of any
// Chermain test, so it is paid once here.)
TEST_F(ChooserIsa, ChermainLanesMatchScalarOnItsTableAndASwappedLaneIsCaught) {
  for_each_isa([&] {
    const auto [got, want] = chermain(LanePath::kLibrary);
    EXPECT_EQ(differing(got, want, "chermain"), 0u) << got.size() << " rows";
    std::size_t smooth = 0;
    for (double l : want) smooth += l == 0 ? 1 : 0;
    EXPECT_GT(smooth, 0u);
    EXPECT_LT(smooth, want.size());
    const auto [broken, broken_want] = chermain(LanePath::kLastLaneSwapped);
    const std::size_t differ = count_differing(broken, broken_want);
    EXPECT_GT(differ, 0u);
    std::printf("%s (%zu lanes), last lane swapped: chermain %zu of %zu rows differ\n",
                param().name, fns_.lanes, differ, broken.size());
  });
}

// The control: the same comparisons fail a lane path whose selects are swapped in one lane.
TEST_F(ChooserIsa, ALaneWithSwappedSelectsIsCaught) {
  for_each_isa([&] {
    const Rows& r = binomial_rows();
    const std::size_t n = r.tau.size();
    std::vector<double> out(n);
    fns_.binomial(r.facets.data(), r.p.data(), r.tau.data(), out.data(), n,
                  LanePath::kLastLaneSwapped);
    const std::size_t binomial = count_differing(out, r.scalar);
    const auto [db, db_want] = binomial_model(db_groups(), true, LanePath::kLastLaneSwapped);
    const auto [kk, kk_want] = binomial_model(kk_groups(), false, LanePath::kLastLaneSwapped);
    const std::size_t db_differ = count_differing(db, db_want),
                      kk_differ = count_differing(kk, kk_want);
    EXPECT_GT(binomial, 0u);
    EXPECT_GT(db_differ, 0u);
    EXPECT_GT(kk_differ, 0u);
    std::printf(
        "%s (%zu lanes), last lane swapped: binomial %zu of %zu rows differ, deliot_belcour "
        "%zu of %zu, kneiphof_klein %zu of %zu\n",
        param().name, fns_.lanes, binomial, n, db_differ, db.size(), kk_differ, kk.size());
  });
}

// ---- The float batches ------------------------------------------------------------------------
//
// The same choosers on float lanes (the inputs rounded to float, every step in float) against the
// scalar double chooser on the same rows. Float may choose another level where a predicted
// quantity lies within float's rounding of its threshold; each differing row is explained by the
// least relative move δ of the ladder kMoves under which the double chooser gives the float
// level: TAU × (1 ± δ) and the footprint (its uv derivatives; for the binomial rows N_P and p) ×
// (1 ± δ). The test states how many rows of each family may differ and the largest move that
// explains them; a broken float lane path exceeds the count.
constexpr std::array<double, 5> kMoves = {1e-6, 1e-5, 1e-4, 1e-3, 1e-2};

// How many rows differ, and how many of them each move of kMoves explains first (the last
// entry: none explains them).
struct FloatDiff {
  std::size_t rows = 0, differ = 0;
  std::array<std::size_t, kMoves.size() + 1> by_move{};
  std::string examples;  // the first differing rows
  // The largest move that explains a differing row (infinity where one is unexplained).
  double largest_move() const {
    double m = 0;
    for (std::size_t k = 0; k < by_move.size(); ++k)
      if (by_move[k] > 0) m = k < kMoves.size() ? kMoves[k] : INFINITY;
    return m;
  }
  std::string text() const {
    std::string t = std::to_string(differ) + " of " + std::to_string(rows) + " rows differ";
    for (std::size_t k = 0; k < by_move.size(); ++k)
      if (by_move[k] > 0) {
        char m[64];
        if (k < kMoves.size())
          std::snprintf(m, sizeof m, "; %zu explained by a move of %g", by_move[k], kMoves[k]);
        else
          std::snprintf(m, sizeof m, "; %zu unexplained", by_move[k]);
        t += m;
      }
    return t + examples;
  }
};

// The index in kMoves of the least move under which level_at(τ scale, footprint scale, p scale)
// is `level` (kMoves.size() where none is).
template <class F>
std::size_t least_move(double level, F&& level_at) {
  for (std::size_t k = 0; k < kMoves.size(); ++k)
    for (int a = -1; a <= 1; ++a)
      for (int b = -1; b <= 1; ++b)
        for (int c = -1; c <= 1; ++c)
          if (level_at(1 + a * kMoves[k], 1 + b * kMoves[k], 1 + c * kMoves[k]) == level)
            return k;
  return kMoves.size();
}

// A query with its footprint scaled (both uv derivatives: the area by scale²).
ModelQuery<double> scaled_footprint(ModelQuery<double> q, double scale) {
  q.footprint.duv_dx = scale * q.footprint.duv_dx;
  q.footprint.duv_dy = scale * q.footprint.duv_dy;
  return q;
}

// Every group's rows through `call` (float lanes) against the scalar double levels;
// perturbed(group, row, τ scale, footprint scale, p scale) is the double chooser moved. The
// broken lane path's rows are counted, not explained (`explain` false: thousands of rows).
template <class Call, class Perturbed>
FloatDiff float_against_double(const std::vector<Group>& groups, Call&& call,
                               Perturbed&& perturbed, bool explain = true) {
  FloatDiff d;
  for (const Group& g : groups) {
    std::vector<double> out(g.rows.tau.size());
    call(g, out.data());
    for (std::size_t i = 0; i < out.size(); ++i) {
      ++d.rows;
      if (std::bit_cast<std::uint64_t>(out[i]) == std::bit_cast<std::uint64_t>(g.rows.scalar[i]))
        continue;
      ++d.differ;
      const std::size_t k = !explain ? kMoves.size()
                                     : least_move(out[i], [&](double ts, double fs, double ps) {
                                         return perturbed(g, i, ts, fs, ps);
                                       });
      ++d.by_move[k];
      if (d.differ <= 5) {
        char line[160];
        std::snprintf(line, sizeof line, "; row %zu: double level %g, float %g, TAU %g, move %g", i,
                      g.rows.scalar[i], out[i], g.rows.tau[i],
                      k < kMoves.size() ? kMoves[k] : INFINITY);
        d.examples += line;
      }
    }
  }
  return d;
}

// The binomial rows as one group.
const std::vector<Group>& binomial_row_group() {
  static const std::vector<Group> g = {Group{{}, nullptr, binomial_rows()}};
  return g;
}

// The measured cost order of the by-cost rows (as in the double test).
constexpr std::array<double, kBinomialLevels> kMeasuredOrder = {25, 85, 90, 50};

// The double chooser moved, per family.
double binomial_moved(const Group& g, std::size_t i, double ts, double fs, double ps) {
  return choose_binomial_level(g.rows.facets[i] * fs, g.rows.p[i] * ps, g.rows.tau[i] * ts);
}
double binomial_by_cost_moved(const Group& g, std::size_t i, double ts, double fs, double ps) {
  return choose_binomial_level_by_cost(g.rows.facets[i] * fs, g.rows.p[i] * ps,
                                       g.rows.tau[i] * ts, kMeasuredOrder);
}
template <class M>
double model_moved(const Group& g, std::size_t i, double ts, double fs, double) {
  const auto ps = M::template params<double>(g.params);
  const ModelQuery<double> q = scaled_footprint(g.rows.q[i], fs);
  const double tau = g.rows.tau[i] * ts;
  if constexpr (std::is_same_v<M, DeliotBelcour>)
    return choose_deliot_belcour_level(ps, q, tau);
  else if constexpr (std::is_same_v<M, KneiphofKlein>)
    return choose_kneiphof_klein_level(ps, q, tau);
  else
    return choose_kemppinen_model_level(ps, q, tau);
}
double chermain_moved(const Group& g, std::size_t i, double ts, double fs, double) {
  const auto ps = chermain_level_params(*g.chermain, kChermainMostComplete, 0);
  return choose_chermain_model_level(ps, scaled_footprint(g.rows.q[i], fs), g.rows.tau[i] * ts);
}
template <class M>
double kemppinen_by_cost_moved(const Group& g, std::size_t i, double ts, double fs, double) {
  return choose_kemppinen_model_level_by_cost(M::template params<double>(g.params),
                                              scaled_footprint(g.rows.q[i], fs),
                                              g.rows.tau[i] * ts, kKemppinenMeasuredOrder);
}
double chermain_by_cost_moved(const Group& g, std::size_t i, double ts, double fs, double) {
  const auto ps = chermain_level_params(*g.chermain, kChermainMostComplete, 0);
  return choose_chermain_model_level_by_cost(ps, scaled_footprint(g.rows.q[i], fs),
                                             g.rows.tau[i] * ts, kChermainMeasuredOrder);
}

// Groups whose scalar levels are the double chooser for given costs' (by a measured order).
template <class M>
std::vector<Group> kemppinen_by_cost_groups() {
  std::vector<Group> groups = kemppinen_model_groups<M>();
  for (Group& g : groups)
    for (std::size_t i = 0; i < g.rows.q.size(); ++i)
      g.rows.scalar[i] = kemppinen_by_cost_moved<M>(g, i, 1, 1, 1);
  return groups;
}
std::vector<Group> chermain_by_cost_groups() {
  std::vector<Group> groups = chermain_model_groups();
  for (Group& g : groups)
    for (std::size_t i = 0; i < g.rows.q.size(); ++i)
      g.rows.scalar[i] = chermain_by_cost_moved(g, i, 1, 1, 1);
  return groups;
}

class ChooserIsaFloat : public EveryIsa<true> {
 protected:
  FloatDiff binomial(LanePath path) {
    return float_against_double(
        binomial_row_group(),
        [&](const Group& g, double* out) {
          fns_.binomial(g.rows.facets.data(), g.rows.p.data(), g.rows.tau.data(), out,
                        g.rows.tau.size(), path);
        },
        binomial_moved, path == LanePath::kLibrary);
  }
  FloatDiff binomial_by_cost() {
    std::vector<Group> g = binomial_row_group();
    for (std::size_t i = 0; i < g[0].rows.tau.size(); ++i)
      g[0].rows.scalar[i] = choose_binomial_level_by_cost(g[0].rows.facets[i], g[0].rows.p[i],
                                                          g[0].rows.tau[i], kMeasuredOrder);
    return float_against_double(
        g,
        [&](const Group& x, double* out) {
          fns_.binomial_by_cost(x.rows.facets.data(), x.rows.p.data(), x.rows.tau.data(),
                                kMeasuredOrder, out, x.rows.tau.size(), LanePath::kLibrary);
        },
        binomial_by_cost_moved);
  }
  template <class M>
  FloatDiff binomial_model(LanePath path) {
    const bool db = std::is_same_v<M, DeliotBelcour>;
    return float_against_double(
        db ? db_groups() : kk_groups(),
        [&](const Group& x, double* out) {
          (db ? fns_.deliot_belcour : fns_.kneiphof_klein)(x.params, x.rows.q.data(),
                                                           x.rows.tau.data(), out,
                                                           x.rows.q.size(), path);
        },
        model_moved<M>, path == LanePath::kLibrary);
  }
  template <class M>
  FloatDiff kemppinen() {
    const bool ggx = std::is_same_v<M, KemppinenGGX>;
    return float_against_double(
        kemppinen_model_groups<M>(),
        [&](const Group& x, double* out) {
          (ggx ? fns_.kemppinen_ggx : fns_.kemppinen_beckmann)(
              x.params, x.rows.q.data(), x.rows.tau.data(), out, x.rows.q.size());
        },
        model_moved<M>);
  }
  FloatDiff chermain(LanePath path) {
    return float_against_double(
        chermain_model_groups(),
        [&](const Group& x, double* out) {
          const auto ps = chermain_level_params(*x.chermain, kChermainMostComplete, 0);
          fns_.chermain(ps.sdf, ps.d, x.rows.q.data(), x.rows.tau.data(), out, x.rows.q.size(),
                        path);
        },
        chermain_moved, path == LanePath::kLibrary);
  }
  template <class M>
  FloatDiff kemppinen_by_cost(LanePath path) {
    const bool ggx = std::is_same_v<M, KemppinenGGX>;
    return float_against_double(
        kemppinen_by_cost_groups<M>(),
        [&](const Group& x, double* out) {
          (ggx ? fns_.kemppinen_ggx_by_cost : fns_.kemppinen_beckmann_by_cost)(
              x.params, x.rows.q.data(), x.rows.tau.data(), kKemppinenMeasuredOrder, out,
              x.rows.q.size(), path);
        },
        kemppinen_by_cost_moved<M>, path == LanePath::kLibrary);
  }
  FloatDiff chermain_by_cost(LanePath path) {
    return float_against_double(
        chermain_by_cost_groups(),
        [&](const Group& x, double* out) {
          const auto ps = chermain_level_params(*x.chermain, kChermainMostComplete, 0);
          fns_.chermain_by_cost(ps.sdf, ps.d, x.rows.q.data(), x.rows.tau.data(),
                                kChermainMeasuredOrder, out, x.rows.q.size(), path);
        },
        chermain_by_cost_moved, path == LanePath::kLibrary);
  }
  void report(const char* family, const FloatDiff& d) {
    std::printf("%s float (%zu lanes), %s: %s\n", param().name, fns_.lanes, family,
                d.text().c_str());
  }
};

// What each family's float lanes may differ by, on every ISA (the scalar unit on the C
// library's float functions, the batches on xsimd's): the rows and the largest move.
struct FloatAllowance {
  std::size_t rows;
  double move;
};
constexpr FloatAllowance kBinomialFloat = {0, 0};
constexpr FloatAllowance kDeliotBelcourFloat = {0, 0};
constexpr FloatAllowance kKneiphofKleinFloat = {1, 1e-4};
constexpr FloatAllowance kKemppinenGgxFloat = {2, 1e-3};
constexpr FloatAllowance kKemppinenBeckmannFloat = {0, 0};
constexpr FloatAllowance kChermainFloat = {0, 0};
// The choosers for given costs by the measured order.
constexpr FloatAllowance kKemppinenGgxByCostFloat = {2, 1e-3};
constexpr FloatAllowance kKemppinenBeckmannByCostFloat = {0, 0};
constexpr FloatAllowance kChermainByCostFloat = {0, 0};

void expect_within(const FloatDiff& d, const FloatAllowance& a, const char* family) {
  EXPECT_LE(d.differ, a.rows) << family << ": " << d.text();
  EXPECT_LE(d.largest_move(), a.move) << family << ": " << d.text();
}

TEST_F(ChooserIsaFloat, BinomialFloatLanesDifferOnlyAtBoundariesWithinFloatRounding) {
  for_each_isa([&] {
    const FloatDiff b = binomial(LanePath::kLibrary), c = binomial_by_cost();
    report("binomial", b);
    report("binomial by cost", c);
    expect_within(b, kBinomialFloat, "binomial");
    expect_within(c, kBinomialFloat, "binomial by cost");
    const FloatDiff db = binomial_model<DeliotBelcour>(LanePath::kLibrary);
    const FloatDiff kk = binomial_model<KneiphofKlein>(LanePath::kLibrary);
    report("deliot_belcour", db);
    report("kneiphof_klein", kk);
    expect_within(db, kDeliotBelcourFloat, "deliot_belcour");
    expect_within(kk, kKneiphofKleinFloat, "kneiphof_klein");
  });
}

TEST_F(ChooserIsaFloat, KemppinenFloatLanesDifferOnlyAtBoundariesWithinFloatRounding) {
  for_each_isa([&] {
    const FloatDiff ggx = kemppinen<KemppinenGGX>(), beckmann = kemppinen<KemppinenBeckmann>();
    report("kemppinen_ggx", ggx);
    report("kemppinen_beckmann", beckmann);
    expect_within(ggx, kKemppinenGgxFloat, "kemppinen_ggx");
    expect_within(beckmann, kKemppinenBeckmannFloat, "kemppinen_beckmann");
  });
}

// With its control (the dictionary's construction is paid once per test).
TEST_F(ChooserIsaFloat, ChermainFloatLanesDifferOnlyAtBoundariesAndASwappedLaneExceedsTheCount) {
  for_each_isa([&] {
    const FloatDiff d = chermain(LanePath::kLibrary);
    report("chermain", d);
    expect_within(d, kChermainFloat, "chermain");
    const FloatDiff broken = chermain(LanePath::kLastLaneSwapped);
    report("chermain, last lane swapped", broken);
    EXPECT_GT(broken.differ, kChermainFloat.rows);
  });
}

// The choosers for given costs (core/glints/cost_chooser.h) by the measured order, in float
// against the scalar double chooser for the same costs, with their controls (the Kemppinen ones'
// selects swapped where the level is composed by cost, as in double).
TEST_F(ChooserIsaFloat,
       CostChoosersFloatLanesDifferOnlyAtBoundariesAndASwappedLaneExceedsTheCount) {
  for_each_isa([&] {
    const FloatDiff ggx = kemppinen_by_cost<KemppinenGGX>(LanePath::kLibrary);
    const FloatDiff beckmann = kemppinen_by_cost<KemppinenBeckmann>(LanePath::kLibrary);
    const FloatDiff ch = chermain_by_cost(LanePath::kLibrary);
    report("kemppinen_ggx by cost", ggx);
    report("kemppinen_beckmann by cost", beckmann);
    report("chermain by cost", ch);
    expect_within(ggx, kKemppinenGgxByCostFloat, "kemppinen_ggx by cost");
    expect_within(beckmann, kKemppinenBeckmannByCostFloat, "kemppinen_beckmann by cost");
    expect_within(ch, kChermainByCostFloat, "chermain by cost");
    const FloatDiff broken = chermain_by_cost(LanePath::kLastLaneSwapped);
    report("chermain by cost, last lane swapped", broken);
    EXPECT_GT(broken.differ, kChermainByCostFloat.rows);
    const FloatDiff ggx_broken = kemppinen_by_cost<KemppinenGGX>(LanePath::kLastLaneSwapped);
    const FloatDiff beckmann_broken =
        kemppinen_by_cost<KemppinenBeckmann>(LanePath::kLastLaneSwapped);
    report("kemppinen_ggx by cost, last lane swapped", ggx_broken);
    report("kemppinen_beckmann by cost, last lane swapped", beckmann_broken);
    EXPECT_GT(ggx_broken.differ, kKemppinenGgxByCostFloat.rows);
    EXPECT_GT(beckmann_broken.differ, kKemppinenBeckmannByCostFloat.rows);
  });
}

// The control: a float lane path whose selects are swapped in one lane exceeds the counts.
TEST_F(ChooserIsaFloat, ALaneWithSwappedSelectsExceedsTheAllowedCounts) {
  for_each_isa([&] {
    const FloatDiff b = binomial(LanePath::kLastLaneSwapped);
    const FloatDiff db = binomial_model<DeliotBelcour>(LanePath::kLastLaneSwapped);
    const FloatDiff kk = binomial_model<KneiphofKlein>(LanePath::kLastLaneSwapped);
    report("binomial, last lane swapped", b);
    report("deliot_belcour, last lane swapped", db);
    report("kneiphof_klein, last lane swapped", kk);
    EXPECT_GT(b.differ, kBinomialFloat.rows);
    EXPECT_GT(db.differ, kDeliotBelcourFloat.rows);
    EXPECT_GT(kk.differ, kKneiphofKleinFloat.rows);
  });
}

}  // namespace
}  // namespace glintlab::verify::adequacy::isa_test
