#pragma once
// `garment: {grade: auto}`: any garment that goes around the torso (a mesh
// file, a MakeHuman piece, the tshirt) graded for each body as a tailor
// grades a pattern to a customer: by the grade that gives this body the ease
// the garment has on the mean body it was made for (its design ease), by the
// tailor's rule of garment_size.hpp (the body's chest or belly against the
// garment's narrowest loop over the same band). The size chart of a garment
// without sizes, made continuous.
//
// Grades are steps of kAutoGradeStep, so that bodies of about one girth
// share one graded garment (each is graded, dressed on its fit body and
// built once): a step of 0.05 leaves the ease within 2.5 points of the design
// ease (5 for a garment made tight, which never goes tighter than designed),
// inside the 5 points the fit note lets pass. A body that needs a grade
// outside 0.5-2 is refused before anything is simulated, with its measure and
// the grade it would need: the garment cannot fit it.
//
// The steps are a size chart (size_table.hpp) of sizes named g0.50 ...
// g2.00 (from the first step the body model can dress: g0.60 for the
// parametric body, whose thinnest body at its mean height has 0.56 of the
// mean girth), each of the design loop times its grade, chosen by the chart's own
// rule (nearest the design ease among those not smaller than the body): a
// dataset keeps it as its size_chart, so that a model trained on the drapes
// chooses each body's grade by the same rule (drape predict, --garment-size
// g1.35 or --garment-grade).
#include <drape/registry.hpp>
#include <drape/scene/scene.hpp>
#include <drape/scene/simulation.hpp>
#include <drape/scene/size_table.hpp>

#include <Eigen/Core>

#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace drape {

inline constexpr double kAutoGradeStep = 0.05;

struct GradeChoice {
  double body_girth = 0;   // m, the body's chest or belly
  double exact = 1;        // the grade that gives the design ease exactly
  double grade = 1;        // the chart's step nearest the design ease: what the body wears
  // The body needs a grade below the smallest the body model can dress (its
  // thinnest body's girth, over the mean body's, is `thinnest`), so it wears
  // that one, looser than designed.
  bool at_smallest = false;
  double thinnest = 0;
  std::string summary() const;  // one line: the measure and the grade
};

class AutoGrade {
 public:
  // `scene` has garment_grade_auto; its design garment (grade 1) is built
  // here. ConfigError when the garment does not go around the torso band
  // (trousers, a skirt: no girth to grade by) or also says size: auto.
  AutoGrade(const Registry& registry, const Scene& scene);
  ~AutoGrade();
  const Simulation& design() const { return *design_; }
  double design_ease() const { return design_ease_; }
  // The steps as a size chart (design size g1.00).
  const SizeTable& table() const { return table_; }
  // The grade `body` wears; ConfigError "<what>: ... cannot fit this body"
  // naming the girths and the grade when it is outside 0.5-2.
  GradeChoice choose(const Eigen::MatrixX3d& body, const std::string& what) const;
  // The scene graded by `grade` (a GradeChoice::grade), built on first use;
  // safe to call from threads.
  const Simulation& simulation(double grade) const;

 private:
  const Registry& registry_;
  Scene scene_;  // grade 1, garment_grade_auto off: what each grade is built from
  std::unique_ptr<Simulation> design_;
  double design_loop_ = 0, design_ease_ = 0;
  double thinnest_ = 0;     // the thinnest fit body's girth over the mean body's (per unit of the garment's fit grade)
  SizeTable table_;
  SizeTable every_grade_;  // the chart from kMinGrade, as if every grade could be dressed (GradeChoice::at_smallest)
  mutable std::mutex mutex_;
  mutable std::map<long, std::unique_ptr<Simulation>> graded_;  // by grade / kAutoGradeStep
};

}  // namespace drape
