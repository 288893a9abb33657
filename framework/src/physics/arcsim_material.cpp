// ArcSim's data-driven stiffness (dde.cpp's evaluate_stretching_sample,
// stretching_stiffness and bending_stiffness, re-derived from their
// definitions) with the derivatives drape's Newton solver needs.
#include <drape/physics/arcsim_material.hpp>

#include <boost/math/quadrature/gauss.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace drape::arcsim {
namespace {

constexpr int kN = kGridSamples;

// Grid coordinate t of a strain component, clamped to [lo, hi]; `slope` is
// d(coordinate)/d(strain), 0 where clamped.
struct Coordinate {
  int cell;
  double frac, slope;
};

Coordinate axis_coordinate(double t, double slope, double lo, double hi) {
  if (!(t > lo)) {
    t = lo;
    slope = 0.0;
  } else if (t > hi) {
    t = hi;
    slope = 0.0;
  }
  const int cell = static_cast<int>(std::floor(t));
  return {cell, t - cell, slope};
}

// ArcSim clamps lookups just inside the last cell.
Coordinate arcsim_coordinate(double t) { return axis_coordinate(t, 0.0, 0.0, kN - 1 - 1e-5); }

// |G_uv| made C1 (kShearBand): c = m f(s / m) with m the band's width at
// G, and c's gradient and Hessian in G up to `order` (the rest left zero: an
// energy value in the line search needs c alone).
struct SmoothedShear {
  double value;
  Eigen::Vector3d d1;
  Eigen::Matrix3d d2;
};

SmoothedShear smoothed_shear(const Eigen::Vector3d& g, int order) {
  const double s = g[2], t = std::abs(s), sign = s < 0 ? -1.0 : 1.0;
  const double m = std::sqrt(kShearBand * kShearBand * (g[0] * g[0] + g[1] * g[1]) + kShearSmoothing * kShearSmoothing);
  SmoothedShear out{t, Eigen::Vector3d(0.0, 0.0, sign), Eigen::Matrix3d::Zero()};
  if (t >= m) return out;
  // f(x) = 2 x^2 - |x|^3 and its derivatives; c = m f(x), x = s / m.
  const double x = s / m, ax = t / m;
  const double f = 2.0 * x * x - ax * ax * ax;
  out.value = m * f;
  if (order < 1) return out;
  const double f1 = 4.0 * x - 3.0 * x * ax, c_s = f1, c_m = f - x * f1;
  // m's gradient in (G_uu, G_vv).
  const double b2 = kShearBand * kShearBand;
  const Eigen::Vector2d m1(b2 * g[0] / m, b2 * g[1] / m);
  out.d1 << c_m * m1, c_s;
  if (order < 2) return out;
  const double f2 = 4.0 - 6.0 * ax, c_ss = f2 / m, c_sm = -x * f2 / m, c_mm = x * x * f2 / m;
  const Eigen::Matrix2d m2 = b2 / m * Eigen::Matrix2d::Identity() - m1 * m1.transpose() / m;
  out.d2.topLeftCorner<2, 2>() = c_mm * m1 * m1.transpose() + c_m * m2;
  out.d2.block<2, 1>(0, 2) = out.d2.block<1, 2>(2, 0).transpose() = c_sm * m1;
  out.d2(2, 2) = c_ss;
  return out;
}

// drape's C1 lookup lets the coordinate run on past the grid, whose nodes
// continue its edge samples (StretchingTable::node), so the rounded hats join
// the last cell to the constant beyond smoothly. Clamping at the edge as
// ArcSim does left a kink there: the regular shirt on a BMI 60 body stretches
// armpit faces to G_uu = 0.75 and compresses them to G_vv = -0.36, past the
// grid's edges at 0.717 and -0.25. Two cells out every node is the edge
// sample, so the stiffness is constant and the slope zero.
Coordinate smooth_coordinate(double t) { return axis_coordinate(t, kN, -2.0, kN + 1.0); }

// q(g) = (g0^2, 2 g0 g1, g1^2, 2 g2^2): ArcSim's energy is k . q / 2, its
// shear term doubled as in the force its solver integrates.
Eigen::Vector4d strain_products(const Eigen::Vector3d& g) {
  return {g[0] * g[0], 2.0 * g[0] * g[1], g[1] * g[1], 2.0 * g[2] * g[2]};
}

}  // namespace

