#pragma once
// The T-shirt's sewing pattern: two T-shaped panels (front, back) with kimono
// half-sleeves, in meters. Coordinates are the "front frame": u to the wearer's
// left (+x in 3D), v up from the hem. The back panel has the same outline with
// a shallower neckline, so every seam piece is the same polyline on both panels.
#include <drape/geometry/polygon2d.hpp>

#include <string>
#include <vector>

namespace drape::tshirt {

using geometry::Polygon2;

struct PatternSpec {
  double half_width = 0.27;          // half the chest width of one panel (circumference 4x this)
  double length = 0.70;              // hem to the neck point
  double neck_half_width = 0.085;
  double front_neck_depth = 0.10;    // below the neck points
  double back_neck_depth = 0.025;
  double shoulder_slope_deg = 18;    // the shoulder seam drops this much from the neck
  double shoulder_half_width = 0.22; // u of the shoulder point, where the sleeve starts
  double sleeve_angle_deg = 20;      // sleeve below horizontal, in the flat pattern
  double sleeve_length = 0.22;       // along the top seam from the shoulder point
  double sleeve_opening = 0.19;      // flat width of the sleeve end (half its circumference)

  // The pattern of a size whose chest is `g` times this one's, graded as
  // ready-to-wear tees are (docs/garments.md, "Sizes"): the girths (chest,
  // shoulder points, sleeve opening) by g; the lengths (body length, neck
  // depths, the sleeve past the armpit) by drape::grade_length(g) = 1 + 0.3
  // (g - 1); the neck's width halfway, by 1 + 0.5 (g - 1). The sleeve's top
  // seam runs from the graded shoulder point past the graded armpit by the
  // graded free sleeve. Angles stay. g = 1 gives this pattern unchanged.
  PatternSpec graded(double g) const;
};

// Graded sizes: the regular pattern graded by the chest (PatternSpec::graded);
// every size has the same mesh (faces identical, only UVs and positions move),
// which is what lets one network serve several. The steps follow a common tee
// grading of 4-6 cm of chest per size: regular 1.08 m around, large 1.21,
// xlarge 1.35. The plus sizes continue by ~15 % of the regular's girth a
// step, up to 2.16 m around (6xlarge), for the heaviest bodies of the seed's
// range, whose chest or belly girth reaches 1.6-2.1 m (docs/garments.md,
// "size: auto"). Lengths grow 0.3 times as fast as the chest, so a 6xlarge
// is 30 % longer than the regular, as on real size charts. Below small, three
// sizes of 10 % of the regular's girth a step (xsmall 0.86 m around, 2xsmall
// 0.76, 3xsmall 0.65) dress the thin half of the range, whose chest or belly
// is 0.57-0.86 m around at BMI 10-20: in the small they stood in a box of
// 30-70 % ease (docs/garments.md, "Sizes below small").
struct SizeGrade {
  const char* name;
  double scale;
};
inline constexpr SizeGrade kSizeGrades[] = {{"3xsmall", 0.6}, {"2xsmall", 0.7}, {"xsmall", 0.8},   {"small", 0.9},
                                            {"regular", 1.0},  {"large", 1.12},  {"xlarge", 1.25},  {"2xlarge", 1.4},
                                            {"3xlarge", 1.55}, {"4xlarge", 1.7}, {"5xlarge", 1.85}, {"6xlarge", 2.0}};
std::vector<std::string> size_names();
double size_grade(const std::string& size);  // ConfigError naming the known sizes

// The corners of the right half (u >= 0); the left half is the mirror image.
struct PatternPoints {
  Eigen::Vector2d neck, shoulder, sleeve_top, sleeve_bottom, armpit, hem;
  Eigen::Vector2d sleeve_dir;     // along the sleeve, away from the body
  Eigen::Vector2d sleeve_across;  // from the top seam towards the underarm seam
  double armpit_s = 0;            // distance of the armpit along sleeve_dir from the shoulder point
};
PatternPoints pattern_points(const PatternSpec& spec);

// v of the top seam (shoulder, then top of sleeve) above |u|; the neck line above |u| < neck.
double top_seam_v(const PatternSpec& spec, double u);

struct Outline {
  Polygon2 loop;              // counter-clockwise
  std::vector<char> on_seam;  // per point: lies on a seam (shared with the other panel)
  // Per point: the straight piece of the outline it lies on (0-10, from the
  // left hem corner counter-clockwise; kNeckline for the neck's curve) and
  // how far along it (0 at its start).
  std::vector<int> piece;
  std::vector<double> along;
};
inline constexpr int kNeckline = -1;

// The panel's boundary sampled about `spacing` apart; seam pieces give
// bit-identical points for front and back.
Outline panel_outline(const PatternSpec& spec, bool front, double spacing);

// Where a point of `from`'s outline (its piece and how far along, as
// panel_outline gives them; p itself for the neckline) lies on `to`'s: the
// same fraction of the same piece, and on the neckline the point scaled by the
// two necklines' widths and depths. A function of the point alone, so the
// points both panels share stay shared.
Eigen::Vector2d outline_point_on(const PatternSpec& from, const PatternSpec& to, int piece, double along,
                                 const Eigen::Vector2d& p);

// The front panel's bounding box (normalised print coordinates refer to it).
struct Box2 {
  Eigen::Vector2d lo, hi;
};
Box2 front_box(const PatternSpec& spec);

}  // namespace drape::tshirt
