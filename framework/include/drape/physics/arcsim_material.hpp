#pragma once
// ArcSim's data-driven cloth model (Wang, Ramamoorthi & O'Brien 2011, as
// ArcSim's dde.cpp and physics.cpp evaluate it), with the derivatives a
// Newton solver needs. docs/materials.md, "How drape evaluates ArcSim's
// model", lists every convention and each place drape departs from ArcSim.
//
// Stretching. ArcSim tabulates a stiffness k = [k_uu, k_uv, k_vv, k_shear]
// (N/m) over the Green strain G = (g0, g1, g2) = (G_uu, G_vv, G_uv):
//  * a sample (evaluate_stretching_sample) takes the largest principal stretch
//    w of C = 2G + I and the angle of its direction from u, interpolates
//    bilinearly between the zero-strain row and the five rows measured at
//    w = 1 + 1/6 (0, 22.5, 45, 67.5, 90 degrees), with the strain weight
//    6 (w - 1) clamped to [0, 1), clamps each coefficient at 0 and doubles it;
//  * the samples sit on a 30^3 grid, G_uu and G_vv in -0.25 + i/30, G_uv in
//    i/30, and k(G) is their trilinear interpolation at (G_uu, G_vv, |G_uv|)
//    (stretching_stiffness), clamped to the grid.
// ArcSim's solver integrates the stress s(G) = A(k(G)) G with
//   A(k) = [[k_uu, k_uv, 0], [k_uv, k_vv, 0], [0, 0, 2 k_shear]]
// (the derivative of (k_uu g0^2 + k_vv g1^2 + 2 k_uv g0 g1 + 2 k_shear g2^2) / 2
// with k held fixed), which no energy has as its gradient once k depends on G.
// drape's energy per unit rest area is the work that stress does along the
// straight strain path from rest,
//   psi(G) = int_0^1 s(t G) . G dt = int_0^1 (2 / t) phi(t G) dt,
//   phi(G) = (k_uu g0^2 + k_vv g1^2 + 2 k_uv g0 g1 + 2 k_shear g2^2) / 2, k = k(G),
// by kWorkQuadrature-point Gauss-Legendre quadrature, differentiated exactly:
// a true potential of the positions whose stress along a uniaxial stretch is
// ArcSim's force. phi itself (ArcSim's stretching_energy with the force's
// shear) was drape's energy until 2026-11-26: its stress k G + (dk/dG) G^2 / 2
// exceeds ArcSim's force by up to 40 % at 10-17 % strain and falls where the
// measured range ends (a negative stiffness, a material instability on which
// heavy drapes did not settle; docs/materials.md). One departure inside k:
// |G_uv| is smoothed near zero, over a band relative to the stretch (see
// kShearBand).
//
// Bending. ArcSim's stiffness (bending_stiffness) of a hinge side is the
// bilinear interpolation of the 3 x 5 table over the edge's material-space
// direction (0, 45, 90 degrees from u, folded by symmetry) and the curvature
// value |theta| l / (A0 + A1) / (10 1/m) (columns 0..4, clamped at 4), clamped
// at 0; a hinge takes the smaller of its two sides'. ArcSim takes theta with
// its sign, so a fold one way extrapolates below the first column and clamps
// to zero stiffness; drape takes |theta|: a fold costs the same either way.
#include <drape/energy.hpp>

#include <Eigen/Core>

#include <array>
#include <vector>

namespace drape::arcsim {

// ArcSim's grid size and the strain where the measured rows apply.
inline constexpr int kGridSamples = 30;
inline constexpr double kMeasuredStretch = 1.0 / 6.0;

// Gauss-Legendre points of the work integral: within 0.4 % of the exact
// integral over uniaxial stretches of 1-25 % in every direction (4 points:
// 1.7 %; scripts/reference/arcsim_reference.py).
inline constexpr int kWorkQuadrature = 8;

// |G_uv| enters ArcSim's lookup as a kink at zero shear (through the angle
// of the principal stretch, |atan2(...)|): the energy's gradient would jump
// there (by as much as the gradient itself on a face stretched along u), a
// V-shaped valley no Newton step settles into. drape replaces |s| by
// m f(s / m), f(x) = 2 x^2 - |x|^3 for |x| < 1 and |x| beyond (C1; equal to
// |s| at 0 and from m on), over a band that grows with the stretch,
//   m = sqrt(kShearBand^2 (G_uu^2 + G_vv^2) + kShearSmoothing^2),
// because the kink's size grows with it: the valley's walls differ in slope
// by dk/d|G_uv| times G^2, so a fixed band of 1e-3 made the Hessian of a
// taut face change twentyfold within 0.1 mm of motion, and Newton steps on
// the default shirt reached a third of the decrease their model predicted.
// Exact at zero shear and wherever |G_uv| >= m: on a uniaxial stretch 20
// degrees or more from the warp or weft (|G_uv| / |(G_uu, G_vv)| >= 0.36
// there) once |G| exceeds 0.4 %, like the fixed band of 1e-3 it replaced.
inline constexpr double kShearSmoothing = 1e-3;
inline constexpr double kShearBand = 0.25;

// Trilinear interpolation is only C0: the energy's gradient jumps across every
// face of the 30^3 grid, by as much as the gradient itself where the stiffness
// switches on with stretch (a face compressed one way and at rest the other,
// the common state of a wrinkled drape), and Newton stalls on such kinks.
// drape evaluates the trilinear stiffness averaged over a box of half-width
// kCornerSmoothing cells about G (separably: each 1D hat's corners rounded,
// the weights still summing to 1): C1, and equal to ArcSim's wherever the
// trilinear function is linear over the box, i.e. farther than 0.1 cell
// (1/300 in strain) from a grid plane. The grid's own edges (G_uu, G_vv =
// -0.25 and 0.717, where ArcSim holds the edge sample) are rounded the same way.
inline constexpr double kCornerSmoothing = 0.1;

// One of ArcSim's samples: the (doubled, clamped) stiffness at strain G.
Eigen::Vector4d stretching_sample(const ArcsimData& data, double g_uu, double g_vv, double g_uv);

// The stiffness k and its derivatives in g = (G_uu, G_vv, G_uv).
struct StiffnessDerivatives {
  Eigen::Vector4d k;
  Eigen::Matrix<double, 4, 3> dk;              // dk_l / dg_m
  std::array<Eigen::Matrix3d, 4> d2k;          // d2k_l / dg_m dg_n
};

// The energy density psi(g) (J/m^2 per unit rest area) and its derivatives.
struct MembraneDensity {
  double psi = 0.0;
  Eigen::Vector3d dpsi = Eigen::Vector3d::Zero();  // dpsi/dg
  Eigen::Matrix3d d2psi = Eigen::Matrix3d::Zero();
};

class StretchingTable {
 public:
  explicit StretchingTable(const ArcsimData& data);