Eigen::Vector4d stretching_sample(const ArcsimData& data, double g_uu, double g_vv, double g_uv) {
  // The right Cauchy-Green tensor C = 2 G + I and its larger eigenpair.
  const double a = 2.0 * g_uu + 1.0, b = 2.0 * g_uv, d = 2.0 * g_vv + 1.0;
  const double largest = 0.5 * (a + d + std::sqrt(4.0 * b * b + (a - d) * (a - d)));
  Eigen::Vector2d direction;
  if (b != 0.0)
    direction = Eigen::Vector2d(largest - d, b);
  else
    direction = a >= d ? Eigen::Vector2d(1.0, 0.0) : Eigen::Vector2d(0.0, 1.0);
  // The direction's angle from u in units of 22.5 degrees, clamped to [0, 4).
  double angle = std::abs(std::atan2(direction.y(), direction.x()) / std::numbers::pi) * 8.0;
  angle = std::clamp(angle, 0.0, 4.0 - 1e-6);
  const int angle_id = static_cast<int>(angle);
  const double angle_weight = angle - angle_id;
  // The weight of the measured rows: 0 at rest, 1 at a principal stretch of 1 + 1/6.
  const double strain_weight = std::clamp((std::sqrt(largest) - 1.0) / kMeasuredStretch, 0.0, 1.0 - 1e-6);
  const Eigen::Vector4d& rest = data.stretching[0];
  const Eigen::Vector4d k = rest * (1.0 - strain_weight) * (1.0 - angle_weight) +
                            data.stretching[static_cast<std::size_t>(1 + angle_id)] * strain_weight * (1.0 - angle_weight) +
                            rest * (1.0 - strain_weight) * angle_weight +
                            data.stretching[static_cast<std::size_t>(2 + std::min(angle_id, 3))] * strain_weight * angle_weight;
  return 2.0 * k.cwiseMax(0.0);
}

StretchingTable::StretchingTable(const ArcsimData& data) {
  samples_.resize(static_cast<std::size_t>(kN) * kN * kN);
  for (int i = 0; i < kN; ++i)
    for (int j = 0; j < kN; ++j)
      for (int k = 0; k < kN; ++k)
        samples_[static_cast<std::size_t>((i * kN + j) * kN + k)] =
            stretching_sample(data, -0.25 + i / double(kN), -0.25 + j / double(kN), k / double(kN));
}

Eigen::Vector4d StretchingTable::stiffness(double g_uu, double g_vv, double g_uv) const {
  const Coordinate a = arcsim_coordinate((g_uu + 0.25) * kN), b = arcsim_coordinate((g_vv + 0.25) * kN),
                   c = arcsim_coordinate(std::abs(g_uv) * kN);
  Eigen::Vector4d k = Eigen::Vector4d::Zero();
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int l = 0; l < 2; ++l) {
        const double w = (i ? a.frac : 1.0 - a.frac) * (j ? b.frac : 1.0 - b.frac) * (l ? c.frac : 1.0 - c.frac);
        k += w * sample(a.cell + i, b.cell + j, c.cell + l);
      }
  return k;
}

