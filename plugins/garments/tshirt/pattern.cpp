#include "pattern.hpp"

#include <drape/errors.hpp>

#include <cmath>

namespace drape::tshirt {
namespace {

double rad(double deg) { return deg * M_PI / 180; }

Eigen::Vector2d mirror(const Eigen::Vector2d& p) { return {-p.x(), p.y()}; }

// Appends a straight piece from a to b (a included, b left to the next piece).
// Its end points are corners; panel_outline marks those shared with a seam.
void add_segment(Outline& out, const Eigen::Vector2d& a, const Eigen::Vector2d& b, bool seam, double spacing) {
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / spacing - 1e-9)));
  for (int k = 0; k < n; ++k) {
    out.loop.push_back(a + (b - a) * (static_cast<double>(k) / n));
    out.on_seam.push_back(seam);
  }
}

}  // namespace

PatternSpec PatternSpec::scaled(double s) const {
  PatternSpec g = *this;
  for (double* x : {&g.half_width, &g.length, &g.neck_half_width, &g.front_neck_depth, &g.back_neck_depth,
                    &g.shoulder_half_width, &g.sleeve_length, &g.sleeve_opening})
    *x *= s;
  return g;
}

std::vector<std::string> size_names() {
  std::vector<std::string> names;
  for (const SizeGrade& g : kSizeGrades) names.emplace_back(g.name);
  return names;
}

double size_grade(const std::string& size) {
  std::string known;
  for (const SizeGrade& g : kSizeGrades) {
    if (size == g.name) return g.scale;
    known += (known.empty() ? "" : ", ") + std::string(g.name);
  }
  throw ConfigError("unknown size '" + size + "'; known: " + known);
}

PatternPoints pattern_points(const PatternSpec& spec) {
  PatternPoints p;
  const double alpha = rad(spec.sleeve_angle_deg);
  p.sleeve_dir = {std::cos(alpha), -std::sin(alpha)};
  p.sleeve_across = {-std::sin(alpha), -std::cos(alpha)};
  p.neck = {spec.neck_half_width, spec.length};
  p.shoulder = {spec.shoulder_half_width,
                spec.length - (spec.shoulder_half_width - spec.neck_half_width) * std::tan(rad(spec.shoulder_slope_deg))};
  p.sleeve_top = p.shoulder + spec.sleeve_length * p.sleeve_dir;
  p.sleeve_bottom = p.sleeve_top + spec.sleeve_opening * p.sleeve_across;
  // The underarm seam runs parallel to the top seam until it meets the side seam.
  p.armpit_s = (spec.half_width - spec.shoulder_half_width + spec.sleeve_opening * std::sin(alpha)) / std::cos(alpha);
  p.armpit = p.shoulder + spec.sleeve_opening * p.sleeve_across + p.armpit_s * p.sleeve_dir;
  p.hem = {spec.half_width, 0.0};
  if (!(p.armpit_s > 0 && p.armpit_s < spec.sleeve_length && p.armpit.y() > 0.2 * spec.length &&
        spec.neck_half_width < spec.shoulder_half_width && spec.shoulder_half_width < spec.half_width))
    throw ConfigError("inconsistent pattern (the sleeve must leave the body above the hem and below the shoulder)");
  return p;
}

double top_seam_v(const PatternSpec& spec, double u) {
  const double a = std::abs(u);
  if (a <= spec.neck_half_width) return spec.length;
  const PatternPoints p = pattern_points(spec);
  if (a <= spec.shoulder_half_width)
    return spec.length - (a - spec.neck_half_width) * std::tan(rad(spec.shoulder_slope_deg));
  return p.shoulder.y() - (a - p.shoulder.x()) * std::tan(rad(spec.sleeve_angle_deg));
}

Outline panel_outline(const PatternSpec& spec, bool front, double spacing) {
  const PatternPoints p = pattern_points(spec);
  Outline out;
  // Counter-clockwise from the left hem corner: hem, right side, right sleeve,
  // right shoulder, neckline, left shoulder, left sleeve, left side.
  add_segment(out, mirror(p.hem), p.hem, false, spacing);
  add_segment(out, p.hem, p.armpit, true, spacing);
  add_segment(out, p.armpit, p.sleeve_bottom, true, spacing);
  add_segment(out, p.sleeve_bottom, p.sleeve_top, false, spacing);
  add_segment(out, p.sleeve_top, p.shoulder, true, spacing);
  add_segment(out, p.shoulder, p.neck, true, spacing);

  // Neckline: half an ellipse through both neck points, resampled by arc length.
  const double depth = front ? spec.front_neck_depth : spec.back_neck_depth;
  Polygon2 curve;
  for (int k = 0; k <= 400; ++k) {
    const double t = M_PI / 2 - M_PI * k / 400;
    curve.emplace_back(spec.neck_half_width * std::sin(t), spec.length - depth * std::cos(t));
  }
  const Polygon2 neck = geometry::resample_polyline(
      curve, std::max(2, static_cast<int>(std::ceil(geometry::polyline_length(curve) / spacing - 1e-9))));
  for (std::size_t k = 0; k + 1 < neck.size(); ++k) {
    out.loop.push_back(neck[k]);
    out.on_seam.push_back(0);
  }
  add_segment(out, mirror(p.neck), mirror(p.shoulder), true, spacing);
  add_segment(out, mirror(p.shoulder), mirror(p.sleeve_top), true, spacing);
  add_segment(out, mirror(p.sleeve_top), mirror(p.sleeve_bottom), false, spacing);
  add_segment(out, mirror(p.sleeve_bottom), mirror(p.armpit), true, spacing);
  add_segment(out, mirror(p.armpit), mirror(p.hem), true, spacing);
  // Corners where an open piece meets a seam belong to the seam.
  for (std::size_t i = 0; i < out.loop.size(); ++i) {
    const Eigen::Vector2d& q = out.loop[i];
    for (const Eigen::Vector2d& c : {p.hem, p.sleeve_top, p.sleeve_bottom, p.neck})
      if ((q - c).norm() < 1e-12 || (q - mirror(c)).norm() < 1e-12) out.on_seam[i] = 1;
  }
  return out;
}

Box2 front_box(const PatternSpec& spec) {
  const PatternPoints p = pattern_points(spec);
  const double umax = std::max({p.sleeve_top.x(), p.sleeve_bottom.x(), p.hem.x()});
  return {{-umax, 0.0}, {umax, spec.length}};
}

}  // namespace drape::tshirt
