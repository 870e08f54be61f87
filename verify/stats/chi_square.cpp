// Chi-square goodness of fit with cubature expectations; see chi_square.h.
#include "verify/stats/chi_square.h"

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/non_central_chi_squared.hpp>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>
#include <utility>

namespace glintlab::verify {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2 * std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::uint64_t kNone = std::numeric_limits<std::uint64_t>::max();

// ---- Adaptive Gauss–Kronrod in one dimension --------------------------------------------------

// A value with the error it already carries (the inner integral's estimate, for nested cubature).
struct ValErr {
  double value = 0;
  double error = 0;
};

struct Piece {
  double a, b;
  double value;
  double rule_error;     // |Kronrod − Gauss| on this piece
  double carried_error;  // the integrand's own error estimates, integrated by the Kronrod rule
};

// 15-point Kronrod with the embedded 7-point Gauss rule: the integrand at its 15 abscissae (0 and
// ± the 7 positive ones Boost lists; gk_abscissae, in the order the rule sums them), combined by
// gk_combine.
constexpr std::size_t kGkPoints = 15;

void gk_abscissae(double a, double b, double* out) {
  static const auto& x = boost::math::quadrature::gauss_kronrod<double, 15>::abscissa();
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  std::size_t k = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    out[k++] = c + h * x[i];
    if (i != 0) out[k++] = c - h * x[i];
  }
}

Piece gk_combine(const ValErr* f, double a, double b) {
  static const auto& x = boost::math::quadrature::gauss_kronrod<double, 15>::abscissa();
  static const auto& wk = boost::math::quadrature::gauss_kronrod<double, 15>::weights();
  static const auto& wg = boost::math::quadrature::gauss<double, 7>::weights();
  const double h = 0.5 * (b - a);
  double k = 0, g = 0, carried = 0;
  std::size_t next = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    ValErr s = f[next++];
    if (i != 0) {
      const ValErr m = f[next++];
      s.value += m.value;
      s.error += m.error;
    }
    k += wk[i] * s.value;
    carried += wk[i] * s.error;
    if (i % 2 == 0) g += wg[i / 2] * s.value;  // the Gauss nodes are the even Kronrod abscissae
  }
  return {a, b, k * h, std::abs((k - g) * h), std::abs(carried * h)};
}

bool finite(const Piece& p) {
  return std::isfinite(p.value) && std::isfinite(p.rule_error) && std::isfinite(p.carried_error);
}

// Globally adaptive: bisect the piece with the largest rule error until the summed rule error is
// ≤ max(abs_tol, rel_tol·|I|) or max_subdivisions bisections are spent. The returned error is the
// summed rule error plus the carried errors. Non-finite integrands give NaN.
// A step machine, so that many integrations run in lockstep with their integrand evaluated for
// all of them at once (integrate_bin): wanted() is the pieces whose rule the next step needs,
// feed() takes them, in that order.
class AdaptiveGk {
 public:
  AdaptiveGk() = default;
  AdaptiveGk(const std::vector<double>& nodes, double abs_tol, double rel_tol,
             unsigned max_subdivisions) {
    start(nodes, abs_tol, rel_tol, max_subdivisions);
  }
  // A new integration, keeping the storage of the last one (the cubature starts millions).
  void start(const std::vector<double>& nodes, double abs_tol, double rel_tol,
             unsigned max_subdivisions) {
    abs_tol_ = abs_tol;
    rel_tol_ = rel_tol;
    max_subdivisions_ = max_subdivisions;
    subdivisions_ = 0;
    heap_.clear();
    wanted_.clear();
    worst_ = {};
    value_ = rule_ = 0;
    initial_ = true;
    done_ = false;
    result_ = {};
    for (std::size_t i = 0; i + 1 < nodes.size(); ++i) wanted_.push_back({nodes[i], nodes[i + 1]});
    if (wanted_.empty()) finish();
  }
  bool done() const { return done_; }
  const std::vector<std::pair<double, double>>& wanted() const { return wanted_; }
  ValErr result() const { return result_; }

  void feed(std::span<const Piece> pieces) {
    if (initial_) {
      initial_ = false;
      for (const Piece& p : pieces) {
        if (!finite(p)) return fail();
        heap_.push_back(p);
        value_ += p.value;
        rule_ += p.rule_error;
      }
      std::make_heap(heap_.begin(), heap_.end(), less);
    } else {
      const Piece &l = pieces[0], &r = pieces[1];
      if (!finite(l) || !finite(r)) return fail();
      value_ += l.value + r.value - worst_.value;
      rule_ += l.rule_error + r.rule_error - worst_.rule_error;
      heap_.push_back(l);
      std::push_heap(heap_.begin(), heap_.end(), less);
      heap_.push_back(r);
      std::push_heap(heap_.begin(), heap_.end(), less);
      ++subdivisions_;
    }
    next_step();
  }

 private:
  static bool less(const Piece& p, const Piece& q) { return p.rule_error < q.rule_error; }
  void next_step() {
    wanted_.clear();
    if (subdivisions_ >= max_subdivisions_ || heap_.empty() ||
        rule_ <= std::max(abs_tol_, rel_tol_ * std::abs(value_)))
      return finish();
    std::pop_heap(heap_.begin(), heap_.end(), less);
    worst_ = heap_.back();
    const double mid = 0.5 * (worst_.a + worst_.b);
    if (!(mid > worst_.a && mid < worst_.b)) {
      std::push_heap(heap_.begin(), heap_.end(), less);
      return finish();
    }
    heap_.pop_back();
    wanted_ = {{worst_.a, mid}, {mid, worst_.b}};
  }
  void fail() {
    wanted_.clear();
    result_ = {kNaN, kNaN};
    done_ = true;
  }
  void finish() {
    // Re-sum in interval order: no drift from the running updates, and an order-free result.
    std::sort(heap_.begin(), heap_.end(), [](const Piece& p, const Piece& q) { return p.a < q.a; });
    result_ = {};
    for (const Piece& p : heap_) {
      result_.value += p.value;
      result_.error += p.rule_error + p.carried_error;
    }
    wanted_.clear();
    done_ = true;
  }

  double abs_tol_ = 0, rel_tol_ = 0;
  unsigned max_subdivisions_ = 0, subdivisions_ = 0;
  std::vector<Piece> heap_;
  std::vector<std::pair<double, double>> wanted_;
  Piece worst_{};
  double value_ = 0, rule_ = 0;
  bool initial_ = true, done_ = false;
  ValErr result_;
};

