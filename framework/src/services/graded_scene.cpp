// The scene's garment for a model that takes the grade (services/graded_scene.hpp).
#include <drape/services/graded_scene.hpp>

#include <drape/errors.hpp>
#include <drape/scene/auto_grade.hpp>
#include <drape/scene/simulation.hpp>

#include <cmath>
#include <cstdio>

namespace drape {

double scene_garment_grade(const Registry& registry, const SceneSimulations& simulations, const Eigen::MatrixX3d& body,
                           const std::string& what, const Simulation** simulation) {
  const Scene& scene = simulations.design().scene();
  if (simulations.auto_size()) {
    SizeChoice choice;
    const Simulation& s = simulations.for_body(body, what, &choice);
    if (simulation) *simulation = &s;
    return scene.garment_grade * simulations.chart()->table().grade(choice.size);
  }
  if (simulations.auto_grade()) {
    GradeChoice choice;
    const Simulation& s = simulations.for_body(body, what, nullptr, &choice);
    if (simulation) *simulation = &s;
    return choice.grade;
  }
  if (simulation) *simulation = &simulations.design();
  // One garment: its grade, times its size's when the scene names a size other than the design size.
  const auto size = scene.garment_params.find("size");
  if (size == scene.garment_params.end() || !size->second.node.IsScalar()) return scene.garment_grade;
  const std::string name = size->second.node.as<std::string>();
  if (name == default_garment_size(registry, scene)) return scene.garment_grade;
  return scene.garment_grade * SizeChart(registry, scene).table().grade(name);
}

const Simulation& graded_simulation(const Registry& registry, const SceneSimulations& simulations, const Model& model, SampleBatch& batch, bool grade_given, const std::string& what) {
  if (!model.needs_input("garment_grade")) return simulations.design();
  // The size is chosen on the body at rest, as a posed scene chooses it.
  const Tensor& rest = batch.unposed_body.empty() ? batch.body : batch.unposed_body;
  const Simulation* simulation = nullptr;
  const double grade = scene_garment_grade(registry, simulations, rest.mat(0).cast<double>(), what, &simulation);
  if (grade_given && !batch.garment_grade.empty() && std::abs(batch.garment_grade(0, 0, 0) - grade) > 1e-3) {
    char text[320];
    std::snprintf(text, sizeof text,
                  "%s: the garment's grade is %.3f but the scene dresses this body in grade %.3f: its energies would pull "
                  "the drape towards that garment; optimise with a scene of that size (or size: auto), or leave the "
                  "size to the scene",
                  what.c_str(), static_cast<double>(batch.garment_grade(0, 0, 0)), grade);
    throw ConfigError(text);
  }
  batch.garment_grade = Tensor(batch.size(), 1, 1, static_cast<float>(grade));
  return *simulation;
}

}  // namespace drape
