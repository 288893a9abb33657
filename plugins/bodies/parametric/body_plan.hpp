#pragma once
// The rig: shape parameters -> the implicit body. Every shape has the same
// parts in the same order, so a template vertex bound to part i on the mean
// body can be carried to part i of any other body.
#include "implicit_body.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace drape::parametric {

// Index of each entry of the shape vector.
enum ShapeIndex { kHeight = 0, kSex, kWeight, kChest, kWaist, kBelly, kHips, kArms, kThighs, kNumShape };

struct ShapeSpec {
  std::string name;
  double mean, min, max;
  std::string doc;
};

// Names, means and the ranges accepted by vertices().
const std::vector<ShapeSpec>& shape_specs();
Eigen::VectorXd mean_shape_vector();
// Throws ConfigError naming the entry when `shape` has the wrong size or an entry out of range.
void check_shape(const Eigen::VectorXd& shape);

// Two rigs share the shape vector: the mannequin (every dataset and shipped
// model so far) and the human one (issue 54: a head with a face, shoulders
// that slope, hands with a thumb, feet with heel and toes; human_plan.cpp).
enum class Rig { Mannequin, Human };

// The implicit body of `shape`, before the final exact height normalisation.
ImplicitBody plan_body(const Eigen::VectorXd& shape, Rig rig = Rig::Mannequin);
ImplicitBody plan_mannequin_body(const Eigen::VectorXd& shape);
ImplicitBody plan_human_body(const Eigen::VectorXd& shape);

}  // namespace drape::parametric