// ---- Polar coordinates of the sampling domain ---------------------------------------------------

// Coordinates (u, φ) with u = 1 − cosθ' on the sphere (dω = du dφ) or u = r² on the disk
// (dA = ½ du dφ), and the radial coordinate t = θ' or r used for the ring edges.
struct PolarMap {
  SampleDomain domain = SampleDomain::kSphere;
  double t_max = kPi;
  Vec3<double> fx{1, 0, 0}, fy{0, 1, 0}, fz{0, 0, 1};
  bool tilted = false;    // hemisphere in a tilted frame: mask z ≥ 0, split at the horizon
  Vec3<double> up{0, 0, 1};  // world +z in frame coordinates
  const DirectionPdf* dpdf = nullptr;
  const DirectionPdfRows* dpdf_rows = nullptr;  // optional: the pdf at many directions per call
  const PointPdf* ppdf = nullptr;

  bool disk() const { return domain == SampleDomain::kDisk; }
  double u_of_t(double t) const {
    if (disk()) return t * t;
    const double s = std::sin(0.5 * t);
    return 2 * s * s;
  }
  double t_of_u(double u) const {
    if (disk()) return std::sqrt(std::max(0.0, u));
    return 2 * std::asin(std::sqrt(std::clamp(0.5 * u, 0.0, 1.0)));
  }
  // The density per du dφ at (u, φ) with c = cosφ, s = sinφ.
  double density(double u, double c, double s) const {
    if (disk()) {
      const double r = std::sqrt(std::max(0.0, u));
      return 0.5 * (*ppdf)(Vec2<double>{0.5 + r * c, 0.5 + r * s});
    }
    const Vec3<double> w = direction(u, c, s);
    if (tilted && w.z < 0) return 0.0;
    return (*dpdf)(w);
  }
  struct Node {
    double u, c, s;
  };
  // density() at many nodes: one call of the direction pdf's rows function where there is one
  // (the batched pdf: its values may differ from the pdf's by a few ULPs), else node by node.
  void densities(std::span<const Node> nodes, std::vector<double>& out,
                 std::vector<Vec3<double>>& w, std::vector<double>& rows) const {
    out.assign(nodes.size(), 0.0);
    if (!dpdf_rows) {
      for (std::size_t k = 0; k < nodes.size(); ++k)
        out[k] = density(nodes[k].u, nodes[k].c, nodes[k].s);
      return;
    }
    w.resize(nodes.size());
    const PolarMap frame = *this;  // locals: the stores to w cannot alias the frame
    Vec3<double>* out_w = w.data();
    for (std::size_t k = 0; k < nodes.size(); ++k)
      out_w[k] = frame.direction(nodes[k].u, nodes[k].c, nodes[k].s);
    if (!tilted) return (*dpdf_rows)(w, out);
    // Below the horizon density() is 0 without asking the pdf.
    std::size_t above = 0;
    for (std::size_t k = 0; k < w.size(); ++k)
      if (!(w[k].z < 0)) w[above++] = w[k];
    rows.assign(above, 0.0);
    if (above > 0) (*dpdf_rows)(std::span<const Vec3<double>>(w.data(), above), rows);
    std::size_t next = 0;
    for (std::size_t k = 0; k < nodes.size(); ++k)
      if (!(direction(nodes[k].u, nodes[k].c, nodes[k].s).z < 0)) out[k] = rows[next++];
  }
  Vec3<double> direction(double u, double c, double s) const {
    const double st = std::sqrt(std::max(0.0, u * (2 - u)));
    return (st * c) * fx + (st * s) * fy + (1 - u) * fz;
  }
  // The u where the horizon z = 0 crosses azimuth φ, for a tilted hemisphere.
  bool horizon_u(double c, double s, double& u) const {
    if (!tilted) return false;
    double th = std::atan2(-up.z, up.x * c + up.y * s);
    if (th < 0) th += kPi;
    u = u_of_t(th);
    return true;
  }
};

struct CubatureSetup {
  std::vector<double> u_breaks;    // sorted, in (0, u_max)
  std::vector<double> phi_breaks;  // sorted, in (0, 2π)
  double n = 1;
  const ChiSquareOptions* options = nullptr;
};

