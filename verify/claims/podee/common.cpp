// The images podee.rmse and podee.far-failure compare, and the MSE estimates (common.h).
#include "verify/claims/podee/common.h"

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "verify/check.h"
#include "verify/scenes/podee_scene.h"

namespace glintlab::verify::podee_claims {

RmsePixels rmse_pixels(double distance, int size, int spp) {
  const podee::Scene scene(podee::config(distance, size), podee::normal_map());
  const std::string id = fmt::format("podee.rmse/references/d={}/n={}", distance, size);
  const auto lum = [](const Image& im) {
    const std::size_t c = im.channel("Y");
    std::vector<double> v;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x) v.push_back(im.at(x, y, c));
    return v;
  };
  RmsePixels p;
  p.distance = distance;
  p.r1 = lum(podee::render_podee_reference(scene, spp, check_seed(id, 0), 0));
  p.r2 = lum(podee::render_podee_reference(scene, spp, check_seed(id, 1), 0));
  p.near_truth = lum(podee::render_podee_reference(scene, kPaperSpp, check_seed(id, 2), 0));
  for (double& v : p.near_truth) v *= 1 + kNearTruthBias;
  p.centre = lum(podee::render_podee(scene, podee::Method::kCentre, 0));
  p.lean = lum(podee::render_podee(scene, podee::Method::kLean, 0));
  p.method = lum(podee::render_podee(scene, podee::Method::kPodee, 0));
  return p;
}

Ordering order(const std::vector<double>& a, const std::vector<double>& b, const RmsePixels& px) {
  double d = 0, v = 0;
  const std::size_t n = a.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double ab = a[i] - b[i], rr = px.r1[i] - px.r2[i];
    d += ab * (a[i] + b[i] - px.r1[i] - px.r2[i]);
    v += ab * ab * rr * rr;
  }
  Ordering o;
  o.d_mse = d / double(n);
  o.se = std::sqrt(v) / double(n);
  o.p = o.se > 0 ? std::erfc(std::abs(o.d_mse) / o.se / std::sqrt(2.0)) : (o.d_mse == 0 ? 1 : 0);
  return o;
}

double mse_vs_truth(const std::vector<double>& a, const RmsePixels& px) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += (a[i] - px.r1[i]) * (a[i] - px.r2[i]);
  return s / double(a.size());
}

}  // namespace glintlab::verify::podee_claims
