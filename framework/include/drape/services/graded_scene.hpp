// A model of drapes in each body's own size (it takes the garment's grade)
// optimised against a scene's energies: the energies must be those of the
// garment the network is asked for, or the optimisation pulls a 2xlarge
// prediction towards the regular shirt's rest shape. The scene chooses: its
// size: auto or grade: auto by the tailor's rule, else its one garment; the
// network is fed that grade, and a grade asked for that is not the scene's is
// refused.
#pragma once

#include <drape/scene/garment_size.hpp>
#include <drape/training/model.hpp>

#include <string>

namespace drape {

// The garment grades of a scene's simulations, measured once per command
// (the one garment's grade may need its size chart built).
class GradedScene {
 public:
  GradedScene(const Registry& registry, const SceneSimulations& simulations);

  // The one garment's grade: its `grade`, times its size's when the scene
  // names a size other than the design size (measured on the size chart);
  // 0 with size: auto or grade: auto, where the grade is per body.
  double fixed_grade() const { return fixed_grade_; }
  // The grade the scene dresses `body` in: its size's grade times the
  // scene's `grade` (size: auto), the body's grade (grade: auto), or
  // fixed_grade(). *simulation: the simulation of that garment.
  double grade_for(const Eigen::MatrixX3d& body, const std::string& what, const Simulation** simulation = nullptr) const;
  // The simulation a model's prediction for the one body of `batch` is
  // optimised against. For a model that takes the grade: the scene's garment
  // for that body, its grade written into batch.garment_grade; when
  // `grade_given` (the user's --garment-size/--garment-grade, a dataset
  // sample's own) and it differs from the scene's, ConfigError "<what>: ...".
  // Other models: the scene's design simulation, the batch untouched.
  // *regraded (when given): a note, when the batch held a grade the rule
  // chose and the scene dresses the body in another ("" otherwise), which
  // drape optimize prints and Python warns.
  const Simulation& for_model(const Model& model, SampleBatch& batch, bool grade_given, const std::string& what,
                              std::string* regraded = nullptr) const;

 private:
  const SceneSimulations& simulations_;
  double fixed_grade_ = 0.0;
};

}  // namespace drape
