// fit_body (drape/bodies/fit_body.hpp): the body a larger (or smaller) size is
// cut for, of the mean height and sex and girth_ratio times the mean body's
// girth; the mean body itself, exactly, at 1; the largest the model reaches
// beyond its range.
#include <catch2/catch.hpp>

#include <drape/bodies/fit_body.hpp>
#include <drape/geometry/volume.hpp>
#include <drape/scene/garment_size.hpp>
#include <test_support.hpp>

#include <memory>

using namespace drape;

TEST_CASE("fit body: the mean request solves back to the mean body", "[bodies][sizes]") {
  const auto model = test::parametric_body();
  const BodyRequest r = model->mean_request();
  const Eigen::MatrixX3d mean = model->vertices(model->mean_shape());
  CHECK(r.height == Approx(1.75).margin(1e-9));
  CHECK(r.sex == 0.5);
  CHECK(r.bmi == Approx(geometry::mesh_volume(mean, model->faces()) * 985.0 / (1.75 * 1.75)).epsilon(1e-12));
  // The solve stops within 0.05 of the BMI: the body is the mean one to a millimetre.
  const Eigen::MatrixX3d again = model->vertices(model->solve(r));
  CHECK((again - mean).rowwise().norm().maxCoeff() < 1e-3);
}

TEST_CASE("fit body: the girth a grade asks for, the mean body at 1, the largest reached beyond", "[bodies][sizes]") {
  const auto model = test::parametric_body();
  const Eigen::MatrixX3i& faces = model->faces();
  const Eigen::MatrixX3d mean = model->vertices(model->mean_shape());
  const double mean_girth = body_girth(mean, faces);

  const FitBody same = fit_body(*model, 1.0);
  CHECK(same.vertices == mean);  // exactly: the regular size is dressed as it always was
  CHECK_FALSE(same.clamped);

  for (const double grade : {0.9, 1.4, 1.7}) {
    INFO("grade " << grade);
    const FitBody fit = fit_body(*model, grade);
    CHECK_FALSE(fit.clamped);
    CHECK(body_girth(fit.vertices, faces) / mean_girth == Approx(grade).epsilon(2e-3));
    CHECK(fit.girth_ratio == Approx(grade).epsilon(2e-3));
    // The mean's height and sex, another BMI: the same body solved at that BMI.
    CHECK(fit.request.height == Approx(1.75).margin(1e-9));
    CHECK(fit.request.sex == 0.5);
    CHECK(fit.vertices == model->vertices(model->solve(fit.request)));
    CHECK((fit.request.bmi > 24.7) == (grade > 1));
  }
  // The parametric body of 1.75 m reaches 1.83 times the mean girth (BMI 65): a 6xlarge's fit body is that one.
  const FitBody largest = fit_body(*model, 2.0);
  CHECK(largest.clamped);
  CHECK(largest.request.bmi == Approx(65.0));
  CHECK(largest.girth_ratio == Approx(1.835).margin(0.01));
}