// N-free integral of the density over [u0, u1] × [p0, p1] (probability units).
ValErr integrate_bin(const PolarMap& pm, const CubatureSetup& cs, double u0, double u1, double p0,
                     double p1) {
  if (!(u1 > u0) || !(p1 > p0)) return {};
  const ChiSquareOptions& o = *cs.options;
  std::vector<double> pnodes{p0};
  for (double b : cs.phi_breaks)
    if (b > p0 && b < p1) pnodes.push_back(b);
  pnodes.push_back(p1);
  std::vector<double> base{u0};
  for (double b : cs.u_breaks)
    if (b > u0 && b < u1) base.push_back(b);
  base.push_back(u1);
  const double abs_tol = o.abs_tol_counts / cs.n;
  const double inner_abs = 0.5 * abs_tol / (p1 - p0);
  // The inner rule's nodes at azimuth (c, s): the breaks, and the horizon of a tilted hemisphere.
  auto inner_nodes = [&](double c, double s, std::vector<double>& nodes) {
    nodes.assign(base.begin(), base.end());
    double uh = 0;
    if (pm.horizon_u(c, s, uh) && uh > u0 && uh < u1)
      nodes.insert(std::upper_bound(nodes.begin(), nodes.end(), uh), uh);
  };
  // Each step of the outer rule over φ runs the inner integrals over u at all of its azimuths in
  // lockstep; each round of their bisections evaluates the density at the nodes of all of their
  // rules in one call (PolarMap::densities), so a batched pdf sees hundreds of directions at once.
  // Every integration takes the steps it would take alone, in the same order and arithmetic.
  // Scratch kept per thread across bins: the inner integrations' storage is reused, not
  // allocated anew for each of the millions of integrations a plan runs. One per nesting level: a
  // pdf that waits on a parallel loop may have this thread run another bin meanwhile.
  struct Inner {
    double c = 0, s = 0;
    AdaptiveGk gk;
  };
  struct Scratch {
    std::vector<Inner> inners;
    std::vector<Piece> outer_pieces, pieces;
    std::vector<PolarMap::Node> nodes;
    std::vector<double> density, rows, u_nodes;
    std::vector<Vec3<double>> w;
  };
  thread_local std::vector<std::unique_ptr<Scratch>> pool;
  thread_local std::size_t depth = 0;
  if (depth == pool.size()) pool.push_back(std::make_unique<Scratch>());
  Scratch& z = *pool[depth];
  struct Nest {
    std::size_t& d;
    explicit Nest(std::size_t& level) : d(level) { ++d; }
    ~Nest() { --d; }
    Nest(const Nest&) = delete;
    Nest& operator=(const Nest&) = delete;
  } nest(depth);
  AdaptiveGk outer(pnodes, 0.5 * abs_tol, 0.5 * o.rel_tol, o.max_subdivisions);
  while (!outer.done()) {
    std::size_t count = 0;
    for (const auto& [a, b] : outer.wanted()) {
      double phis[kGkPoints];
      gk_abscissae(a, b, phis);
      for (double phi : phis) {
        if (count == z.inners.size()) z.inners.emplace_back();
        Inner& in = z.inners[count++];
        in.c = std::cos(phi);
        in.s = std::sin(phi);
        inner_nodes(in.c, in.s, z.u_nodes);
        in.gk.start(z.u_nodes, inner_abs, 0.5 * o.rel_tol, o.max_subdivisions);
      }
    }
    const std::span<Inner> inners(z.inners.data(), count);
    for (;;) {
      z.nodes.clear();
      for (const Inner& in : inners) {
        if (in.gk.done()) continue;
        for (const auto& [a, b] : in.gk.wanted()) {
          double us[kGkPoints];
          gk_abscissae(a, b, us);
          for (double u : us) z.nodes.push_back({u, in.c, in.s});
        }
      }
      if (z.nodes.empty()) break;
      pm.densities(z.nodes, z.density, z.w, z.rows);
      std::size_t next = 0;
      for (Inner& in : inners) {
        if (in.gk.done()) continue;
        z.pieces.clear();
        for (const auto& [a, b] : in.gk.wanted()) {
          ValErr v[kGkPoints];
          for (ValErr& x : v) x = {z.density[next++], 0.0};
          z.pieces.push_back(gk_combine(v, a, b));
        }
        in.gk.feed(z.pieces);
      }
    }
    z.outer_pieces.clear();
    std::size_t next = 0;
    for (const auto& [a, b] : outer.wanted()) {
      ValErr v[kGkPoints];
      for (ValErr& x : v) x = inners[next++].gk.result();
      z.outer_pieces.push_back(gk_combine(v, a, b));
    }
    outer.feed(z.outer_pieces);
  }
  return outer.result();
}

// ---- Bin layouts --------------------------------------------------------------------------------

BinGrid make_grid(std::vector<double> t_edges, std::vector<std::size_t> sectors) {
  BinGrid g;
  g.t_edges = std::move(t_edges);
  g.sectors = std::move(sectors);
  g.offset.resize(g.sectors.size() + 1, 0);
  for (std::size_t i = 0; i < g.sectors.size(); ++i) g.offset[i + 1] = g.offset[i] + g.sectors[i];
  return g;
}

std::size_t ring_count(std::size_t bins, double aspect) {
  return std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(std::sqrt(double(bins) / aspect))));
}
std::size_t sector_count(std::size_t bins, std::size_t rings) {
  return std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(double(bins) / double(rings))));
}

BinGrid equal_area_grid(const PolarMap& pm, std::size_t bins, double aspect) {
  const std::size_t rings = ring_count(bins, aspect), sectors = sector_count(bins, rings);
  const double u_max = pm.u_of_t(pm.t_max);
  std::vector<double> edges{0.0};
  for (std::size_t i = 1; i < rings; ++i) edges.push_back(pm.t_of_u(u_max * double(i) / double(rings)));
  edges.push_back(pm.t_max);
  return make_grid(std::move(edges), std::vector<std::size_t>(rings, sectors));
}

// The density's mass in thin full rings [t_j, t_{j+1}] × [0, 2π), refined until no ring holds more
// than total / (16·max_rings).
struct RingMass {
  std::vector<double> t;     // nodes
  std::vector<double> mass;  // per cell
  double total = 0;
  bool ok = true;
  std::string reason;
};

RingMass ring_mass(const PolarMap& pm, const CubatureSetup& cs, std::size_t max_rings) {
  std::vector<double> nodes{0.0, pm.t_max};
  for (int k = 1; k <= 24; ++k) nodes.push_back(std::ldexp(pm.t_max, -k));
  for (int j = 1; j < 512; ++j) nodes.push_back(pm.t_max * j / 512.0);
  for (double b : cs.options->radial_breaks)
    if (b > 0 && b < pm.t_max) nodes.push_back(b);
  if (!pm.disk() && pm.t_max > 0.5 * kPi) nodes.push_back(0.5 * kPi);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  const std::size_t cells = nodes.size() - 1;
  auto ring = [&](double ta, double tb) {
    return integrate_bin(pm, cs, pm.u_of_t(ta), pm.u_of_t(tb), 0.0, kTwoPi).value;
  };
  std::vector<double> coarse(cells);
  tbb::parallel_for(std::size_t(0), cells, [&](std::size_t j) { coarse[j] = ring(nodes[j], nodes[j + 1]); });
  RingMass r;
  for (double m : coarse) {
    if (!std::isfinite(m) || m < 0) {
      r.ok = false;
      r.reason = "the pdf is non-finite or negative";
      return r;
    }
    r.total += m;
  }
  if (!(r.total > 0)) {
    r.ok = false;
    r.reason = "the pdf integrates to 0";
    return r;
  }
  const double limit = r.total / (16.0 * double(max_rings));
  // Each cell refined on its own, results kept by cell index and concatenated in order.
  std::vector<std::vector<std::pair<double, double>>> parts(cells);  // (upper t, mass)
  tbb::parallel_for(std::size_t(0), cells, [&](std::size_t j) {
    auto split = [&](auto&& self, double ta, double tb, double m, int depth) -> void {
      if (m <= limit || depth >= 40 || tb - ta <= 1e-12 * pm.t_max) {
        parts[j].push_back({tb, m});
        return;
      }
      const double mid = 0.5 * (ta + tb);
      const double ml = ring(ta, mid), mr = ring(mid, tb);
      self(self, ta, mid, std::isfinite(ml) ? ml : 0.0, depth + 1);
      self(self, mid, tb, std::isfinite(mr) ? mr : 0.0, depth + 1);
    };
    split(split, nodes[j], nodes[j + 1], coarse[j], 0);
  });
  r.t.push_back(0.0);
  for (const auto& p : parts)
    for (const auto& [t, m] : p) {
      r.t.push_back(t);
      r.mass.push_back(m);
    }
  r.total = 0;
  for (double m : r.mass) r.total += m;
  return r;
}

