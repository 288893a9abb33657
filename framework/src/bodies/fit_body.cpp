// fit_body (fit_body.hpp) and the default BodyModel::mean_request.
#include <drape/bodies/fit_body.hpp>
#include <drape/errors.hpp>
#include <drape/garment_dressing.hpp>
#include <drape/geometry/volume.hpp>
#include <drape/scene/garment_size.hpp>

#include <algorithm>
#include <cmath>
#include <optional>

namespace drape {

BodyRequest BodyModel::mean_request() const {
  const Eigen::MatrixX3d v = vertices(mean_shape());
  BodyRequest r;
  r.height = v.col(1).maxCoeff() - v.col(1).minCoeff();
  r.bmi = geometry::mesh_volume(v, faces()) * 985.0 / (r.height * r.height);
  r.sex = 0.5;
  return r;
}

FitBody fit_body(const BodyModel& model, double fit_grade) {
  if (!(fit_grade > 0.0)) throw ConfigError("a garment's fit grade must be positive");
  FitBody out;
  const Eigen::MatrixX3d mean = model.vertices(model.mean_shape());
  out.request = model.mean_request();
  if (fit_grade == 1.0) {
    out.vertices = mean;
    return out;
  }
  const Eigen::MatrixX3i& faces = model.faces();
  const double mean_girth = body_girth(mean, faces), target = fit_grade * mean_girth;
  const auto [bmi_lo, bmi_hi] = model.bmi_range();
  double lo = bmi_lo, hi = bmi_hi;  // narrowed where solve() refuses a BMI

  struct Eval {
    double bmi, girth;
    Eigen::MatrixX3d vertices;
  };
  std::optional<Eval> best;
  // The body at `bmi`, or nothing when the model cannot reach it for this
  // height and sex (then the bound moves in).
  auto eval = [&](double bmi) -> std::optional<Eval> {
    BodyRequest r = out.request;
    r.bmi = bmi;
    try {
      Eval e{bmi, 0.0, model.vertices(model.solve(r))};
      e.girth = body_girth(e.vertices, faces);
      if (!best || std::abs(e.girth - target) < std::abs(best->girth - target)) best = e;
      return e;
    } catch (const ConfigError&) {
      (bmi > out.request.bmi ? hi : lo) = bmi;
      return std::nullopt;
    }
  };
  // Secant steps on girth(BMI) from the mean body. First guess: at a fixed
  // height the girth grows about as BMI^0.77 (the parametric body).
  double x0 = out.request.bmi, f0 = mean_girth - target;
  double x1 = std::clamp(x0 * std::pow(fit_grade, 1.3), lo, hi);
  std::optional<Eval> e1 = eval(x1);
  for (int k = 0; k < 8 && !e1; ++k) e1 = eval(x1 = 0.5 * (x0 + x1));  // back towards the mean until reached
  if (!e1) throw ConfigError("the body model reaches no body near its mean shape for a garment of fit grade " +
                             std::to_string(fit_grade));
  double f1 = e1->girth - target;
  for (int k = 0; k < 10 && std::abs(f1) > 2e-3 * target; ++k) {
    double x2 = f1 != f0 ? x1 - f1 * (x1 - x0) / (f1 - f0) : x1;
    x2 = std::clamp(x2, lo, hi);
    if (std::abs(x2 - x1) < 1e-3) break;  // at a bound of the range: as near as the model goes
    std::optional<Eval> e2 = eval(x2);
    if (!e2) {
      x2 = std::clamp(x2, lo, hi);  // the refused bound moved in: try just inside it
      if (!(e2 = eval(x2 = 0.5 * (x1 + x2)))) break;
    }
    x0 = x1, f0 = f1, x1 = x2, f1 = e2->girth - target;
  }
  out.vertices = std::move(best->vertices);
  out.request.bmi = best->bmi;
  out.girth_ratio = best->girth / mean_girth;
  out.clamped = std::abs(best->girth - target) > 2e-3 * target;
  return out;
}

FitBody dress_on_fit_body(const BodyModel& model, Garment& garment, const std::string& what) {
  FitBody body = fit_body(model, garment.fit_grade);
  dress_on(body, model, garment, what);
  return body;
}

DressReport dress_on(const FitBody& body, const BodyModel& model, Garment& garment, const std::string& what) {
  const Mesh mesh{body.vertices, model.faces(), {}, {}};
  check_garment_around_body(garment.mesh, mesh, what);
  return dress(garment, mesh);
}

}  // namespace drape
