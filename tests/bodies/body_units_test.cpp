// check_body_units: a body in other units, lying down or with an absurd
// coordinate is refused with the cause, before any work (issue 58).
#include <drape/geometry/body_units.hpp>
#include <drape/errors.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

using namespace drape;

namespace {

// A box standing like a person: 0.5 m wide (x), 1.75 m tall (y), 0.3 m deep (z), soles at y = 0.
Eigen::MatrixX3d standing_box() {
  Eigen::MatrixX3d v(8, 3);
  for (int i = 0; i < 8; ++i) v.row(i) << (i & 1 ? 0.25 : -0.25), (i & 2 ? 1.75 : 0.0), (i & 4 ? 0.15 : -0.15);
  return v;
}

}  // namespace

TEST_CASE("a standing body in metres passes, from a toddler to the tallest person", "[bodies][units]") {
  CHECK(body_units_problem(standing_box(), "body") == "");
  CHECK(body_units_problem(standing_box() * (0.45 / 1.75), "body") == "");
  CHECK(body_units_problem(standing_box() * (2.72 / 1.75), "body") == "");
  Eigen::MatrixX3d t_pose = standing_box();
  t_pose.col(0) *= 1.75 / 0.5 * 1.05;  // an arm span 5 % over the height
  CHECK(body_units_problem(t_pose, "body") == "");
}

TEST_CASE("a body in centimetres or millimetres is refused with the scale that would fit", "[bodies][units]") {
  const std::string cm = body_units_problem(standing_box() * 100, "body b.obj");
  CHECK_THAT(cm, Catch::Contains("body b.obj is 175 m tall") && Catch::Contains("scaled by 0.01 it would be 1.75 m"));
  const std::string mm = body_units_problem(standing_box() * 1000, "body b.obj");
  CHECK_THAT(mm, Catch::Contains("1750 m tall") && Catch::Contains("scaled by 0.001 it would be 1.75 m"));
  CHECK_THAT(body_units_problem(standing_box() * 1e6, "body b.obj"), Catch::Contains("scaled by 1e-06 it would be 1.75 m"));
  const std::string dm = body_units_problem(standing_box() * 10, "body b.obj");
  CHECK_THAT(dm, Catch::Contains("scaled by 0.1 it would be 1.75 m"));
  CHECK_THROWS_AS(check_body_units(standing_box() * 100, "body"), ConfigError);
}

TEST_CASE("a body in inches or feet is named so, not as centimetres or decimetres", "[bodies][units]") {
  // Read as a power of ten, 69 inches were "centimetres (0.689 m)", which the 0.4-2.8 m range would pass.
  const std::string inches = body_units_problem(standing_box() / 0.0254, "body b.obj");
  CHECK_THAT(inches, Catch::Contains("likely in inches (scaled by 0.0254 it would be 1.75 m)"));
  const std::string feet = body_units_problem(standing_box() / 0.3048, "body b.obj");
  CHECK_THAT(feet, Catch::Contains("likely in feet (scaled by 0.3048 it would be 1.75 m)"));
  // Between common units (a body 3,000 times too large: 5.25 m in millimetres): the factor, no unit guessed.
  CHECK_THAT(body_units_problem(standing_box() * 3000, "body"),
             Catch::Contains("no common unit") && Catch::Contains("scaled by 0.000324 it would be 1.7 m"));
}

TEST_CASE("a spike is named as stray vertices, and a body at one point as no body", "[bodies][units]") {
  // 400 points of a body 1.75 m tall, then two thrown 5 m out: the extent says 6.75 m, the body does not.
  Eigen::MatrixX3d v(400, 3);
  for (int i = 0; i < 400; ++i) v.row(i) << 0.25 * std::sin(i), 1.75 * (i % 97) / 96.0, 0.15 * std::cos(i);
  v.row(7) << 0.0, 1.7, 5.0;
  v.row(300) << 0.0, 1.0, 4.5;
  const std::string spike = body_units_problem(v, "body b.obj");
  CHECK_THAT(spike, Catch::Contains("body b.obj: 2 vertices lie far outside the rest of the body, which is 1.75 m tall") &&
                        Catch::Contains("vertex 7 at (0, 1.7, 5)") && Catch::Contains("not a body in other units"));
  const std::string point = body_units_problem(Eigen::MatrixX3d::Constant(50, 3, 0.3), "body b.obj");
  CHECK(point == "body b.obj has every vertex at one point (0 m tall): it is no body");
}

TEST_CASE("a body lying along z or x is refused", "[bodies][units]") {
  Eigen::MatrixX3d z_up = standing_box();
  z_up.col(1).swap(z_up.col(2));
  CHECK_THAT(body_units_problem(z_up, "body"), Catch::Contains("longer along z than along y (1.75 m against 0.3 m)"));
  Eigen::MatrixX3d on_side = standing_box();
  on_side.col(0).swap(on_side.col(1));
  CHECK_THAT(body_units_problem(on_side, "body"), Catch::Contains("longer along x"));
}

TEST_CASE("a non-finite or absurd body coordinate is named, without a 300-digit number", "[bodies][units]") {
  Eigen::MatrixX3d v = standing_box();
  v(5, 0) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THAT(body_units_problem(v, "body"), Catch::Contains("body vertex 5 has x = nan") && Catch::Contains("finite"));
  v = standing_box();
  v(3, 2) = -std::numeric_limits<double>::infinity();
  CHECK_THAT(body_units_problem(v, "body"), Catch::Contains("body vertex 3 has z = -inf"));
  v = standing_box();
  v(6, 1) = 1e308;
  const std::string far = body_units_problem(v, "body");
  CHECK_THAT(far, Catch::Contains("body vertex 6 has y = 1e+308") && Catch::Contains("over 1e9 m"));
  CHECK(far.size() < 200);
}