BinGrid equal_probability_grid(const PolarMap& pm, const RingMass& rm, std::size_t bins, double aspect) {
  const std::size_t rings = ring_count(bins, aspect), sectors = sector_count(bins, rings);
  const std::size_t cells = rm.mass.size();
  std::vector<double> cum(cells + 1, 0.0);
  for (std::size_t j = 0; j < cells; ++j) cum[j + 1] = cum[j] + rm.mass[j];
  std::size_t j0 = 0, j1 = cells - 1;
  while (j0 < cells && rm.mass[j0] == 0) ++j0;
  while (j1 > j0 && rm.mass[j1] == 0) --j1;
  const double t_lo = rm.t[j0], t_hi = rm.t[j1 + 1];
  std::vector<double> inner{t_lo};
  for (std::size_t i = 1; i < rings; ++i) {
    const double target = cum[cells] * double(i) / double(rings);
    std::size_t j = static_cast<std::size_t>(std::lower_bound(cum.begin() + 1, cum.end(), target) - (cum.begin() + 1));
    j = std::min(j, cells - 1);
    const double ua = pm.u_of_t(rm.t[j]), ub = pm.u_of_t(rm.t[j + 1]);
    const double frac = rm.mass[j] > 0 ? std::clamp((target - cum[j]) / rm.mass[j], 0.0, 1.0) : 0.0;
    const double t = std::clamp(pm.t_of_u(ua + frac * (ub - ua)), rm.t[j], rm.t[j + 1]);
    if (t > inner.back() && t < t_hi) inner.push_back(t);
  }
  inner.push_back(t_hi);
  std::vector<double> edges;
  std::vector<std::size_t> secs;
  if (t_lo > 0) {  // zero-mass cap around the lobe: one bin
    edges.push_back(0.0);
    secs.push_back(1);
  }
  for (std::size_t i = 0; i + 1 < inner.size(); ++i) {
    edges.push_back(inner[i]);
    secs.push_back(sectors);
  }
  edges.push_back(t_hi);
  if (t_hi < pm.t_max) {  // zero-mass remainder: one bin
    edges.push_back(pm.t_max);
    secs.push_back(1);
  }
  return make_grid(std::move(edges), std::move(secs));
}

void compute_expectations(const PolarMap& pm, const CubatureSetup& cs, BinGrid& g) {
  const std::size_t bins = g.bins();
  g.expected.assign(bins, 0.0);
  g.error.assign(bins, 0.0);
  std::vector<std::size_t> ring_of(bins);
  for (std::size_t i = 0; i < g.rings(); ++i)
    for (std::size_t b = g.offset[i]; b < g.offset[i + 1]; ++b) ring_of[b] = i;
  tbb::parallel_for(std::size_t(0), bins, [&](std::size_t b) {
    const std::size_t i = ring_of[b], j = b - g.offset[i];
    const double ns = double(g.sectors[i]);
    const double p0 = kTwoPi * double(j) / ns, p1 = kTwoPi * double(j + 1) / ns;
    const ValErr v = integrate_bin(pm, cs, pm.u_of_t(g.t_edges[i]), pm.u_of_t(g.t_edges[i + 1]), p0, p1);
    g.expected[b] = cs.n * v.value;
    g.error[b] = cs.n * v.error;
  });
  g.mass = g.mass_error = 0;
  for (std::size_t b = 0; b < bins; ++b) {
    g.mass += g.expected[b] / cs.n;
    g.mass_error += g.error[b] / cs.n;
  }
}

// Orthonormal frame with the given unit z axis (the branchless construction of Duff et al. 2017).
void orthonormal_frame(const Vec3<double>& z, Vec3<double>& x, Vec3<double>& y) {
  const double sign = std::copysign(1.0, z.z);
  const double a = -1.0 / (sign + z.z);
  const double b = z.x * z.y * a;
  x = {1 + sign * z.x * z.x * a, sign * b, -sign * z.x};
  y = {b, sign + z.y * z.y * a, -z.y};
}

// Geometric breaks around each point feature: half-widths kPointFeatureReach·2^−k (rad of arc),
// k = 1 … kPointFeatureLevels (the finest ≈ 1.2e-4 rad).
constexpr double kPointFeatureReach = 0.5;
constexpr int kPointFeatureLevels = 12;

