#pragma once
// The space of bodies drape samples (drape body --sample, drape generate):
// BMI uniform over its range and, independently, sex, height and every
// proportion the body model offers (girths), so that bodies of one BMI differ
// in build as people do. docs/bodies.md shows the distribution.
#include <drape/bodies/body.hpp>
#include <drape/training/rng.hpp>

#include <string>

namespace drape {

struct BodySpace {
  double bmi_lo = 10, bmi_hi = 65;
  double height_lo = 1.50, height_hi = 2.00;  // m, uniform
  // Equal odds of sex_lo and sex_hi when they differ (the models blend two
  // sexes; in-between values are not people), else that value.
  double sex_lo = 0, sex_hi = 1;
  // Each proportion uniform over this fraction of the body model's own range
  // around zero (BodyModel::proportions): 0 keeps the mean build, 1 the full range.
  double proportion_spread = 1.0;
};

// Draws one request: the same number of draws whatever the ranges, so body
// i of a seed keeps its draws when one range changes.
BodyRequest draw_body(const BodySpace& space, const BodyModel& model, Rng& rng);

// The proportions part of that draw alone: each of the model's proportions
// uniform over `spread` of its range, one draw each; none when spread is 0.
void draw_proportions(double spread, const BodyModel& model, Rng& rng, BodyRequest& request);

// The shape that reaches the request. Proportions with which the model cannot
// reach the BMI (a very lean build at BMI 65), or with which the body passes
// through itself (broad arms on a BMI 10 torso), are halved towards the mean
// build until it can, at most four times, then dropped; `halvings` tells how
// many that took (0 for most draws) and `request` holds what was used.
// ConfigError when not even the mean build reaches it.
Eigen::VectorXd solve_in_space(const BodyModel& model, BodyRequest& request, int* halvings = nullptr);

// ConfigError naming the body model and the accepted names when a request
// holds a proportion the model does not offer, or one outside its range.
void check_proportions(const BodyModel& model, const std::string& model_name, const BodyRequest& request);

}  // namespace drape
