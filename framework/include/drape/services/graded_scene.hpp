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

class Model;

// The garment grade the scene dresses `body` in: its size's grade times the
// scene's `grade` (size: auto), the body's grade (grade: auto), or the one
// garment's (measured on its size chart when the scene names another size
// than the design size). *simulation: the simulation of that garment.
double scene_garment_grade(const Registry& registry, const SceneSimulations& simulations, const Eigen::MatrixX3d& body, const std::string& what, const Simulation** simulation = nullptr);

// The simulation a model's prediction for the one body of `batch` is
// optimised against. For a model that takes the grade: the scene's garment
// for that body, its grade written into batch.garment_grade; when
// `grade_given` (the user's --garment-size/--garment-grade, a dataset
// sample's own) and it differs from the scene's, ConfigError "<what>: ...".
// Other models: the scene's design simulation, the batch untouched.
const Simulation& graded_simulation(const Registry& registry, const SceneSimulations& simulations, const Model& model, SampleBatch& batch, bool grade_given, const std::string& what);

}  // namespace drape
