#pragma once
// The membrane in compression: the Green strain's compressive principal
// values scaled down before the material sees them (the stretching plugin's
// `compressive_stiffness`, docs/materials.md, "Folds at the scale of knit").
//
// A knit resists stretching but hardly resists compression: its yarns and the
// sheet itself buckle at scales far below a drape's triangles (ArcSim's knit
// bends so easily that its bending length under its own weight is 1.0-1.7 cm,
// the default shirt's triangle height). ArcSim's measured tables are tensile
// tests; ArcSim applies their zero-strain row to compression as well, so a
// compressed triangle pushes back as hard as a stretched one, and a mesh whose
// triangles cannot shrink must shorten by folding at its own scale: the
// one-triangle crinkles of issue 54. With this map a compressed face shortens
// at a fraction s of ArcSim's stiffness (standing for wrinkles narrower than
// the mesh can show), and tension is ArcSim's exactly.
//
// With G's eigenvalues l (principal Green strains) and eigenvectors v,
// G~ = sum f(l) v v^T, f(l) = l for l >= 0, f(l) = c l - (1 - c) delta / 2 for
// l <= -delta (c = sqrt(s): the energy, quadratic in G~, then has s times
// ArcSim's stiffness), and between them a C2 blend: f' = c + (1 - c) S(t),
// S(t) = 3 t^2 - 2 t^3, t = (l + delta) / delta. In the strain's components,
// with m = (l+ + l-) / 2 and r = (l+ - l-) / 2:
//   G~ = p (G - m I) + q I,  p = (f(m + r) - f(m - r)) / (2 r),  q = (f(m + r) + f(m - r)) / 2,
// smooth in G (a divided difference of a C2 function); below r = kIsotropic
// p and q are their Taylor series in r^2 (p = f'(m) + f'''(m) r^2 / 6,
// q = f(m) + f''(m) r^2 / 2), which avoids the square root's singular
// derivatives at r = 0. A face whose strain has no compressive value
// (l- >= 0) is left exactly as it was.
#include <drape/dual.hpp>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <type_traits>

namespace drape::membrane {

class CompressionMap {
 public:
  // Width of the blend in principal Green strain (0.2 %).
  static constexpr double kBlend = 2e-3;
  static constexpr double kIsotropic = 1e-8;

  // stiffness: the fraction s of ArcSim's stiffness left to compression, (0, 1].
  explicit CompressionMap(double stiffness = 1.0) : c_(std::sqrt(stiffness)) {}

  bool active() const { return c_ < 1.0; }

  // Whether the strain g = (G_uu, G_vv, G_uv) has a compressive principal value
  // (below which the map is not the identity).
  bool compressed(const Eigen::Vector3d& g) const {
    if (!active()) return false;
    const double m = 0.5 * (g[0] + g[1]), d = 0.5 * (g[0] - g[1]);
    return m - std::sqrt(d * d + g[2] * g[2]) < 0.0;
  }

  // G~ in components, over double or Dual<3> (value, gradient, Hessian).
  template <class T>
  std::array<T, 3> apply(const std::array<T, 3>& g) const {
    const T m = 0.5 * (g[0] + g[1]), d = 0.5 * (g[0] - g[1]);
    const T r2 = d * d + g[2] * g[2];
    T p, q;
    if (primal(r2) < kIsotropic * kIsotropic) {
      p = lift<T>(m, 1) + (f(primal(m), 3) / 6.0) * r2;
      q = lift<T>(m, 0) + (f(primal(m), 2) / 2.0) * r2;
    } else {
      using std::sqrt;
      const T r = sqrt(r2);
      const T hi = lift<T>(m + r, 0), lo = lift<T>(m - r, 0);
      p = (hi - lo) * inverse(2.0 * r);
      q = 0.5 * (hi + lo);
    }
    return {p * d + q, q - p * d, p * g[2]};
  }

  // f and its derivatives up to the third.
  double f(double x, int order) const {
    const double c = c_, delta = kBlend;
    if (x >= 0.0) return order == 0 ? x : order == 1 ? 1.0 : 0.0;
    if (x <= -delta) return order == 0 ? c * x - (1.0 - c) * delta / 2.0 : order == 1 ? c : 0.0;
    const double t = (x + delta) / delta;
    switch (order) {
      case 0: return c * x + (1.0 - c) * delta * (t * t * t - 0.5 * t * t * t * t - 0.5);
      case 1: return c + (1.0 - c) * t * t * (3.0 - 2.0 * t);
      case 2: return (1.0 - c) * 6.0 * t * (1.0 - t) / delta;
      default: return (1.0 - c) * (6.0 - 12.0 * t) / (delta * delta);
    }
  }

 private:
  // f^(order) of x as a T (the chain rule through x for a Dual).
  template <class T>
  T lift(const T& x, int order) const {
    const double v = primal(x);
    if constexpr (std::is_same_v<T, double>)
      return f(v, order);
    else
      return chain(x, f(v, order), f(v, order + 1), order + 2 <= 3 ? f(v, order + 2) : 0.0);
  }

  double c_;
};

}  // namespace drape::membrane