namespace {

// The hat function of linear interpolation averaged over [x - e, x + e]
// (e = kCornerSmoothing): equal to max(0, 1 - |x|) except within e of its
// corners at 0 and +-1, where it is quadratic; C1, and the weights of all
// nodes still sum to 1. Value, first and second derivative.
struct Weight {
  double w, d1, d2;
};

Weight smoothed_hat(double x) {
  const double e = kCornerSmoothing, t = std::abs(x), sign = x < 0 ? -1.0 : 1.0;
  if (t <= e) return {1.0 - (t * t + e * e) / (2.0 * e), -x / e, -1.0 / e};
  if (t <= 1.0 - e) return {1.0 - t, -sign, 0.0};
  if (t < 1.0 + e) {
    const double r = 1.0 + e - t;
    return {r * r / (4.0 * e), -sign * r / (2.0 * e), 1.0 / (2.0 * e)};
  }
  return {0.0, 0.0, 0.0};
}

// The nodes whose rounded hats reach coordinate t (consecutive, from `first`):
// two away from the grid planes (weights 1 - f and f, no curvature), three
// within kCornerSmoothing of one.
struct AxisWeights {
  int first = 0;
  int count = 0;
  Weight weights[3];
};

AxisWeights axis_weights(double t) {
  AxisWeights out;
  const double cell = std::floor(t), f = t - cell;
  if (f >= kCornerSmoothing && f <= 1.0 - kCornerSmoothing) {
    // Away from the planes: the plain hats (smoothed_hat's middle branch).
    out.first = static_cast<int>(cell);
    out.count = 2;
    out.weights[0] = {1.0 - f, -1.0, 0.0};
    out.weights[1] = {f, 1.0, 0.0};
    return out;
  }
  const int base = static_cast<int>(cell) - 1;
  for (int k = 0; k < 4; ++k) {
    const Weight w = smoothed_hat(t - (base + k));
    if (w.w == 0.0 && w.d1 == 0.0 && w.d2 == 0.0) continue;
    if (out.count == 0) out.first = base + k;
    out.weights[out.count++] = w;
  }
  return out;
}

// The C1 lookup at strain g with its derivatives up to Order (0: k alone; 1:
// dk too; 2: d2k too), `node(i, j, k)` giving the extended grid's samples.
template <int Order, class Node>
StiffnessDerivatives smooth_lookup(const Eigen::Vector3d& g, const Node& node) {
  const SmoothedShear shear = smoothed_shear(g, Order);
  const Coordinate ca = smooth_coordinate((g[0] + 0.25) * kN), cb = smooth_coordinate((g[1] + 0.25) * kN),
                   cc = smooth_coordinate(shear.value * kN);
  const AxisWeights wa = axis_weights(ca.cell + ca.frac), wb = axis_weights(cb.cell + cb.frac),
                    wc = axis_weights(cc.cell + cc.frac);
  // Sums over the 8-27 nodes that reach g, in grid coordinates a, b, c.
  Eigen::Vector4d k = Eigen::Vector4d::Zero(), k_a = k, k_b = k, k_c = k, k_aa = k, k_bb = k, k_cc = k, k_ab = k,
                  k_ac = k, k_bc = k;
  for (int i = 0; i < wa.count; ++i)
    for (int j = 0; j < wb.count; ++j)
      for (int l = 0; l < wc.count; ++l) {
        const Weight &x = wa.weights[i], &y = wb.weights[j], &z = wc.weights[l];
        const Eigen::Vector4d s = node(wa.first + i, wb.first + j, wc.first + l);
        k += x.w * y.w * z.w * s;
        if constexpr (Order >= 1) {
          k_a += x.d1 * y.w * z.w * s;
          k_b += x.w * y.d1 * z.w * s;
          k_c += x.w * y.w * z.d1 * s;
        }
        if constexpr (Order >= 2) {
          k_aa += x.d2 * y.w * z.w * s;
          k_bb += x.w * y.d2 * z.w * s;
          k_cc += x.w * y.w * z.d2 * s;
          k_ab += x.d1 * y.d1 * z.w * s;
          k_ac += x.d1 * y.w * z.d1 * s;
          k_bc += x.w * y.d1 * z.d1 * s;
        }
      }
  StiffnessDerivatives out;
  out.k = k;
  if constexpr (Order == 0) return out;
  // Chain rule to g through the grid coordinates' Jacobian: a = (g0 + 1/4) N,
  // b = (g1 + 1/4) N, c = N |g2|~ (each slope 0 where clamped); c depends on
  // g0 and g1 too, through the shear band's width.
  Eigen::Matrix3d jacobian = Eigen::Matrix3d::Zero();
  jacobian(0, 0) = ca.slope;
  jacobian(1, 1) = cb.slope;
  jacobian.row(2) = cc.slope * shear.d1.transpose();
  for (int l = 0; l < 4; ++l) out.dk.row(l) = (jacobian.transpose() * Eigen::Vector3d(k_a[l], k_b[l], k_c[l])).transpose();
  if constexpr (Order == 1) {
    out.d2k.fill(Eigen::Matrix3d::Zero());
    return out;
  }
  for (int l = 0; l < 4; ++l) {
    Eigen::Matrix3d grid;
    grid << k_aa[l], k_ab[l], k_ac[l], k_ab[l], k_bb[l], k_bc[l], k_ac[l], k_bc[l], k_cc[l];
    out.d2k[static_cast<std::size_t>(l)] = jacobian.transpose() * grid * jacobian + k_c[l] * cc.slope * shear.d2;
  }
  return out;
}

}  // namespace

StiffnessDerivatives StretchingTable::stiffness_derivatives(const Eigen::Vector3d& g, int order) const {
  const auto nodes = [this](int i, int j, int k) { return node(i, j, k); };
  return order <= 0 ? smooth_lookup<0>(g, nodes) : order == 1 ? smooth_lookup<1>(g, nodes) : smooth_lookup<2>(g, nodes);
}