ChiSquarePlan make_plan(SampleDomain domain, DirectionPdf dpdf, PointPdf ppdf, std::uint64_t n,
                        const ChiSquareOptions& o) {
  ChiSquarePlan plan;
  plan.domain = domain;
  plan.n = n;
  plan.options = o;
  if (plan.options.layout == BinLayout::kAuto)
    plan.options.layout = domain == SampleDomain::kDisk ? BinLayout::kEqualArea : BinLayout::kEqualProbability;
  plan.direction_pdf = std::move(dpdf);
  plan.point_pdf = std::move(ppdf);
  PolarMap pm;
  pm.domain = domain;
  double aspect = kPi;
  if (domain == SampleDomain::kDisk) {
    plan.t_max = 0.5;
    aspect = 4 * kPi;
    pm.ppdf = &plan.point_pdf;
  } else {
    const double len = std::sqrt(o.lobe.x * o.lobe.x + o.lobe.y * o.lobe.y + o.lobe.z * o.lobe.z);
    if (!(len > 0) || !std::isfinite(len)) {
      plan.inconclusive = true;
      plan.reason = "the lobe direction is not a finite non-zero vector";
      return plan;
    }
    const Vec3<double> l = (1.0 / len) * o.lobe;
    if (l.x == 0 && l.y == 0 && l.z == 1) {
      plan.frame_x = {1, 0, 0};
      plan.frame_y = {0, 1, 0};
      plan.frame_z = {0, 0, 1};
    } else {
      plan.frame_z = l;
      orthonormal_frame(l, plan.frame_x, plan.frame_y);
    }
    plan.tilted_hemisphere = domain == SampleDomain::kHemisphere && !(l.x == 0 && l.y == 0 && l.z == 1);
    plan.t_max = domain == SampleDomain::kHemisphere && !plan.tilted_hemisphere ? 0.5 * kPi : kPi;
    aspect = plan.t_max < kPi ? 2 * kPi : kPi;
    pm.fx = plan.frame_x;
    pm.fy = plan.frame_y;
    pm.fz = plan.frame_z;
    pm.tilted = plan.tilted_hemisphere;
    pm.up = {plan.frame_x.z, plan.frame_y.z, plan.frame_z.z};
    pm.dpdf = &plan.direction_pdf;
    if (plan.options.direction_pdf_rows) pm.dpdf_rows = &plan.options.direction_pdf_rows;
  }
  pm.t_max = plan.t_max;
  if (n == 0) {
    plan.inconclusive = true;
    plan.reason = "no samples";
    return plan;
  }

  CubatureSetup cs;
  cs.n = double(n);
  cs.options = &plan.options;
  for (int k = 1; k <= 24; ++k) cs.u_breaks.push_back(pm.u_of_t(std::ldexp(plan.t_max, -k)));
  for (double b : o.radial_breaks)
    if (b > 0 && b < plan.t_max) cs.u_breaks.push_back(pm.u_of_t(b));
  for (const Vec3<double>& f : o.point_features) {
    if (pm.disk()) break;
    double t = 0, phi = 0;
    plan.to_bin_coordinates(f, t, phi);
    if (!(t > 0 && t < plan.t_max)) continue;
    cs.u_breaks.push_back(pm.u_of_t(t));
    const bool azimuth = phi > 0 && phi < kTwoPi;
    if (azimuth) cs.phi_breaks.push_back(phi);
    // Breaks closing in on the feature geometrically in θ' and φ' (≈ equal arc lengths): pieces
    // shrink towards it, as polar coordinates about it would. Measured need: at a Heaviside
    // cap edge that excises a small region around −ωi with a large density just outside (Eto &
    // Tokuyoshi's bounded caps, α = (0.1, 1), θi = 45°), a corner alone lost 1.1e-5 of the mass
    // with an error estimate of 1.5e-8; with these breaks the mass is 1 ± 1.3e-8.
    for (int k = 1; k <= kPointFeatureLevels; ++k) {
      const double d = kPointFeatureReach * std::ldexp(1.0, -k);
      for (double tb : {t - d, t + d})
        if (tb > 0 && tb < plan.t_max) cs.u_breaks.push_back(pm.u_of_t(tb));
      if (!azimuth) continue;
      const double dphi = d / std::max(std::sin(t), 1e-3);
      for (double pb : {phi - dphi, phi + dphi})
        if (pb > 0 && pb < kTwoPi) cs.phi_breaks.push_back(pb);
    }
  }
  if (!pm.disk() && plan.t_max > 0.5 * kPi) cs.u_breaks.push_back(1.0);
  std::sort(cs.u_breaks.begin(), cs.u_breaks.end());
  cs.u_breaks.erase(std::unique(cs.u_breaks.begin(), cs.u_breaks.end()), cs.u_breaks.end());
  for (double b : o.phi_breaks)
    if (b > 0 && b < kTwoPi) cs.phi_breaks.push_back(b);
  std::sort(cs.phi_breaks.begin(), cs.phi_breaks.end());

  std::vector<std::size_t> counts{std::max<std::size_t>(1, o.coarse_bins)};
  const double fine = std::min(double(o.fine_max_bins), std::floor(double(n) / o.fine_expected_per_bin));
  if (fine > double(counts[0])) counts.push_back(static_cast<std::size_t>(fine));

  RingMass rm;
  const BinLayout layout = plan.options.layout;
  if (layout == BinLayout::kEqualProbability) {
    // The ring masses only place the ring edges (the bins' expectations are integrated afresh), so
    // they are integrated to a looser tolerance.
    ChiSquareOptions loose = plan.options;
    loose.rel_tol = std::max(loose.rel_tol, 1e-5);
    loose.abs_tol_counts = std::max(loose.abs_tol_counts, 1e-2);
    loose.max_subdivisions = std::min(loose.max_subdivisions, 50u);
    CubatureSetup layout_cs = cs;
    layout_cs.options = &loose;
    rm = ring_mass(pm, layout_cs, ring_count(counts.back(), aspect));
    if (!rm.ok) {
      plan.inconclusive = true;
      plan.reason = rm.reason;
      return plan;
    }
  }
  for (std::size_t bins : counts) {
    BinGrid g = layout == BinLayout::kEqualArea ? equal_area_grid(pm, bins, aspect)
                                                  : equal_probability_grid(pm, rm, bins, aspect);
    compute_expectations(pm, cs, g);
    plan.grids.push_back(std::move(g));
  }
  for (const BinGrid& g : plan.grids)
    for (std::size_t b = 0; b < g.bins(); ++b)
      if (!std::isfinite(g.expected[b]) || !std::isfinite(g.error[b]) || g.expected[b] < 0) {
        plan.inconclusive = true;
        plan.reason = "the pdf is non-finite or negative over a bin";
        return plan;
      }
  if (!(plan.grids[0].mass > 0)) {
    plan.inconclusive = true;
    plan.reason = "the pdf integrates to 0";
  }
  return plan;
}

// ---- Running a plan -------------------------------------------------------------------------------

struct Tally {
  std::vector<std::vector<std::int64_t>> counts;  // per grid, per bin
  std::uint64_t no_sample = 0, malformed = 0, outside = 0, zero_pdf = 0, missed = 0;
  std::uint64_t first_no_sample = kNone, first_malformed = kNone, first_outside = kNone,
                first_zero_pdf = kNone, first_missed = kNone;

  explicit Tally(const ChiSquarePlan& plan) {
    for (const BinGrid& g : plan.grids) counts.emplace_back(g.bins(), 0);
  }
  void merge(const Tally& o) {
    for (std::size_t g = 0; g < counts.size(); ++g)
      for (std::size_t b = 0; b < counts[g].size(); ++b) counts[g][b] += o.counts[g][b];
    no_sample += o.no_sample;
    malformed += o.malformed;
    outside += o.outside;
    zero_pdf += o.zero_pdf;
    missed += o.missed;
    first_no_sample = std::min(first_no_sample, o.first_no_sample);
    first_malformed = std::min(first_malformed, o.first_malformed);
    first_outside = std::min(first_outside, o.first_outside);
    first_zero_pdf = std::min(first_zero_pdf, o.first_zero_pdf);
    first_missed = std::min(first_missed, o.first_missed);
  }
};

