#include "placement.hpp"

#include <algorithm>
#include <iterator>
#include <cmath>

namespace drape::tshirt {
namespace {

double smoothstep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

// Ramanujan's approximation of an ellipse's perimeter.
double ellipse_perimeter(double a, double b) {
  return M_PI * (3 * (a + b) - std::sqrt((3 * a + b) * (a + 3 * b)));
}

struct Ellipse {
  double a, b;
};

// Grown from the body's chest + margin until half its perimeter holds the
// panel's width, so the wrap does not stretch the knit around the chest. The
// ease goes mostly to the sides, as on a worn tee (the flat panels stand off the
// body at the side seams, not in front of the chest): depth grows by the square
// root of the overall factor, and the half-width takes the rest.
Ellipse torso_ellipse(const PatternSpec& spec, const TorsoFrame& torso) {
  const double a0 = torso.half_width + torso.margin, b0 = torso.half_depth + torso.margin;
  const double half = 2 * spec.half_width;
  const double s = half / (0.5 * ellipse_perimeter(a0, b0));
  if (s <= 1) return {a0, b0};
  const double b = b0 * std::sqrt(s);
  double lo = a0, hi = 4 * a0;
  for (int k = 0; k < 60; ++k) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * ellipse_perimeter(mid, b) < half ? lo : hi) = mid;
  }
  return {0.5 * (lo + hi), b};
}

// The body part for u >= 0.
Eigen::Vector3d torso_map(const PatternSpec& spec, const PatternPoints& pp, const TorsoFrame& torso, const Ellipse& e,
                          double u, double v, double side) {
  const double phi = M_PI / 2 * std::min(u / spec.half_width, 1.0);
  const double x = e.a * std::sin(phi) + std::max(0.0, u - spec.half_width);
  // Above the armpits the body is the shoulders, deeper than the chest's
  // ellipse says out there (it falls to zero depth at the side seam) and
  // centred behind it: the fold's radius grows to the shoulder's half-depth
  // and its centre moves to the arm's, over a band above the armpit. Below the
  // armpit (every side and underarm seam point) nothing changes, so the seams
  // stay closed. Without it the back panel started 4 cm inside the shoulder blades.
  const double above_armpit = smoothstep((v - pp.armpit.y()) / 0.10);
  const double lateral = smoothstep((phi - M_PI / 4) / (M_PI / 4));
  const double centre_z = torso.centre_z + above_armpit * lateral * (torso.arm_axis_z - torso.centre_z);
  // Over the shoulder the panel bends along a quarter circle whose radius is
  // the local depth, so front and back meet at the top seam. The circle is
  // parametrised by arc length (the pattern's v), so the fold is isometric:
  // mapping v straight to height instead stretched the shoulders up to 2.5x.
  const double radius = std::max(e.b * std::cos(phi), above_armpit * torso.shoulder_half_depth);
  const double y_seam = torso.neck_height - (spec.length - top_seam_v(spec, u));
  const double s = std::max(0.0, top_seam_v(spec, u) - v);  // along the panel from the seam
  const double arc = M_PI / 2 * radius;
  double y = 0, depth = 0;
  if (s < arc) {
    const double theta = s / radius;  // radius > 0 here since arc > s >= 0
    y = y_seam - radius + radius * std::cos(theta);
    depth = radius * std::sin(theta);
  } else {
    y = y_seam - radius - (s - arc);
    depth = radius;
  }
  return {x, y, centre_z + side * depth};
}

