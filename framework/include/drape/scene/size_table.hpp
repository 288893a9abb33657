#pragma once
// A garment's size chart as numbers only: each size's girth (the narrowest
// loop of its fabric over the chest-and-belly band of the mean body, m), the
// design size and its ease on the mean body. It is what `size: auto` chooses
// by (garment_size.hpp builds it from the sizes' meshes), and what a dataset
// of drapes in each body's own size and a model trained on it carry, so that
// `drape predict` chooses a body's size by the same rule without building a
// garment (docs/garments.md, "Which size fits which body").
#include <string>
#include <utility>
#include <vector>

namespace drape {

// The size a body wears by the tailor's rule, with the measurements.
struct SizeChoice {
  std::string size;                                   // empty when no size fits
  double body_girth = 0.0;                            // m
  double design_ease = 0.0;                           // the default size's ease on the mean body
  std::vector<std::pair<std::string, double>> girth;  // every size's girth, m, smallest size first
  double garment_girth(const std::string& s) const;   // m, of size s (0 when unknown)
  double ease(const std::string& s) const { return garment_girth(s) / body_girth - 1.0; }
  // One line: the measurements and the choice, or why nothing fits.
  std::string summary() const;
};

inline constexpr double kMinimumEase = 0.0;

struct SizeTable {
  std::vector<std::pair<std::string, double>> girth;  // m, smallest size first
  std::string design;                                 // the size the garment was made in
  double design_ease = 0.0;                           // its ease on the mean body

  bool empty() const { return girth.empty(); }
  // The size whose ease on a body of this girth is nearest the design ease
  // among those with ease >= min(kMinimumEase, design_ease) (a garment smaller than the body
  // would be stretched onto it); SizeChoice::size is empty when none is.
  SizeChoice choose(double body_girth) const;
  // A size's grade: its girth over the design size's (1 for the design size).
  // ConfigError naming the sizes for an unknown one.
  double grade(const std::string& size) const;
  std::string names() const;  // "3xsmall, 2xsmall, ..., 6xlarge"

  // As text, one line (a dataset attribute, a model's metadata):
  // "design=regular; design_ease=0.14; small=0.972, regular=1.08, ...".
  std::string to_text() const;
  // The text back; ConfigError naming `what` when it is not a size chart.
  static SizeTable parse(const std::string& text, const std::string& what);

  // The chart of both, when they are one garment's chart made at two times
  // (a dataset made before a size was added joins one made after): the same
  // design size and ease, and the same girth for every size both name; the
  // sizes of either, smallest first. ConfigError saying what differs, else.
  static SizeTable join(const SizeTable& a, const SizeTable& b);
};

}  // namespace drape