enum class Kind { kBinned, kNoSample, kMalformed, kOutside };

// Generate and bin every sample. `classify(i, t, phi)` returns the kind of sample i and, for a
// binned one, its bin coordinates; `classify.pdf(i)` is the pdf at sample i (asked only for
// samples in zero-expectation bins).
template <class Classify>
Tally tally_samples(const ChiSquarePlan& plan, Classify&& classify) {
  const std::uint64_t chunk = std::max<std::uint64_t>(1, plan.options.chunk);
  const std::uint64_t chunks = (plan.n + chunk - 1) / chunk;
  tbb::combinable<Tally> local([&] { return Tally(plan); });
  tbb::parallel_for(tbb::blocked_range<std::uint64_t>(0, chunks, 1), [&](const tbb::blocked_range<std::uint64_t>& r) {
    Tally& t = local.local();
    for (std::uint64_t c = r.begin(); c != r.end(); ++c) {
      const std::uint64_t end = std::min(plan.n, (c + 1) * chunk);
      // The chunk's view of the samples (a batched sampler draws the whole chunk here).
      decltype(auto) samples = classify.begin_chunk(c * chunk, end);
      for (std::uint64_t i = c * chunk; i < end; ++i) {
        double tc = 0, phi = 0;
        const Kind k = samples(i, tc, phi);
        switch (k) {
          case Kind::kNoSample:
            ++t.no_sample;
            t.first_no_sample = std::min(t.first_no_sample, i);
            continue;
          case Kind::kMalformed:
            ++t.malformed;
            t.first_malformed = std::min(t.first_malformed, i);
            continue;
          case Kind::kOutside:
            ++t.outside;
            t.first_outside = std::min(t.first_outside, i);
            continue;
          case Kind::kBinned:
            break;
        }
        bool zero_bin = false;
        for (std::size_t g = 0; g < plan.grids.size(); ++g) {
          const std::size_t b = plan.grids[g].bin_of(tc, phi);
          ++t.counts[g][b];
          zero_bin = zero_bin || plan.grids[g].expected[b] == 0;
        }
        if (zero_bin) {
          const double p = samples.pdf(i);
          if (p > 0) {
            ++t.missed;
            t.first_missed = std::min(t.first_missed, i);
          } else {
            ++t.zero_pdf;
            t.first_zero_pdf = std::min(t.first_zero_pdf, i);
          }
        }
      }
    }
  });
  Tally total(plan);
  local.combine_each([&](const Tally& t) { total.merge(t); });  // integer sums and minima
  return total;
}

// Whether the pdf integrates to (at least) 1 within the cubature error: then "no sample" results
// have expectation 0.
bool full_mass(const BinGrid& g) { return 1.0 - g.mass <= 10 * g.mass_error + 1e-12; }

ChiSquareResolution evaluate(const ChiSquarePlan& plan, const BinGrid& g,
                             const std::vector<std::int64_t>& counts, std::uint64_t no_samples,
                             std::size_t resolutions) {
  const ChiSquareOptions& o = plan.options;
  const double n = double(plan.n);
  ChiSquareResolution r;
  r.bins = g.bins();
  r.mass = g.mass;
  r.mass_error = g.mass_error;
  std::vector<double> expected(g.expected), error(g.error);
  std::vector<std::int64_t> observed(counts);
  // The "no sample" cell, last in the pooling order; none where the pdf integrates to 1 within
  // its cubature error.
  expected.push_back(full_mass(g) ? 0.0 : n * (1.0 - g.mass));
  error.push_back(expected.back() > 0 ? n * g.mass_error : 0.0);
  observed.push_back(static_cast<std::int64_t>(no_samples));

  const Pooling pool = pool_bins(expected, o.min_expected);
  std::vector<double> ce(pool.cells, 0.0), cerr(pool.cells, 0.0);
  std::vector<std::int64_t> co(pool.cells, 0);
  for (std::size_t b = 0; b < expected.size(); ++b) {
    const std::size_t c = pool.group[b];
    if (c == kZeroExpectationBin) continue;
    ce[c] += expected[b];
    cerr[c] += error[b];
    co[c] += observed[b];
  }
  r.cells = pool.cells;
  double q = 0, rel = 0;
  for (std::size_t c = 0; c < pool.cells; ++c) {
    const double d = double(co[c]) - ce[c];
    r.statistic += d * d / ce[c];
    q += cerr[c] * cerr[c] / ce[c];
    rel += cerr[c] / ce[c];
    r.max_error_ratio = std::max(r.max_error_ratio, cerr[c] / std::sqrt(ce[c]));
  }
  r.dof = double(pool.cells) - 1;
  r.error_shift = q + 2 * std::sqrt(q) + rel;
  const double level = sidak_level(o.level, resolutions);
  if (plan.inconclusive) {
    r.inconclusive = true;
    r.reason = plan.reason;
    r.p_value = kNaN;
    return r;
  }
  if (pool.cells < 2) {
    r.inconclusive = true;
    r.reason = "fewer than two cells after pooling";
    r.p_value = kNaN;
    return r;
  }
  r.p_value = boost::math::cdf(boost::math::complement(boost::math::chi_squared_distribution<double>(r.dof), r.statistic));
  if (!(r.error_shift <= o.inconclusive_shift * std::sqrt(2 * r.dof))) {
    r.inconclusive = true;
    std::ostringstream s;
    s << "quadrature error could shift X² by " << r.error_shift << " > " << o.inconclusive_shift
      << "·√(2·dof) = " << o.inconclusive_shift * std::sqrt(2 * r.dof)
      << " (max N·err/√E " << r.max_error_ratio << ")";
    r.reason = s.str();
  }
  r.min_noncentrality = min_detectable_noncentrality(r.dof, level, o.power);
  r.detectable_global = std::sqrt(r.min_noncentrality / n);
  r.detectable_one_cell = std::sqrt(r.min_noncentrality * double(r.cells) / n);
  return r;
}