// The collar rings the neck: the back neckline lies only 2.5 cm from the neck
// points in the pattern, so the fold put it through the neck's middle. Points
// above the neck's base closer to its axis than its radius plus the margin
// are moved out to that distance, radially in the neck's (elliptic) section,
// to their own panel's side. The move depends on the 3D point and the panel
// only where the panels do not meet (seam points lie farther out), so the
// seams stay closed.
Eigen::Vector3d clear_neck(const TorsoFrame& torso, Eigen::Vector3d p, double side) {
  const double above_base = smoothstep((p.y() - torso.neck_base_height) / 0.04);
  if (above_base <= 0) return p;
  const double a = torso.neck_half_width + torso.neck_margin, b = torso.neck_half_depth + torso.neck_margin;
  // Normalised section coordinates: the clearance ellipse is the unit circle.
  Eigen::Vector2d q(p.x() / a, (p.z() - torso.neck_centre_z) / b);
  if (torso.neck_sideways && side * q.y() < 1e-3) {
    // On the other panel's side of the neck's centre: beside the neck at the
    // top seam, where both panels meet in front of the neck's centre. Moved
    // out sideways (to the ellipse at its own depth): flipped to its own side
    // as below, a row of them landed on one point, which crossed its
    // neighbours on the larger sizes' thicker necks.
    if (std::abs(q.y()) >= 1 || q.x() >= std::sqrt(1 - q.y() * q.y())) return p;
    p.x() = a * (q.x() + above_base * (std::sqrt(1 - q.y() * q.y()) - q.x()));
    return p;
  }
  if (side * q.y() < 1e-3) q.y() = side * 1e-3;  // the panel's own side of the neck
  const double r = q.norm();
  if (r >= 1) return p;
  q *= (r + above_base * (1 - r)) / r;
  p.x() = q.x() * a;
  p.z() = torso.neck_centre_z + q.y() * b;
  return p;
}

// What the torso frame of the fit body of a girth ratio differs by from the
// mean body's, measured on the parametric bodies of 1.75 m and sex 0.5 that
// fit_body gives (BMI 10 = 0.556 of the mean girth, 21.1, 24.7 = the mean,
// 29.3, 34.8, 41.8, 49.3, 57.3, 65 = 1.835) by scripts/tshirt_fit_torso.py:
// the chest's loop at y = 1.24-1.28 (largest |x|; z extent and centre), the
// neck's at y = 1.50-1.54, the upper arm's axis through the centroids of its
// sections by the planes x = 0.30-0.60 (its height and z where x = 0.292; its
// angle), and the arm's half-depth at its root (x = 0.30). The top of the
// shoulders beside the neck stays at y = 1.46 on all of them, so the neck
// points keep their height. (Measured so on the mean body, the chest is
// 0.178 wide, the frame's default 0.155: the defaults were set by hand, so
// the sizes move them by differences.)
struct TorsoDelta {
  double girth_ratio;
  double half_width, half_depth, centre_z, neck_half_width, neck_half_depth, neck_centre_z, arm_angle_deg, arm_axis_y,
      arm_axis_z, shoulder_half_depth;
};
constexpr TorsoDelta kFitTorso[] = {
    {0.556, -0.0761, -0.0515, -0.0041, -0.0157, -0.0152, 0.0007, 2.78, -0.0396, 0.0005, -0.0204},
    {0.900, -0.0145, -0.0103, -0.0008, -0.0028, -0.0027, 0.0001, 0.41, -0.0197, 0.0002, -0.0047},
    {1.000, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0},
    {1.119, 0.0158, 0.0129, 0.0011, 0.0042, 0.0041, -0.0002, -0.41, 0.0213, -0.0002, 0.0057},
    {1.250, 0.0311, 0.0282, 0.0024, 0.0105, 0.0102, -0.0004, -0.84, 0.0416, -0.0008, 0.0112},
    {1.400, 0.0478, 0.0454, 0.0039, 0.0176, 0.0171, -0.0007, -1.30, 0.0632, -0.0015, 0.0178},
    {1.550, 0.0637, 0.0623, 0.0054, 0.0246, 0.0240, -0.0009, -1.42, 0.0818, -0.0021, 0.0240},
    {1.699, 0.0790, 0.0790, 0.0068, 0.0315, 0.0308, -0.0010, -2.13, 0.0955, -0.0025, 0.0301},
    {1.835, 0.0925, 0.0939, 0.0081, 0.0376, 0.0369, -0.0011, -3.03, 0.1069, -0.0024, 0.0332},
};

}  // namespace

