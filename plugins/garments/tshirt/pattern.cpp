#include "pattern.hpp"

#include <drape/errors.hpp>
#include <drape/garment_grading.hpp>

#include <cmath>

namespace drape::tshirt {
namespace {

double rad(double deg) { return deg * M_PI / 180; }

Eigen::Vector2d mirror(const Eigen::Vector2d& p) { return {-p.x(), p.y()}; }

// The straight pieces of the outline, counter-clockwise from the left hem
// corner (the neckline's curve lies between pieces 5 and 6): start and end.
constexpr int kPieces = 11;
std::pair<Eigen::Vector2d, Eigen::Vector2d> piece_ends(const PatternPoints& p, int piece) {
  switch (piece) {
    case 0: return {mirror(p.hem), p.hem};
    case 1: return {p.hem, p.armpit};
    case 2: return {p.armpit, p.sleeve_bottom};
    case 3: return {p.sleeve_bottom, p.sleeve_top};
    case 4: return {p.sleeve_top, p.shoulder};
    case 5: return {p.shoulder, p.neck};
    case 6: return {mirror(p.neck), mirror(p.shoulder)};
    case 7: return {mirror(p.shoulder), mirror(p.sleeve_top)};
    case 8: return {mirror(p.sleeve_top), mirror(p.sleeve_bottom)};
    case 9: return {mirror(p.sleeve_bottom), mirror(p.armpit)};
    case 10: return {mirror(p.armpit), mirror(p.hem)};
    default: throw Error("tshirt: no outline piece " + std::to_string(piece));
  }
}

// Appends straight piece `piece` (its start included, its end left to the
// next piece). Its end points are corners; panel_outline marks those shared
// with a seam.
void add_segment(Outline& out, const PatternPoints& p, int piece, bool seam, double spacing) {
  const auto [a, b] = piece_ends(p, piece);
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / spacing - 1e-9)));
  for (int k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / n;
    out.loop.push_back(a + (b - a) * t);
    out.on_seam.push_back(seam);
    out.piece.push_back(piece);
    out.along.push_back(t);
  }
}

// The armpit's distance along the sleeve from the shoulder point (pattern_points).
double armpit_along_sleeve(const PatternSpec& s) {
  const double alpha = rad(s.sleeve_angle_deg);
  return (s.half_width - s.shoulder_half_width + s.sleeve_opening * std::sin(alpha)) / std::cos(alpha);
}

}  // namespace

PatternSpec PatternSpec::graded(double g) const {
  if (g == 1.0) return *this;
  const double length_factor = grade_length(g), neck_factor = 1.0 + 0.8 * (g - 1.0),
               half_factor = 1.0 + 0.5 * (g - 1.0);
  PatternSpec out = *this;
  for (double* x : {&out.half_width, &out.shoulder_half_width}) *x *= g;
  for (double* x : {&out.length, &out.front_neck_depth, &out.back_neck_depth}) *x *= length_factor;
  out.neck_half_width *= neck_factor;
  out.sleeve_opening *= half_factor;
  out.sleeve_length = armpit_along_sleeve(out) + length_factor * (sleeve_length - armpit_along_sleeve(*this));
  return out;
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
  add_segment(out, p, 0, false, spacing);  // hem
  add_segment(out, p, 1, true, spacing);   // right side
  add_segment(out, p, 2, true, spacing);   // underarm
  add_segment(out, p, 3, false, spacing);  // sleeve end
  add_segment(out, p, 4, true, spacing);   // top of the sleeve
  add_segment(out, p, 5, true, spacing);   // shoulder

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
    out.piece.push_back(k == 0 ? 5 : kNeckline);  // the neck point ends the shoulder
    out.along.push_back(k == 0 ? 1.0 : 0.0);
  }
  add_segment(out, p, 6, true, spacing);
  add_segment(out, p, 7, true, spacing);
  add_segment(out, p, 8, false, spacing);
  add_segment(out, p, 9, true, spacing);
  add_segment(out, p, 10, true, spacing);
  // Corners where an open piece meets a seam belong to the seam.
  for (std::size_t i = 0; i < out.loop.size(); ++i) {
    const Eigen::Vector2d& q = out.loop[i];
    for (const Eigen::Vector2d& c : {p.hem, p.sleeve_top, p.sleeve_bottom, p.neck})
      if ((q - c).norm() < 1e-12 || (q - mirror(c)).norm() < 1e-12) out.on_seam[i] = 1;
  }
  return out;
}

Eigen::Vector2d outline_point_on(const PatternSpec& from, const PatternSpec& to, int piece, double along,
                                 const Eigen::Vector2d& p) {
  if (piece == kNeckline)  // the same neckline ellipses (the front's and the back's depths grade alike)
    return {p.x() * (to.neck_half_width / from.neck_half_width),
            to.length - (from.length - p.y()) * (to.front_neck_depth / from.front_neck_depth)};
  if (piece < 0 || piece >= kPieces) throw Error("tshirt: no outline piece " + std::to_string(piece));
  const auto [a, b] = piece_ends(pattern_points(to), piece);
  return a + (b - a) * along;
}

Box2 front_box(const PatternSpec& spec) {
  const PatternPoints p = pattern_points(spec);
  const double umax = std::max({p.sleeve_top.x(), p.sleeve_bottom.x(), p.hem.x()});
  return {{-umax, 0.0}, {umax, spec.length}};
}

}  // namespace drape::tshirt