template <class Classify>
ChiSquareResult run_plan(const ChiSquarePlan& plan, Classify&& classify) {
  ChiSquareResult res;
  res.n = plan.n;
  if (plan.grids.empty()) {
    res.inconclusive = true;
    res.reason = plan.reason.empty() ? "no bins" : plan.reason;
    res.p_value = kNaN;
    return res;
  }
  const Tally t = tally_samples(plan, classify);
  res.no_samples = t.no_sample;
  res.mass = plan.grids[0].mass;
  res.mass_error = plan.grids[0].mass_error;
  for (std::size_t g = 0; g < plan.grids.size(); ++g) {
    res.resolutions.push_back(evaluate(plan, plan.grids[g], t.counts[g], t.no_sample, plan.grids.size()));
    res.raw_p_values.push_back(res.resolutions.back().p_value);
    res.max_error_ratio = std::max(res.max_error_ratio, res.resolutions.back().max_error_ratio);
  }
  res.p_value = sidak_min(res.raw_p_values);
  std::string reasons;
  for (std::size_t g = 0; g < res.resolutions.size(); ++g)
    if (res.resolutions[g].inconclusive) {
      res.inconclusive = true;
      reasons += (reasons.empty() ? "" : "; ") + std::string(g == 0 ? "coarse: " : "fine: ") + res.resolutions[g].reason;
    }
  if (t.missed > 0) {
    res.inconclusive = true;
    std::ostringstream s;
    s << t.missed << " samples (first #" << t.first_missed
      << ") landed in bins whose cubature gave 0 where the pdf is positive";
    reasons += (reasons.empty() ? "" : "; ") + s.str();
  }
  res.reason = reasons;
  // Hard failures, most specific first.
  std::ostringstream hf;
  std::uint64_t first = kNone;
  auto fail = [&](std::uint64_t count, std::uint64_t at, const char* what) {
    if (count == 0) return;
    hf << (first == kNone ? "" : "; ") << count << " " << what << " (first #" << at << ")";
    first = std::min(first, at);
  };
  fail(t.malformed, t.first_malformed, "malformed samples");
  fail(t.outside, t.first_outside, "samples outside the domain");
  fail(t.zero_pdf, t.first_zero_pdf, "samples where the pdf is 0 over the whole bin");
  if (full_mass(plan.grids[0])) fail(t.no_sample, t.first_no_sample, "'no sample' results while the pdf integrates to ≥ 1");
  if (first != kNone) {
    res.hard_fail = true;
    res.hard_fail_reason = hf.str();
    res.first_bad_sample = first;
    res.p_value = 0;
  }
  return res;
}

}  // namespace

// ---- Public: pooling, Pearson, power ------------------------------------------------------------

Pooling pool_bins(std::span<const double> expected, double min_expected) {
  Pooling p;
  p.group.assign(expected.size(), kZeroExpectationBin);
  std::size_t g = 0;
  double acc = 0;
  bool open = false;
  for (std::size_t b = 0; b < expected.size(); ++b) {
    if (expected[b] == 0) continue;
    p.group[b] = g;
    acc += expected[b];
    open = true;
    if (acc >= min_expected) {
      ++g;
      acc = 0;
      open = false;
    }
  }
  if (open && g > 0) {
    for (std::size_t& x : p.group)
      if (x == g) x = g - 1;
  } else if (open) {
    ++g;  // a single short cell
  }
  p.cells = g;
  return p;
}

PearsonResult pearson_chi_square(std::span<const std::int64_t> observed,
                                 std::span<const double> expected, double min_expected,
                                 double constraints) {
  PearsonResult r;
  const Pooling pool = pool_bins(expected, min_expected);
  std::vector<double> ce(pool.cells, 0.0);
  std::vector<std::int64_t> co(pool.cells, 0);
  for (std::size_t b = 0; b < expected.size(); ++b) {
    const std::int64_t o = b < observed.size() ? observed[b] : 0;
    if (pool.group[b] == kZeroExpectationBin) {
      r.observations_in_zero_bins += static_cast<std::uint64_t>(std::max<std::int64_t>(0, o));
      continue;
    }
    ce[pool.group[b]] += expected[b];
    co[pool.group[b]] += o;
  }
  r.cells = pool.cells;
  for (std::size_t c = 0; c < pool.cells; ++c) {
    const double d = double(co[c]) - ce[c];
    r.statistic += d * d / ce[c];
  }
  r.dof = double(pool.cells) - constraints;
  if (r.observations_in_zero_bins > 0) {
    r.hard_fail = true;
    r.p_value = 0;
  } else if (r.dof <= 0 || !std::isfinite(r.statistic)) {
    r.p_value = kNaN;
  } else {
    r.p_value = boost::math::cdf(boost::math::complement(boost::math::chi_squared_distribution<double>(r.dof), r.statistic));
  }
  return r;
}

double min_detectable_noncentrality(double dof, double level, double power) {
  if (!(dof > 0) || !(level > 0 && level < 1) || !(power > 0 && power < 1)) return kNaN;
  if (power <= level) return 0.0;
  const double crit = boost::math::quantile(boost::math::complement(boost::math::chi_squared_distribution<double>(dof), level));
  // λ with P(χ'² ≤ crit) = 1 − power.
  return boost::math::non_central_chi_squared_distribution<double>::find_non_centrality(dof, crit, 1 - power);
}

double min_detectable_relative_error(double n, double dof, double level, double mass_fraction,
                                     double power) {
  return std::sqrt(min_detectable_noncentrality(dof, level, power) / (n * mass_fraction));
}

// ---- Public: bins, plans, runs --------------------------------------------------------------------

std::size_t BinGrid::bin_of(double t, double phi) const {
  const std::size_t rings_n = rings();
  const auto it = std::upper_bound(t_edges.begin() + 1, t_edges.begin() + std::ptrdiff_t(rings_n), t);
  const std::size_t i = static_cast<std::size_t>(it - (t_edges.begin() + 1));
  const double ns = double(sectors[i]);
  double s = std::floor(phi / kTwoPi * ns);
  s = std::clamp(s, 0.0, ns - 1);
  return offset[i] + static_cast<std::size_t>(s);
}

