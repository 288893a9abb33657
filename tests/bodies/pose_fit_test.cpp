// Reading the pose off a body mesh given posed (pose_fit.hpp): bodies drawn
// over the shape space, posed by angles drawn from the pose space, turned and
// moved as another tool would leave them. What comes back is compared with
// what made them (the drawn angles, the solved body), not with the fit's own
// output: the angles, the body at rest, and the move back onto the mesh.
#include <drape/bodies/body_space.hpp>
#include <drape/bodies/pose_fit.hpp>
#include <drape/bodies/posed_body.hpp>
#include <drape/errors.hpp>

#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace drape;

namespace {

const BodyModel& human_rig() {
  static const auto model = test::parametric_body("{rig: human}");
  return *model;
}

double largest_angle_error(const Pose& fitted, const Pose& truth, std::string& which) {
  double worst = 0;
  for (const auto& [name, value] : truth.angles)
    if (const double e = std::abs(fitted.get(name, std::nan("")) - value); !(e <= worst)) worst = e, which = name;
  return worst;
}

double largest_distance(const Eigen::MatrixX3d& a, const Eigen::MatrixX3d& b) { return (a - b).rowwise().norm().maxCoeff(); }

}  // namespace

TEST_CASE("fit_pose reads the angles and the body at rest of bodies posed over the shape and pose spaces",
          "[bodies][pose-fit]") {
  const BodyModel& model = human_rig();
  Rng rng(11);
  BodySpace space;  // BMI 10-65, heights 1.5-2.0 m, both sexes, girths over their whole range
  // Turned 5 degrees and tilted 2 (about an axis the pose space has no angle
  // for), and moved: the fit takes the body's turn as a whole as well.
  const Eigen::Matrix3d turn = skinning::rodrigues(Eigen::Vector3d(0.035, 0.087, -0.01));
  const Eigen::RowVector3d offset(0.2, -0.03, 0.5);
  for (int i = 0; i < 4; ++i) {
    BodyRequest request = draw_body(space, model, rng);
    const Eigen::VectorXd shape = solve_in_space(model, request);
    const DrawnPose drawn = draw_free_pose(model, shape, rng);
    const Eigen::MatrixX3d rest = model.vertices(shape);
    const Pose truth = full_pose(model, drawn.pose, rest);
    const Eigen::MatrixX3d given = (drawn.vertices * turn.transpose()).rowwise() + offset;

    const PoseFit fit = fit_pose(model, given);
    INFO("BMI " << request.bmi << ", height " << request.height << ", sex " << request.sex << ", pose "
                << format_pose(truth));
    std::string which;
    const double angle_error = largest_angle_error(fit.pose, truth, which);
    INFO("worst angle " << which << " off by " << angle_error << " degrees");
    CHECK(angle_error < 0.5);
    // The body at rest, in the model's frame, where the model made it.
    CHECK(largest_distance(fit.rest, rest) < 1e-3);
    // Posed again and moved back: the mesh given.
    CHECK(fit.reposed_error < 1e-3);
    CHECK(largest_distance(fit.moved.back(model.posed_vertices(fit.rest, fit.pose, 1.0)), given) < 1e-3);
    // The model's own bodies are fitted to a fraction of a millimetre.
    CHECK(fit.fit_rms < 5e-4);
  }
}

TEST_CASE("fit_pose reads a body at rest as the rest pose, and refuses a body model without a skeleton or a mesh of another vertex count",
          "[bodies][pose-fit]") {
  const BodyModel& model = human_rig();
  const Eigen::VectorXd shape = model.solve(BodyRequest{17.0, 1.58, 0.0});  // thin: her thighs turn 10 degrees at rest
  const Eigen::MatrixX3d rest = model.vertices(shape);
  const PoseFit fit = fit_pose(model, rest);
  std::string which;
  const double angle_error = largest_angle_error(fit.pose, model.rest_pose(shape), which);
  INFO("worst angle " << which << " off by " << angle_error << " degrees");
  CHECK(angle_error < 0.5);
  CHECK(largest_distance(fit.rest, rest) < 1e-3);
  CHECK(fit.moved.rotation.isIdentity(1e-4));

  CHECK_THROWS_WITH(fit_pose(*test::skeletonless_body(), rest), Catch::Contains("no skeleton"));
  CHECK_THROWS_AS(fit_pose(model, rest.topRows(100)), ConfigError);
  Eigen::MatrixX3d broken = rest;
  broken(17, 1) = std::nan("");
  CHECK_THROWS_WITH(fit_pose(model, broken), Catch::Contains("not a finite number"));
  CHECK_THROWS_WITH(fit_pose(model, rest.topRows(100)), Catch::Contains("100 vertices"));
}

TEST_CASE("fit_pose on the hard cases: the body space's corners with elbows bent past the corrective's onset, an arm "
          "abducted 90 degrees (where its flexion and rotation turn about one axis)", "[bodies][pose-fit]") {
  const BodyModel& model = human_rig();
  struct Case {
    BodyRequest body;
    const char* pose;
  };
  for (const Case& c : {Case{{10.0, 1.5, 0.0}, "elbow_flexion=120,shoulder_abduction=100,spine_flexion=25"},
                        Case{{65.0, 1.5, 0.0}, "shoulder_abduction=90,shoulder_flexion=40,elbow_flexion=130"}}) {
    INFO("BMI " << c.body.bmi << ", pose " << c.pose);
    const Eigen::VectorXd shape = model.solve(c.body);
    const Pose pose = parse_pose(c.pose, model.pose_angles(), "test");
    const Eigen::MatrixX3d rest = model.vertices(shape);
    const Eigen::MatrixX3d given = model.posed(shape, pose);
    const PoseFit fit = fit_pose(model, given);
    REQUIRE(fit.rest.allFinite());
    std::string which;
    const double angle_error = largest_angle_error(fit.pose, full_pose(model, pose, rest), which);
    INFO("worst angle " << which << " off by " << angle_error << " degrees");
    // At 90 degrees of abduction flexion and rotation trade against each other (0.4 degrees of each moved the
    // body by a hundredth of a millimetre): the angles to a degree, the bodies exactly.
    CHECK(angle_error < 1.0);
    CHECK(std::abs(fit.pose.get("left_elbow_flexion", 0) - pose.get("left_elbow_flexion", 0)) < 0.5);
    CHECK(largest_distance(fit.rest, rest) < 1e-3);
    CHECK(fit.reposed_error < 1e-3);
  }
}
