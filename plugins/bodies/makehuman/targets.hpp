#pragma once
// MakeHuman macro targets: sparse per-vertex offsets mixed by slider values
// exactly as MakeHuman does (see the assets' README): each slider becomes a few
// piecewise-linear key weights, and a file's weight is the product of the key
// weights its name lists.
#include <Eigen/Core>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace drape::makehuman {

struct Sliders {
  double gender = 1.0;       // 0 female, 1 male
  double muscle = 0.5;
  double weight = 0.5;
  double height = 0.5;
  double proportions = 0.5;
  double african = 1.0 / 3, asian = 1.0 / 3, caucasian = 1.0 / 3;  // renormalised to sum 1
};

struct Target {
  std::string name;             // path relative to targets/macrodetails, without .target
  std::vector<int> index;
  Eigen::MatrixX3f offset;      // one row per index, in the base mesh's units (dm)
};

// Reads every *.target under <root>/targets/macrodetails (recursively).
std::vector<Target> load_macro_targets(const std::filesystem::path& root);

// The weight of one target file for these sliders (age fixed at young = 1).
double target_weight(const std::string& name, const Sliders& s);

// base + sum(weight * offsets) over all targets with non-zero weight.
Eigen::MatrixX3d apply_targets(const Eigen::MatrixX3d& base, const std::vector<Target>& targets, const Sliders& s);

}  // namespace drape::makehuman