TorsoFrame fit_torso(const TorsoFrame& mean, double grade) {
  if (grade == 1.0) return mean;
  const std::size_t n = std::size(kFitTorso);
  const double r = std::clamp(grade, kFitTorso[0].girth_ratio, kFitTorso[n - 1].girth_ratio);
  std::size_t i = 0;
  while (i + 2 < n && kFitTorso[i + 1].girth_ratio < r) ++i;
  const TorsoDelta &a = kFitTorso[i], &b = kFitTorso[i + 1];
  const double t = (r - a.girth_ratio) / (b.girth_ratio - a.girth_ratio);
  auto at = [&](double TorsoDelta::*m) { return a.*m + t * (b.*m - a.*m); };
  TorsoFrame f = mean;
  f.neck_sideways = true;
  // 2.5 cm more collar clearance per unit of grade: at the coarse resolution
  // the back neckline's points of a 2xlarge lie 10 cm apart around its fit
  // body's neck (15 cm across against the mean's 11), and the straight edges
  // between them sagged 1.5 cm inwards, into the neck.
  if (grade > 1.0) f.neck_margin += 0.025 * (grade - 1.0);
  f.half_width += at(&TorsoDelta::half_width);
  f.half_depth += at(&TorsoDelta::half_depth);
  f.centre_z += at(&TorsoDelta::centre_z);
  f.neck_half_width += at(&TorsoDelta::neck_half_width);
  f.neck_half_depth += at(&TorsoDelta::neck_half_depth);
  f.neck_centre_z += at(&TorsoDelta::neck_centre_z);
  f.arm_angle_deg += at(&TorsoDelta::arm_angle_deg);
  f.arm_axis_y += at(&TorsoDelta::arm_axis_y);
  f.arm_axis_z += at(&TorsoDelta::arm_axis_z);
  f.shoulder_half_depth += at(&TorsoDelta::shoulder_half_depth);
  return f;
}

Eigen::Vector3d place(const PatternSpec& spec, const TorsoFrame& torso, const Eigen::Vector2d& p, double side) {
  const Ellipse e = torso_ellipse(spec, torso);
  const double mirror = p.x() < 0 ? -1 : 1;
  const double u = std::abs(p.x()), v = p.y();
  const PatternPoints pp = pattern_points(spec);
  const Eigen::Vector3d body = clear_neck(torso, torso_map(spec, pp, torso, e, u, v, side), side);

  // Sleeve: s along the sleeve from the shoulder point, w across it from the top seam.
  const Eigen::Vector2d q = Eigen::Vector2d(u, v) - pp.shoulder;
  const double s = q.dot(pp.sleeve_dir), w = q.dot(pp.sleeve_across);
  const double weight = smoothstep(s / pp.armpit_s) * (1 - smoothstep((w - spec.sleeve_opening) / 0.04));
  Eigen::Vector3d out = body;
  if (weight > 0) {
    const double theta = torso.arm_angle_deg * M_PI / 180;
    const Eigen::Vector3d along(std::cos(theta), -std::sin(theta), 0), up(std::sin(theta), std::cos(theta), 0);
    const double radius = spec.sleeve_opening / M_PI;  // the flat width is half the circumference
    // The tube is coaxial with the arm and starts level with the torso's
    // shoulder point; the blend weight joins the two maps across the armhole.
    const Eigen::Vector3d arm(torso.arm_axis_x, torso.arm_axis_y, torso.arm_axis_z);
    const Eigen::Vector3d shoulder = torso_map(spec, pp, torso, e, pp.shoulder.x(), pp.shoulder.y(), side);
    const Eigen::Vector3d axis0 = arm + (shoulder - arm).dot(along) * along;
    const double psi = M_PI * std::clamp(w / spec.sleeve_opening, 0.0, 1.0);
    const Eigen::Vector3d sleeve =
        axis0 + s * along + radius * (std::cos(psi) * up + side * std::sin(psi) * Eigen::Vector3d::UnitZ());
    out = (1 - weight) * body + weight * sleeve;
  }
  out.x() *= mirror;
  return out;
}

}  // namespace drape::tshirt
