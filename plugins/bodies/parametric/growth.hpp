#pragma once
// How a girth grows with the global adiposity `weight`, shared by both rigs
// (body_plan.cpp, human_plan.cpp).
#include <cmath>

namespace drape::parametric {

// The mean adiposity. The template, and the shipped model's assets, were built
// from the mean body, so it must stay bit-identical: the growth rates for heavy
// bodies apply only above it, and every body up to it keeps its first shape.
constexpr double kMeanWeight = 0.2;
// Adiposity above the mean, eased in over kEase (about BMI 25 to 31) so that a
// girth's growth rate changes without a kink; exactly 0 up to the mean.
constexpr double kEase = 0.2;
inline double heavy_excess(double w) {
  const double d = w - kMeanWeight;
  if (d <= 0) return 0;
  return d < kEase ? d * d / (2 * kEase) : d - 0.5 * kEase;
}

inline double lerp(double a, double b, double t) { return a + (b - a) * t; }

// A girth factor: exp(rate * w + girth) up to the mean adiposity, growing at
// `heavy_rate` above it (`excess` = heavy_excess(w)).
inline double growth(double rate, double heavy_rate, double girth, double w, double excess) {
  return std::exp(rate * w + (heavy_rate - rate) * excess + girth);
}

}  // namespace drape::parametric
