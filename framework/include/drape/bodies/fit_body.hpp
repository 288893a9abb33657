#pragma once
#include <drape/garment_dressing.hpp>
// The body a graded garment is cut for. A garment made for the mean body
// (fit_grade 1) is dressed on it and every drape's morph starts there; a
// larger size is cut for a larger body, so it is dressed on, and morphs
// from, the body of the model's mean proportions (the mean request's height
// and sex) whose girth is fit_grade times the mean body's: the girth the
// size-auto rule measures (body_girth, drape/scene/garment_size.hpp), so
// that the size has its design ease on its own fit body.
//
// Without it every size started on the mean body: a 6xlarge placed around a
// body half its girth hung as a tent, its sleeves and torso wrap passed
// through each other under the arms, and the morph then had to grow the body
// into it (docs/garments.md, "Sizes").
#include <drape/bodies/body.hpp>
#include <drape/energy.hpp>

#include <Eigen/Core>

#include <string>

namespace drape {

struct FitBody {
  Eigen::MatrixX3d vertices;
  BodyRequest request;       // what was solved (the mean request with its BMI)
  double girth_ratio = 1.0;  // its girth over the mean body's: fit_grade, unless clamped
  bool clamped = false;      // the model reaches no body that large (or small): its largest (smallest) was taken
};

// The mean body itself (exactly, not solved) when fit_grade is 1. Otherwise
// a secant search over the BMI within the model's bmi_range() to 0.2 % of the
// wanted girth; beyond the range (the parametric body at 1.75 m reaches
// 1.83 times the mean girth at BMI 65) the nearest body it reaches.
FitBody fit_body(const BodyModel& model, double fit_grade);

// Checks that `garment` goes around the body it is cut for (fit_body of its
// fit_grade; check_garment_around_body names it `what`), dresses it there
// (drape::dress) and returns that body. What Simulation and the assets build do.
FitBody dress_on_fit_body(const BodyModel& model, Garment& garment, const std::string& what);
// The same on a fit body already found (fit_body), for a caller that places
// the garment on it first (place_graded_garment, drape/garment_grading.hpp);
// what the dressing found (a garment placed through the body: placed_through).
DressReport dress_on(const FitBody& body, const BodyModel& model, Garment& garment, const std::string& what);

}  // namespace drape
