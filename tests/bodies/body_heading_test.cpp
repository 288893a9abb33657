// A body given turned about the vertical, leaning, or standing a few
// millimetres off where its model makes bodies (body_heading.hpp,
// body_anchor.hpp): found, undone exactly, and a lean beyond the limit refused.
#include <drape/bodies/body_anchor.hpp>
#include <drape/bodies/limb_turns.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/body_heading.hpp>
#include <drape/training/model_domain.hpp>

#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace drape;

namespace {

Eigen::Matrix3d about_y(double degrees) {
  const double t = degrees * std::numbers::pi / 180.0;
  Eigen::Matrix3d r;
  r << std::cos(t), 0, std::sin(t), 0, 1, 0, -std::sin(t), 0, std::cos(t);  // +z turns towards +x
  return r;
}

Eigen::Matrix3d about_x(double degrees) {
  const double t = degrees * std::numbers::pi / 180.0;
  Eigen::Matrix3d r;
  r << 1, 0, 0, 0, std::cos(t), -std::sin(t), 0, std::sin(t), std::cos(t);
  return r;
}

// Rows turned by r about the origin, then moved by t.
Eigen::MatrixX3d moved(const Eigen::MatrixX3d& v, const Eigen::Matrix3d& r, const Eigen::RowVector3d& t) {
  return (v * r.transpose()).rowwise() + t;
}

struct Bodies {
  std::unique_ptr<BodyModel> model = test::parametric_body("{rig: human}");
  Eigen::MatrixX3d mean = model->vertices(model->mean_shape());
  // Far from the mean body: a heavy tall man (his centroid 2-3 mm before the mean body's).
  Eigen::MatrixX3d heavy = model->vertices(model->solve(BodyRequest{55.0, 2.0, 1.0}));
};

const Bodies& bodies() {
  static const Bodies b;
  return b;
}

}  // namespace

TEST_CASE("a body's heading: the turn about the vertical and the lean, against the mean body", "[bodies][heading]") {
  const Bodies& b = bodies();
  // As the model makes it: neither turned nor leaning, whatever its build.
  const BodyHeading own = body_heading(b.heavy, b.mean);
  CHECK(std::abs(own.turn_degrees) < 0.01);
  CHECK(own.lean_degrees < 0.5);
  for (const double turn : {10.0, -35.0, 90.0, 180.0}) {
    const BodyHeading h = body_heading(moved(b.heavy, about_y(turn), {0.3, 1.0, -2.0}), b.mean);
    INFO("turned " << turn);
    CHECK(std::abs(std::remainder(h.turn_degrees - turn, 360.0)) < 0.01);
    CHECK(h.lean_degrees < 0.5);
  }
  const BodyHeading leaning = body_heading(moved(b.heavy, about_x(7.0), {0, 0, 0}), b.mean);
  CHECK(leaning.lean_degrees == Approx(7.0).margin(0.5));
}

TEST_CASE("turn_to_face undoes a turn exactly and moves the drape back, and refuses a lean past the limit",
          "[bodies][heading]") {
  const Bodies& b = bodies();
  SECTION("as the model makes it: left alone") {
    Eigen::MatrixX3d body = b.heavy;
    std::string note;
    const BodyMove move = turn_to_face(body, b.mean, "the body", &note);
    CHECK(move.is_identity());
    CHECK(note.empty());
    CHECK(body == b.heavy);
  }
  SECTION("turned half round: faces as the model's bodies again, up to where it stands") {
    const Eigen::MatrixX3d given = moved(b.heavy, about_y(180.0), {0.5, 0.0, 0.2});
    Eigen::MatrixX3d body = given;
    std::string note;
    const BodyMove move = turn_to_face(body, b.mean, "the body", &note);
    CHECK(move.turned());
    CHECK_THAT(note, Catch::Contains("faces 180.0 degrees") && Catch::Contains("turned back"));
    // The same body as made, moved only: every vertex by the same offset.
    const Eigen::MatrixX3d shift = body - b.heavy;
    CHECK((shift.rowwise() - shift.row(0)).cwiseAbs().maxCoeff() < 1e-5);
    // A drape made there goes back onto the given body; placed() and back() are inverses.
    CHECK((move.back(body) - given).cwiseAbs().maxCoeff() < 1e-9);
    CHECK((move.placed(given) - body).cwiseAbs().maxCoeff() < 1e-9);
  }
  SECTION("leaning a little: stood upright, with a note") {
    Eigen::MatrixX3d body = moved(b.heavy, about_x(5.0), {0, 0, 0});
    std::string note;
    const BodyMove move = turn_to_face(body, b.mean, "the body", &note);
    CHECK(move.turned());
    CHECK_THAT(note, Catch::Contains("leans 5."));  // 5 and the build's own tilt against the mean body
    CHECK(body_heading(body, b.mean).lean_degrees < 0.5);
  }
  SECTION("leaning past the limit: refused, naming the lean") {
    Eigen::MatrixX3d body = moved(b.heavy, about_x(25.0), {0, 0, 0});
    CHECK_THROWS_WITH(turn_to_face(body, b.mean, "body lean.obj"),
                      Catch::Contains("body lean.obj leans 25.") && Catch::Contains("degrees from upright") &&
                          Catch::Contains("stand it upright"));
  }
}