Eigen::Vector4d StretchingTable::smoothed_stiffness(const Eigen::Vector3d& g) const { return stiffness_derivatives(g, 0).k; }

namespace {

// Gauss-Legendre points and weights on [0, 1] (Boost.Math's rule on [-1, 1]
// lists the non-negative half).
struct Quadrature {
  std::array<double, kWorkQuadrature> t{}, w{};
  Quadrature() {
    using Rule = boost::math::quadrature::gauss<double, kWorkQuadrature>;
    static_assert(kWorkQuadrature % 2 == 0, "an even rule: no point at the middle");
    const auto& x = Rule::abscissa();
    const auto& weight = Rule::weights();
    for (std::size_t i = 0; i < x.size(); ++i) {
      t[2 * i] = 0.5 * (1.0 - x[i]);
      t[2 * i + 1] = 0.5 * (1.0 + x[i]);
      w[2 * i] = w[2 * i + 1] = 0.5 * weight[i];
    }
  }
};

const Quadrature& work_quadrature() {
  static const Quadrature q;
  return q;
}

}  // namespace

double StretchingTable::energy_density(const Eigen::Vector3d& g) const {
  // psi = sum_i w_i (2 / t_i) phi(t_i g).
  const Quadrature& q = work_quadrature();
  double psi = 0.0;
  for (std::size_t i = 0; i < q.t.size(); ++i) {
    const Eigen::Vector3d y = q.t[i] * g;
    psi += q.w[i] / q.t[i] * smoothed_stiffness(y).dot(strain_products(y));
  }
  return psi;
}

MembraneDensity StretchingTable::density(const Eigen::Vector3d& g, bool hessian) const {
  // d/dg phi(t g) = t phi'(t g), d2/dg2 = t^2 phi''(t g).
  const Quadrature& q = work_quadrature();
  MembraneDensity out;
  for (std::size_t i = 0; i < q.t.size(); ++i) {
    const MembraneDensity d = point_density(q.t[i] * g, hessian);
    out.psi += 2.0 * q.w[i] / q.t[i] * d.psi;
    out.dpsi += 2.0 * q.w[i] * d.dpsi;
    out.d2psi += 2.0 * q.w[i] * q.t[i] * d.d2psi;
  }
  return out;
}

MembraneDensity StretchingTable::point_density(const Eigen::Vector3d& g, bool hessian) const {
  const StiffnessDerivatives s = stiffness_derivatives(g, hessian ? 2 : 1);
  const Eigen::Vector4d q = strain_products(g);  // psi = k . q / 2
  Eigen::Matrix<double, 3, 4> dq;  // column l: dq_l/dg
  dq << 2.0 * g[0], 2.0 * g[1], 0.0, 0.0,  //
      0.0, 2.0 * g[0], 2.0 * g[1], 0.0,    //
      0.0, 0.0, 0.0, 4.0 * g[2];
  MembraneDensity out;
  out.psi = 0.5 * s.k.dot(q);
  out.dpsi = 0.5 * (s.dk.transpose() * q + dq * s.k);
  if (!hessian) return out;
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (int l = 0; l < 4; ++l) {
    h += q[l] * s.d2k[static_cast<std::size_t>(l)];
    const Eigen::Vector3d dk = s.dk.row(l).transpose();
    h += dk * dq.col(l).transpose() + dq.col(l) * dk.transpose();
  }
  // sum_l k_l d2q_l.
  h(0, 0) += 2.0 * s.k[0];
  h(0, 1) += 2.0 * s.k[1];
  h(1, 0) += 2.0 * s.k[1];
  h(1, 1) += 2.0 * s.k[2];
  h(2, 2) += 4.0 * s.k[3];
  out.d2psi = 0.5 * h;
  return out;
}

MembraneDensity linear_membrane_density(const Eigen::Vector4d& k, const Eigen::Vector3d& g) {
  // Written term by term as drape's linear membrane always was (same rounding).
  MembraneDensity out;
  out.d2psi << k[0], k[1], 0.0, k[1], k[2], 0.0, 0.0, 0.0, k[3];
  out.dpsi = Eigen::Vector3d(k[0] * g[0] + k[1] * g[1], k[1] * g[0] + k[2] * g[1], k[3] * g[2]);
  out.psi = 0.5 * (k[0] * g[0] * g[0] + k[2] * g[1] * g[1] + 2.0 * k[1] * g[0] * g[1] + k[3] * g[2] * g[2]);
  return out;
}