void ChiSquarePlan::to_bin_coordinates(const Vec3<double>& w, double& t, double& phi) const {
  const double x = w.x * frame_x.x + w.y * frame_x.y + w.z * frame_x.z;
  const double y = w.x * frame_y.x + w.y * frame_y.y + w.z * frame_y.z;
  const double z = w.x * frame_z.x + w.y * frame_z.y + w.z * frame_z.z;
  t = std::min(std::atan2(std::hypot(x, y), z), t_max);
  phi = std::atan2(y, x);
  if (phi < 0) phi += kTwoPi;
}

ChiSquarePlan plan_direction_chi_square(SampleDomain domain, DirectionPdf pdf, std::uint64_t n,
                                        const ChiSquareOptions& options) {
  if (domain == SampleDomain::kDisk) {
    ChiSquarePlan p;
    p.domain = domain;
    p.inconclusive = true;
    p.reason = "plan_direction_chi_square needs the sphere or the hemisphere";
    return p;
  }
  return make_plan(domain, std::move(pdf), {}, n, options);
}

ChiSquarePlan plan_disk_chi_square(PointPdf pdf, std::uint64_t n, const ChiSquareOptions& options) {
  return make_plan(SampleDomain::kDisk, {}, std::move(pdf), n, options);
}

// The kind of direction w and, for a binned one, its bin coordinates.
static Kind classify_direction(const ChiSquarePlan& plan, const Vec3<double>& w, double& t,
                               double& phi) {
  if (w.x == 0 && w.y == 0 && w.z == 0) return Kind::kNoSample;
  const double l2 = w.x * w.x + w.y * w.y + w.z * w.z;
  if (!std::isfinite(l2) || std::abs(l2 - 1) > 2e-5) return Kind::kMalformed;
  if (plan.domain == SampleDomain::kHemisphere && w.z < -1e-12) return Kind::kOutside;
  plan.to_bin_coordinates(w, t, phi);
  return Kind::kBinned;
}

ChiSquareResult run_direction_chi_square(const ChiSquarePlan& plan, const DirectionSampler& sample) {
  struct Classify {
    const ChiSquarePlan& plan;
    const DirectionSampler& sample;
    const Classify& begin_chunk(std::uint64_t, std::uint64_t) const { return *this; }
    Kind operator()(std::uint64_t i, double& t, double& phi) const {
      return classify_direction(plan, sample(i), t, phi);
    }
    double pdf(std::uint64_t i) const {
      const Vec3<double> w = sample(i);
      return plan.direction_pdf(w);
    }
  };
  return run_plan(plan, Classify{plan, sample});
}

ChiSquareResult run_direction_chi_square(const ChiSquarePlan& plan,
                                         const DirectionBatchSampler& sample) {
  // One chunk's samples, drawn at once.
  struct Chunk {
    const ChiSquarePlan& plan;
    std::uint64_t begin;
    std::vector<Vec3<double>> w;
    Kind operator()(std::uint64_t i, double& t, double& phi) const {
      return classify_direction(plan, w[i - begin], t, phi);
    }
    double pdf(std::uint64_t i) const { return plan.direction_pdf(w[i - begin]); }
  };
  struct Classify {
    const ChiSquarePlan& plan;
    const DirectionBatchSampler& sample;
    Chunk begin_chunk(std::uint64_t begin, std::uint64_t end) const {
      Chunk c{plan, begin, std::vector<Vec3<double>>(end - begin)};
      sample(begin, end - begin, c.w.data());
      return c;
    }
  };
  return run_plan(plan, Classify{plan, sample});
}

ChiSquareResult run_disk_chi_square(const ChiSquarePlan& plan, const PointSampler& sample) {
  struct Classify {
    const ChiSquarePlan& plan;
    const PointSampler& sample;
    const Classify& begin_chunk(std::uint64_t, std::uint64_t) const { return *this; }
    Kind operator()(std::uint64_t i, double& t, double& phi) const {
      const Vec2<double> p = sample(i);
      if (std::isnan(p.x) || std::isnan(p.y)) return Kind::kNoSample;
      if (!std::isfinite(p.x) || !std::isfinite(p.y)) return Kind::kMalformed;
      const double dx = p.x - 0.5, dy = p.y - 0.5;
      const double r = std::hypot(dx, dy);
      if (r > 0.5 * (1 + 1e-12)) return Kind::kOutside;
      t = std::min(r, 0.5);
      phi = std::atan2(dy, dx);
      if (phi < 0) phi += kTwoPi;
      return Kind::kBinned;
    }
    double pdf(std::uint64_t i) const { return plan.point_pdf(sample(i)); }
  };
  return run_plan(plan, Classify{plan, sample});
}

ChiSquareResult chi_square_sphere(const DirectionSampler& sample, std::uint64_t n,
                                  const DirectionPdf& pdf, const ChiSquareOptions& options) {
  return run_direction_chi_square(plan_direction_chi_square(SampleDomain::kSphere, pdf, n, options), sample);
}

ChiSquareResult chi_square_hemisphere(const DirectionSampler& sample, std::uint64_t n,
                                      const DirectionPdf& pdf, const ChiSquareOptions& options) {
  return run_direction_chi_square(plan_direction_chi_square(SampleDomain::kHemisphere, pdf, n, options), sample);
}

ChiSquareResult chi_square_disk(const PointSampler& sample, std::uint64_t n, const PointPdf& pdf,
                                const ChiSquareOptions& options) {
  return run_disk_chi_square(plan_disk_chi_square(pdf, n, options), sample);
}

std::string ChiSquareResult::summary() const {
  std::ostringstream s;
  s.precision(4);
  if (hard_fail) s << "HARD FAIL: " << hard_fail_reason << "; ";
  if (inconclusive) s << "INCONCLUSIVE: " << reason << "; ";
  s << "N=" << n;
  for (std::size_t g = 0; g < resolutions.size(); ++g) {
    const ChiSquareResolution& r = resolutions[g];
    s << (g == 0 ? "; coarse" : "; fine") << " X²=" << r.statistic << " dof=" << r.dof << " p=" << r.p_value
      << " (" << r.cells << " cells of " << r.bins << " bins, δ90%=" << r.detectable_global << ")";
  }
  s << "; combined p=" << p_value << "; mass=" << mass << "±" << mass_error
    << "; max N·err/√E=" << max_error_ratio;
  if (no_samples) s << "; no-sample=" << no_samples;
  return s.str();
}

}  // namespace glintlab::verify
