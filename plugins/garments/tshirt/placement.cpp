#include "placement.hpp"

#include <algorithm>
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
  const double a = torso.neck_half_width + torso.margin, b = torso.neck_half_depth + torso.margin;
  // Normalised section coordinates: the clearance ellipse is the unit circle.
  Eigen::Vector2d q(p.x() / a, (p.z() - torso.neck_centre_z) / b);
  if (side * q.y() < 1e-3) q.y() = side * 1e-3;  // the panel's own side of the neck
  const double r = q.norm();
  if (r >= 1) return p;
  q *= (r + above_base * (1 - r)) / r;
  p.x() = q.x() * a;
  p.z() = torso.neck_centre_z + q.y() * b;
  return p;
}

}  // namespace

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