TEST_CASE("BodyMove::then is the two moves in turn, and back() undoes both", "[bodies][heading]") {
  BodyMove first;
  first.rotation = about_y(40.0) * about_x(3.0);
  first.pivot = {0.1, 0.9, -0.2};
  first.offset = {0.3, 0.0, 0.05};
  BodyMove second;
  second.rotation = about_x(-2.0) * about_y(-7.0);
  second.pivot = {-0.4, 1.1, 0.6};
  second.offset = {-0.02, 0.01, 0.2};
  const Eigen::MatrixX3d x = bodies().heavy.topRows(50);
  const BodyMove both = first.then(second);
  CHECK((both.placed(x) - second.placed(first.placed(x))).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((both.back(both.placed(x)) - x).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("the parametric body's anchor places a body given a few millimetres off exactly where the model made it",
          "[bodies][heading]") {
  const Bodies& b = bodies();
  const BodyAnchor anchor = find_body_anchor(*b.model);
  // x by the centroid (symmetric left to right), y by the soles, z by a few vertices.
  CHECK(anchor.measure[0] == BodyAnchor::Measure::centroid);
  CHECK(anchor.measure[1] == BodyAnchor::Measure::lowest);
  CHECK(anchor.measure[2] == BodyAnchor::Measure::vertices);
  CHECK(anchor.spread.maxCoeff() < 1e-4);
  // The centroid, the measure before, moves with the build: that is why it is not used.
  CHECK(std::abs(b.heavy.col(2).mean() - b.mean.col(2).mean()) > 1e-3);
  CHECK(anchor.offset(b.heavy).cwiseAbs().maxCoeff() < 5e-5);
  const Eigen::RowVector3d off(0.0021, -0.0013, 0.0035);
  Eigen::MatrixX3d body = b.heavy.rowwise() + off;
  const Eigen::Vector3d unknown = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  const auto offset = move_to_placement(unknown, unknown, &anchor, body);
  REQUIRE(offset);
  CHECK((offset->transpose() - off).cwiseAbs().maxCoeff() < 5e-5);
  CHECK((body - b.heavy).cwiseAbs().maxCoeff() < 5e-5);
  // Within the slack it is left alone.
  Eigen::MatrixX3d near = b.heavy.rowwise() + Eigen::RowVector3d(0, 0, 0.5 * kAnchorSlack);
  CHECK_FALSE(move_to_placement(unknown, unknown, &anchor, near));
}

TEST_CASE("the mannequin rig's depth is not anchored: no vertex holds it over the whole BMI range", "[bodies][heading]") {
  // Compared over three builds its steadiest z vertices agreed within 0.1 mm,
  // but at BMI 10-11 and 60-65 they drift by 0.15-0.22 mm: predict moved the
  // model's own training bodies by that and eval did not (an outside check).
  // Its z is placed by the centroid within the training bodies' spread.
  const std::unique_ptr<BodyModel> mannequin = test::parametric_body("{rig: mannequin}");
  const BodyAnchor anchor = find_body_anchor(*mannequin);
  CHECK(anchor.measure[0] == BodyAnchor::Measure::centroid);
  CHECK(anchor.measure[1] == BodyAnchor::Measure::lowest);
  CHECK(anchor.measure[2] == BodyAnchor::Measure::none);
  // Each body the model makes stands where it made it: no move on any axis.
  const Eigen::Vector3d unknown = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  for (const BodyRequest& r : {BodyRequest{11.1, 1.91, 0.0}, BodyRequest{64.8, 1.53, 1.0}}) {
    Eigen::MatrixX3d body = mannequin->vertices(mannequin->solve(r));
    CHECK_FALSE(move_to_placement(unknown, unknown, &anchor, body));
  }
  // The human rig's four hip vertices do hold it (the test above).
  CHECK(find_body_anchor(*bodies().model).measure[2] == BodyAnchor::Measure::vertices);
}

TEST_CASE("limb_turns tells a posed body from bodies at rest of every build", "[bodies][heading]") {
  const Bodies& b = bodies();
  // The corners of the space at rest: no limb past the 15 degrees predict warns at.
  for (const double bmi : {10.5, 64.5})
    for (const double sex : {0.0, 1.0})
      for (const double height : {1.5, 2.0}) {
        const Eigen::MatrixX3d rest = b.model->vertices(b.model->solve(BodyRequest{bmi, height, sex}));
        for (const LimbTurn& t : limb_turns(*b.model, b.mean, rest)) {
          INFO("BMI " << bmi << ", sex " << sex << ", " << height << " m: " << t.bone);
          CHECK(t.degrees < 15.0);
        }
      }
  // A pose: each bent joint's bone turned by its angle, the others not.
  Pose pose;
  pose.angles = {{"left_elbow_flexion", 40.0}, {"right_hip_flexion", 25.0}};
  const Eigen::MatrixX3d posed = b.model->posed(b.model->mean_shape(), pose);
  bool forearm = false, thigh = false;
  for (const LimbTurn& t : limb_turns(*b.model, b.mean, posed)) {
    INFO(t.bone << " " << t.degrees);
    if (t.bone == "left_forearm") {
      forearm = true;
      CHECK(t.degrees == Approx(40.0).margin(2.0));
    } else if (t.bone == "right_thigh") {
      thigh = true;
      CHECK(t.degrees == Approx(25.0).margin(2.0));
    } else {
      CHECK(t.degrees < 2.0);
    }
  }
  CHECK((forearm && thigh));
  // Turns are relative: the whole body turned changes none of them.
  const Eigen::MatrixX3d around = moved(posed, about_y(120.0), {1.0, 0.0, 0.0});
  const std::vector<LimbTurn> a = limb_turns(*b.model, b.mean, posed), c = limb_turns(*b.model, b.mean, around);
  REQUIRE(a.size() == c.size());
  for (std::size_t k = 0; k < a.size(); ++k) CHECK(c[k].degrees == Approx(a[k].degrees).margin(1e-6));
}
