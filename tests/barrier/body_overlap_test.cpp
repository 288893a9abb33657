// A body mesh that passes through itself where the garment lies has no
// inside there: the scene refuses it, naming the place, instead of draping on
// it and reporting a p that means nothing. A body that crosses itself far from
// the garment (its feet) is not the garment's business.
#include <drape/errors.hpp>
#include <drape/geometry/self_intersection.hpp>
#include <drape/registry.hpp>
#include <drape/scene/scene.hpp>
#include <drape/scene/simulation.hpp>

#include <catch2/catch.hpp>

#include "../../framework/src/scene/body_overlap.hpp"
#include <drape/scene/body_overlap.hpp>
#include "test_support.hpp"

using namespace drape;

namespace {

Simulation coarse_shirt_scene() {
  return Simulation(test::plugins(), parse_scene("body: {model: parametric}\n"
                                                 "garment: {template: tshirt, params: {size: regular, resolution: coarse}}\n"
                                                 "effects: {gravity: {}, stretching: {}, barrier: {}}\n"
                                                 "solver: {morph_steps: 2, settle_steps: 1}\n"));
}

// The mean body with the vertices in a box moved by `shift`.
Eigen::MatrixX3d moved(const Eigen::MatrixX3d& body, const Eigen::RowVector3d& lo, const Eigen::RowVector3d& hi,
                       const Eigen::RowVector3d& shift, int* count) {
  Eigen::MatrixX3d out = body;
  *count = 0;
  for (Eigen::Index v = 0; v < body.rows(); ++v)
    if ((body.row(v).array() >= lo.array()).all() && (body.row(v).array() <= hi.array()).all()) {
      out.row(v) += shift;
      ++*count;
    }
  return out;
}

}  // namespace

TEST_CASE("a body that passes through itself under the garment is refused, naming where", "[barrier][bodies]") {
  const Simulation sim = coarse_shirt_scene();
  const Eigen::MatrixX3d& mean = sim.mean_body();
  const Eigen::RowVector3d lo = mean.colwise().minCoeff(), hi = mean.colwise().maxCoeff();
  const double height = hi.y() - lo.y(), mid_z = 0.5 * (lo.z() + hi.z());
  // A patch of the chest, at 72-76 % of the height, pushed 0.6 m through the
  // back (deeper than any torso).
  int count = 0;
  const Eigen::MatrixX3d body =
      moved(mean, Eigen::RowVector3d(-0.06, lo.y() + 0.72 * height, mid_z), Eigen::RowVector3d(0.06, lo.y() + 0.76 * height, hi.z()),
            Eigen::RowVector3d(0, 0, -0.6), &count);
  REQUIRE(count >= 4);
  // Read independently of the scene: the moved mesh does cross itself.
  REQUIRE_FALSE(geometry::self_intersections(body, sim.body_model().faces(), 1).empty());
  try {
    sim.run(body);
    FAIL("a self-intersecting body under the shirt was draped");
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK_THAT(what, Catch::Contains("intersects itself where the garment lies"));
    CHECK_THAT(what, Catch::Contains("heights"));
  }
  // The unmodified body passes the check.
  const geometry::BodySurface dressed_on(mean, sim.body_model().faces());
  CHECK(scene_detail::body_overlap_near_garment(dressed_on, mean, sim.garment().mesh.vertices, 0.05).empty());
}

TEST_CASE("a body that crosses itself only far below the shirt passes the check", "[barrier][bodies]") {
  const Simulation sim = coarse_shirt_scene();
  const Eigen::MatrixX3d& mean = sim.mean_body();
  const Eigen::RowVector3d lo = mean.colwise().minCoeff(), hi = mean.colwise().maxCoeff();
  const double height = hi.y() - lo.y();
  // One foot (x > 0, the lowest 5 % of the height) pushed across into the other.
  int count = 0;
  const Eigen::MatrixX3d body = moved(mean, Eigen::RowVector3d(0.0, lo.y(), lo.z()),
                                      Eigen::RowVector3d(hi.x(), lo.y() + 0.05 * height, hi.z()), Eigen::RowVector3d(-0.2, 0, 0), &count);
  REQUIRE(count >= 4);
  REQUIRE_FALSE(geometry::self_intersections(body, sim.body_model().faces(), 1).empty());
  const geometry::BodySurface dressed_on(mean, sim.body_model().faces());
  CHECK(scene_detail::body_overlap_near_garment(dressed_on, body, sim.garment().mesh.vertices, 0.05).empty());
}

TEST_CASE("crossings in two places are named each, not by a centre between them", "[barrier][bodies]") {
  // A patch of the top of each foot pushed down through its sole: two places
  // a foot apart. Their common centre is on the midline, where the body is not.
  const auto model = test::parametric_body();
  const Eigen::MatrixX3d mean = model->vertices(model->mean_shape());
  const Eigen::RowVector3d lo = mean.colwise().minCoeff(), hi = mean.colwise().maxCoeff();
  const double height = hi.y() - lo.y();
  int left = 0, right = 0;
  const Eigen::RowVector3d down(0, -0.06, 0);
  Eigen::MatrixX3d body = moved(mean, Eigen::RowVector3d(0.0, lo.y() + 0.03 * height, 0.04),
                                Eigen::RowVector3d(hi.x(), lo.y() + 0.045 * height, hi.z()), down, &left);
  body = moved(body, Eigen::RowVector3d(lo.x(), lo.y() + 0.03 * height, 0.04), Eigen::RowVector3d(0.0, lo.y() + 0.045 * height, hi.z()),
               down, &right);
  REQUIRE(left >= 3);
  REQUIRE(right >= 3);
  const std::string where = describe_self_intersections(body, model->faces());
  INFO(where);
  REQUIRE_FALSE(where.empty());
  CHECK_THAT(where, Catch::Contains(" more around ("));
  // The first place's centre is on one foot, about 0.1 m off the midline, the other on the other.
  const std::size_t open = where.find("around (");
  const double first_x = std::stod(where.substr(open + 8));
  const std::size_t more = where.find("more around (");
  const double second_x = std::stod(where.substr(more + 13));
  CHECK(std::abs(first_x) > 0.05);
  CHECK(first_x * second_x < 0);
}

TEST_CASE("a heavy short human-rig body whose arms pass through its sides under the sleeves is refused", "[barrier][bodies]") {
  // An outside check: a woman of 1.40 m at BMI 55 on the human rig crosses
  // herself at both armpits (12 face pairs, 2.6-3.1 cm from the sleeve on the
  // mean body, beyond the faces closest to the cloth); drape body warned of
  // it and the human scene draped her, p = 0.
  test::TempDir dir;
  std::string out;
  const int code = test::run_drape("simulate " + (test::source_dir() / "graphs/scenes/tshirt_coarse_human.yaml").string() +
                                       " --bmi 55 --height 1.4 --sex 0 --threads 1 --out " + (dir / "g.obj").string(),
                                   out);
  INFO(out);
  CHECK(code == 2);
  CHECK_THAT(out, Catch::Contains("the body intersects itself where the garment lies: 12 pairs of its faces cross"));
  CHECK_FALSE(std::filesystem::exists(dir / "g.obj"));
}