BendingCurve bending_curve(const ArcsimData& data, const Eigen::Vector2d& du) {
  // The edge's angle from u in units of 45 degrees, folded onto [0, 2]
  // (0 along u, 1 diagonal, 2 along v) since an edge has no direction.
  double bias = std::abs(std::atan2(du.y(), du.x()) * 4.0 / std::numbers::pi);
  if (bias > 4.0) bias = 8.0 - bias;
  if (bias > 2.0) bias = 4.0 - bias;
  const int row = std::clamp(static_cast<int>(bias), 0, 1);
  const double w = bias - row;
  BendingCurve curve;
  for (std::size_t j = 0; j < 5; ++j)
    curve.samples[j] = data.bending[static_cast<std::size_t>(row)][j] * (1.0 - w) + data.bending[static_cast<std::size_t>(row + 1)][j] * w;
  return curve;
}

namespace {

// dk/da on segment j of a bending curve (j = -1 mirrors segment 0: k depends
// on |a|; j = 4: flat past the table).
double bending_slope(const std::array<double, 5>& k, int j) {
  return j < 0 ? -(k[1] - k[0]) : j >= 4 ? 0.0 : k[static_cast<std::size_t>(j + 1)] - k[static_cast<std::size_t>(j)];
}

// The half-width (in columns) of column `knot`'s rounded corner.
double bending_corner_band(const std::array<double, 5>& k, int knot) {
  const double jump = bending_slope(k, knot) - bending_slope(k, knot - 1);
  return std::min(kBendingCornerBand, kBendingCornerDeviation * 4.0 * std::abs(k[static_cast<std::size_t>(knot)]) /
                                          std::max(std::abs(jump), 1e-300));
}

}  // namespace

std::array<double, 10> bending_breakpoints(const BendingCurve& curve) {
  std::array<double, 10> out{};
  out[0] = 10.0 * bending_corner_band(curve.samples, 0);
  for (int j = 1; j <= 4; ++j) {
    const double band = bending_corner_band(curve.samples, j);
    out[static_cast<std::size_t>(2 * j - 1)] = 10.0 * (j - band);
    out[static_cast<std::size_t>(2 * j)] = 10.0 * (j + band);
  }
  // The last band: k is flat on either side of 4 + band (bending_stiffness
  // switches to its flat branch at 4 + kBendingCornerBand, with the same value).
  out[9] = 10.0 * (4.0 + kBendingCornerBand);
  return out;
}

BendingStiffness bending_stiffness(const BendingCurve& curve, double curvature) {
  // Columns every 10 1/m (ArcSim: "samples are per 0.05 cm^-1" of half the
  // curvature), interpolated linearly with ArcSim, except within a band of
  // each column (kBendingCornerBand) where the corner is rounded.
  const double a = 0.1 * std::abs(curvature);
  const auto& k = curve.samples;
  // Past the last column's rounded corner the curve is flat. Said first, so
  // that a curvature of 1e300 (or NaN) never reaches the rounding to a column
  // index below (std::lround of it is undefined: it indexed k far out of range).
  if (!(a < 4.0 + kBendingCornerBand)) {
    BendingStiffness flat;
    if (k[4] > 0.0) flat.k = k[4];
    return flat;
  }
  const int knot = std::min(static_cast<int>(std::lround(a)), 4);
  const double u = a - knot, before = bending_slope(k, knot - 1), jump = bending_slope(k, knot) - before;
  const double band = bending_corner_band(k, knot);
  double value = 0.0, dk_da = 0.0, d2k_da2 = 0.0;
  if (std::abs(u) < band) {
    // A quadratic that meets both lines with their slopes at u = -band and u = +band (C1).
    value = k[static_cast<std::size_t>(knot)] + before * u + jump * (u + band) * (u + band) / (4.0 * band);
    dk_da = before + jump * (u + band) / (2.0 * band);
    d2k_da2 = jump / (2.0 * band);
  } else if (a >= 4.0) {
    value = k[4];
  } else {
    const int column = std::min(static_cast<int>(a), 3);
    const double w = a - column, lo = k[static_cast<std::size_t>(column)], hi = k[static_cast<std::size_t>(column + 1)];
    value = lo * (1.0 - w) + hi * w;
    dk_da = hi - lo;
  }
  BendingStiffness out;
  out.k = value;
  out.dk_dcurvature = 0.1 * dk_da * (curvature < 0 ? -1.0 : 1.0);
  out.d2k_dcurvature2 = 0.01 * d2k_da2;
  if (!(out.k > 0.0)) out = {};
  return out;
}

}  // namespace drape::arcsim
