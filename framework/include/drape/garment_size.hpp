#pragma once
// Which size of a graded garment a body needs, by a tailor's rule, for scenes
// whose garment says `size: auto` (docs/garments.md, "Which size fits which
// body").
//
// The rule works with girths, as a size chart does:
// - the body's girth is the largest tape measure (geometry::horizontal_girth)
//   of its torso between 58 % and 72 % of its height above its soles, the
//   part a T-shirt covers: the chest, or the belly where that is larger;
// - a size's girth is the narrowest loop of its fabric over the same band of
//   the mean body (the torso of a tee is straight; narrowest, so that no
//   loop through an armhole counts);
// - ease = garment girth / body girth - 1. The default size on the mean body
//   has the design ease (14 % for the regular T-shirt on the mean man);
// - the size chosen is the one whose ease is nearest the design ease among
//   those with ease >= 0 (a garment smaller than the body would be stretched
//   onto it); when no size has ease >= 0 the garment does not fit the body,
//   and simulating it would hand back a drape stretched over the body and
//   unsettled: the caller says so instead.
#include <drape/registry.hpp>
#include <drape/scene.hpp>

#include <Eigen/Core>

#include <string>
#include <utility>
#include <vector>

namespace drape {

struct SizeChoice {
  std::string size;                                  // empty when no size fits
  double body_girth = 0.0;                           // m
  double design_ease = 0.0;                          // the default size's ease on the mean body
  std::vector<std::pair<std::string, double>> ease;  // every size's ease on this body, smallest size first
  double garment_girth(const std::string& s) const;  // m, of size s
  std::vector<std::pair<std::string, double>> girth; // every size's girth, m
  // One line: the measurements and the choice, or why nothing fits.
  std::string summary() const;
};

inline constexpr double kMinimumEase = 0.0;
inline constexpr double kGirthBandLow = 0.58, kGirthBandHigh = 0.72;  // fractions of the height

// True when the scene's garment has a `size` parameter set to "auto".
bool garment_size_is_auto(const Scene& scene);
// The default of the scene's garment's size parameter (its design size).
std::string default_garment_size(const Registry& registry, const Scene& scene);
// The scene with its garment's size set.
Scene with_garment_size(const Scene& scene, const std::string& size);
// The body's girth by the rule above (vertices of a body mesh, Y up).
double body_girth(const Eigen::MatrixX3d& body, const Eigen::MatrixX3i& faces);
// The sizes' girths and the design ease of a scene's garment, measured once
// (each size's garment is built and measured on the mean body); then a
// choice per body. ConfigError when the scene's garment has no size
// parameter with choices. choose() is const and may be called from threads.
class SizeChart {
 public:
  SizeChart(const Registry& registry, const Scene& scene);
  // The size for `body` (the scene body model's topology).
  SizeChoice choose(const Eigen::MatrixX3d& body) const;
  const std::vector<std::string>& sizes() const { return sizes_; }

 private:
  std::vector<std::string> sizes_;
  std::vector<std::pair<std::string, double>> girth_;
  double design_ease_ = 0.0;
  Eigen::Index body_vertices_ = 0;
  Eigen::MatrixX3i faces_;
};

// SizeChart(registry, scene).choose(body).
SizeChoice choose_garment_size(const Registry& registry, const Scene& scene, const Eigen::MatrixX3d& body);

}  // namespace drape
