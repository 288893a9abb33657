// The scene's garment for a model that takes the grade (services/graded_scene.hpp).
#include <drape/services/graded_scene.hpp>

#include <drape/errors.hpp>
#include <drape/scene/auto_grade.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/scene/simulation.hpp>

#include <cmath>
#include <cstdio>

namespace drape {

GradedScene::GradedScene(const Registry& registry, const SceneSimulations& simulations) : simulations_(simulations) {
  if (simulations.auto_size() || simulations.auto_grade()) return;  // per body
  const Scene& scene = simulations.design().scene();
  fixed_grade_ = scene.garment_grade;
  const auto size = scene.garment_params.find("size");
  if (size == scene.garment_params.end() || !size->second.node.IsScalar()) return;
  const std::string name = size->second.node.as<std::string>();
  if (name != default_garment_size(registry, scene)) fixed_grade_ *= SizeChart(registry, scene).table().grade(name);
}

double GradedScene::grade_for(const Eigen::MatrixX3d& body, const std::string& what, const Simulation** simulation) const {
  if (simulations_.auto_size()) {
    SizeChoice choice;
    const Simulation& s = simulations_.for_body(body, what, &choice);
    if (simulation) *simulation = &s;
    return simulations_.design().scene().garment_grade * simulations_.chart()->table().grade(choice.size);
  }
  if (simulations_.auto_grade()) {
    GradeChoice choice;
    const Simulation& s = simulations_.for_body(body, what, nullptr, &choice);
    if (simulation) *simulation = &s;
    return choice.grade;
  }
  if (simulation) *simulation = &simulations_.design();
  return fixed_grade_;
}

const Simulation& GradedScene::for_model(const Model& model, SampleBatch& batch, bool grade_given,
                                         const std::string& what, std::string* regraded) const {
  if (!model.needs_input("garment_grade")) return simulations_.design();
  // The size is chosen on the body at rest, as a posed scene chooses it.
  const Tensor& rest = batch.unposed_body.empty() ? batch.body : batch.unposed_body;
  const Simulation* simulation = nullptr;
  // A drape given in one of the chart's sizes is optimised in that size: the
  // shipped sized drapes were made when the smallest size was small, and a
  // thin body the chart now dresses in 2xsmall stopped optimize --data (an
  // outside check: "grade 0.900 but the scene dresses this body in 0.801").
  if (grade_given && !batch.garment_grade.empty() && simulations_.auto_size()) {
    const SizeChart& chart = *simulations_.chart();
    const double design = simulations_.design().scene().garment_grade;
    for (const std::string& size : chart.sizes())
      if (std::abs(design * chart.table().grade(size) - batch.garment_grade(0, 0, 0)) <= 1e-3) {
        batch.garment_grade = Tensor(batch.size(), 1, 1, static_cast<float>(design * chart.table().grade(size)));
        return chart.simulation(size);
      }
  }
  const double grade = grade_for(rest.mat(0).cast<double>(), what, &simulation);
  if (grade_given && !batch.garment_grade.empty() && std::abs(batch.garment_grade(0, 0, 0) - grade) > 1e-3) {
    char text[320];
    std::snprintf(text, sizeof text,
                  "%s: the garment's grade is %.3f but the scene dresses this body in grade %.3f: its energies would pull "
                  "the drape towards that garment; optimise with a scene of that size (or size: auto), or leave the "
                  "size to the scene",
                  what.c_str(), static_cast<double>(batch.garment_grade(0, 0, 0)), grade);
    throw ConfigError(text);
  }
  if (regraded && !batch.garment_grade.empty() && std::abs(batch.garment_grade(0, 0, 0) - grade) > 1e-3) {
    // (Said after the tailor's rule's note of the size the body would wear,
    // which it overrides: both read as the answer, an outside check.)
    char text[320];
    std::snprintf(text, sizeof text,
                  "the scene dresses this body in grade %.3f (its own garment), not the grade %.3f of the size the "
                  "tailor's rule gives it: the model predicts and is optimised in the scene's garment",
                  grade, static_cast<double>(batch.garment_grade(0, 0, 0)));
    *regraded = text;
  }
  batch.garment_grade = Tensor(batch.size(), 1, 1, static_cast<float>(grade));
  return *simulation;
}

}  // namespace drape
