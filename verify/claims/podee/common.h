// What podee.rmse and podee.far-failure share: the images they compare at one camera distance,
// and the MSE estimates against the pixel integral from two independent references. The scene
// itself is verify/scenes/podee_scene.h.
#pragma once

#include <string_view>
#include <vector>

namespace glintlab::verify::podee_claims {

inline constexpr std::string_view kPaper = "Podee, Max, Iwasaki & Dobashi";
inline constexpr int kPaperSpp = 64;  // Sec. 4: "tiling 64x supersampling"
// The controls' near-truth image: an independent 64-spp reference × 1.03.
inline constexpr double kNearTruthBias = 0.03;

// Luminance per pixel of every image at one distance: the two references R1, R2 (`spp` samples
// each), the near-truth image, and the three methods.
struct RmsePixels {
  double distance = 0;
  std::vector<double> r1, r2, near_truth, centre, lean, method;
};
RmsePixels rmse_pixels(double distance, int size, int spp);

// MSE(a) − MSE(b) against the pixel integral: per pixel (A − R1)(A − R2) is an unbiased estimate
// of (A − truth)², so D = mean (A − B)(A + B − R1 − R2), whose only noise is the references'
// (estimated per pixel by (R1 − R2)²): SE(D) = √(Σ (A − B)² (R1 − R2)²) / n; p two-sided.
struct Ordering {
  double d_mse = 0, se = 0, p = 1;
  int sign = 0;  // −1 method lower, +1 method higher, 0 tie (after Holm–Šidák)
};
Ordering order(const std::vector<double>& a, const std::vector<double>& b, const RmsePixels& px);
// The unbiased estimate of MSE(a) against the pixel integral.
double mse_vs_truth(const std::vector<double>& a, const RmsePixels& px);

}  // namespace glintlab::verify::podee_claims