  // ArcSim's lookup exactly (|G_uv|, no smoothing): what the tests compare with.
  Eigen::Vector4d stiffness(double g_uu, double g_vv, double g_uv) const;
  // drape's C1 lookup (kShearSmoothing, kCornerSmoothing) with derivatives.
  // (order 1: d2k left zero, for callers that need no Hessian; 0: k alone.)
  StiffnessDerivatives stiffness_derivatives(const Eigen::Vector3d& g, int order = 2) const;
  // drape's C1 lookup alone, and psi alone (what energy values need).
  Eigen::Vector4d smoothed_stiffness(const Eigen::Vector3d& g) const;
  double energy_density(const Eigen::Vector3d& g) const;
  // psi(g), the work integral, and its exact first and second derivatives
  // (hessian = false: d2psi left zero, for the gradient alone).
  MembraneDensity density(const Eigen::Vector3d& g, bool hessian = true) const;
  // phi(g) = k(g) . q(g) / 2 at one strain with its derivatives: the integrand.
  MembraneDensity point_density(const Eigen::Vector3d& g, bool hessian = true) const;

 private:
  // A sample, extended beyond the grid: the edge samples on the G_uu and G_vv
  // axes (ArcSim clamps there); below G_uv = 0 the first cell's line
  // continued, so that averaging across zero leaves the value at zero shear
  // exact (|G_uv| is even by itself). Inline: the lookups call it for each of
  // 8-27 nodes, 8 times per face and evaluation, and through the library's
  // PLT the call cost a seventh of the lookup (measured by perf).
  Eigen::Vector4d node(int i, int j, int k) const {
    i = i < 0 ? 0 : i >= kGridSamples ? kGridSamples - 1 : i;
    j = j < 0 ? 0 : j >= kGridSamples ? kGridSamples - 1 : j;
    if (k < 0) return 2.0 * sample(i, j, 0) - sample(i, j, 1);
    return sample(i, j, k < kGridSamples ? k : kGridSamples - 1);
  }
  const Eigen::Vector4d& sample(int i, int j, int k) const {
    return samples_[static_cast<std::size_t>((i * kGridSamples + j) * kGridSamples + k)];
  }
  std::vector<Eigen::Vector4d> samples_;  // [i][j][k] row-major
};

// The linear model's density, (k_uu g0^2 + k_vv g1^2 + 2 k_uv g0 g1 + k_shear g2^2) / 2
// (drape's form before ArcSim's tables: shear counted once, as ArcSim's energy).
MembraneDensity linear_membrane_density(const Eigen::Vector4d& k, const Eigen::Vector3d& g);

// One hinge side's stiffness against the curvature value: the table's rows
// interpolated at the edge's material-space direction `du`.
struct BendingCurve {
  std::array<double, 5> samples{};  // N*m at curvature value 0..4 (0, 10, ..., 40 1/m)
};
BendingCurve bending_curve(const ArcsimData& data, const Eigen::Vector2d& du);

// ArcSim's stiffness at curvature |theta| l / A (1/m; A the two faces' area),
// and its first two derivatives in that curvature.
struct BendingStiffness {
  double k = 0.0;
  double dk_dcurvature = 0.0;
  double d2k_dcurvature2 = 0.0;  // nonzero only on a rounded corner
};
BendingStiffness bending_stiffness(const BendingCurve& curve, double curvature);

// The curvatures (1/m, ascending, >= 0) where bending_stiffness passes from
// one polynomial in |curvature| to the next: each column's rounded corner's
// two ends (the first column's only end is its band; a band of 0 gives the
// column twice). Between two of them, and beyond the last, k is a polynomial
// of degree at most 2 in |curvature|, so the work of the bending moment
// k(|s|) s over each piece is a cubic (the bending energy's work potential).
std::array<double, 10> bending_breakpoints(const BendingCurve& curve);

// ArcSim interpolates the bending table linearly, so dk/dcurvature jumps at
// every column, and the bending force with it: a fold angle sitting on a
// column is a kink of the energy, and Newton's iterates gather on such kinks
// and stall (found on the MakeHuman shirt at BMI 39: forward and backward
// differences of the energy differed by 20 % within 1e-9 m). Each column's
// corner is rounded by a quadratic over |curvature value - column| < band,
// band = min(kBendingCornerBand, 4 kBendingCornerDeviation k_j / |jump of
// slope|), which keeps k within kBendingCornerDeviation of ArcSim's at the
// column and exact outside the band.
inline constexpr double kBendingCornerBand = 0.1;        // in columns (1 1/m of curvature)
inline constexpr double kBendingCornerDeviation = 0.005;  // at most 0.5 % of k at the column

}  // namespace drape::arcsim
