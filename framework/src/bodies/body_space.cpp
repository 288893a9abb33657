// Sampling the body space (body_space.hpp).
#include <drape/bodies/body.hpp>
#include <drape/bodies/body_space.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/self_intersection.hpp>

#include <cstdio>

namespace drape {

BodyRequest draw_body(const BodySpace& space, const BodyModel& model, Rng& rng) {
  BodyRequest r;
  // A fixed number of draws per body, in a fixed order, whatever the ranges:
  // body i of a seed stays body i when one range changes.
  const double b = rng.uniform(), h = rng.uniform(), s = rng.uniform();
  r.bmi = space.bmi_lo + (space.bmi_hi - space.bmi_lo) * b;
  r.height = space.height_lo + (space.height_hi - space.height_lo) * h;
  r.sex = space.sex_lo == space.sex_hi ? space.sex_lo : (s < 0.5 ? space.sex_lo : space.sex_hi);
  draw_proportions(space.proportion_spread, model, rng, r);
  return r;
}

void draw_proportions(double spread, const BodyModel& model, Rng& rng, BodyRequest& request) {
  for (const BodyModel::Proportion& p : model.proportions()) {
    const double u = rng.uniform();
    if (spread > 0) request.proportions[p.name] = spread * (p.min + (p.max - p.min) * u);
  }
}

Eigen::VectorXd solve_in_space(const BodyModel& model, BodyRequest& request, int* halvings) {
  for (int k = 0;; ++k) {
    if (halvings) *halvings = k;
    try {
      const Eigen::VectorXd shape = model.solve(request);
      // Girths drawn independently can clash: broad arms on a BMI 10 torso
      // cross it in the armpit (sample 1018 of the 2,000-drape run). Such a
      // body has no inside there, so it is treated as a build the model cannot
      // reach, as a lean build at BMI 65 is. The one intersection found is
      // enough; bodies without any come out as they always did.
      if (request.proportions.empty() || geometry::self_intersections(model.vertices(shape), model.faces(), 1).empty())
        return shape;
    } catch (const ConfigError&) {
      if (request.proportions.empty()) throw;
    }
    if (k == 4) request.proportions.clear();
    for (auto& [name, value] : request.proportions) value *= 0.5;
  }
}

void check_proportions(const BodyModel& model, const std::string& model_name, const BodyRequest& request) {
  const auto offered = model.proportions();
  for (const auto& [name, value] : request.proportions) {
    const BodyModel::Proportion* found = nullptr;
    for (const auto& p : offered)
      if (p.name == name) found = &p;
    if (!found) {
      std::string names;
      for (const auto& p : offered) names += (names.empty() ? "" : ", ") + p.name;
      throw ConfigError("body " + model_name + ": no proportion '" + name + "'" +
                        (names.empty() ? " (this model offers no proportions: BMI and height shape it)" : " (it has: " + names + ")"));
    }
    if (!(value >= found->min && value <= found->max)) {
      char m[160];
      std::snprintf(m, sizeof m, "body %s: proportion '%s' = %g is outside [%g, %g]", model_name.c_str(), name.c_str(), value,
                    found->min, found->max);
      throw ConfigError(m);
    }
  }
}

}  // namespace drape
