// The barrier's start check (scene/separated_start.hpp) on a sphere for a
// body: a body shrunk past its thickness turns inside out, and a garment the
// shrunk body does not enclose is separated from it, as the winding number
// says and the distance's sign did not; one it does enclose is not; a body
// with a hole falls back on the sign; and the least shrink that frees a
// garment pushed into the body is chosen.
#include <drape/geometry/closest_point.hpp>

#include <catch2/catch.hpp>

#include "../../framework/src/scene/separated_start.hpp"
#include "test_support.hpp"

#include <cmath>
#include <vector>

using namespace drape;

namespace {

// A small triangle around `centre`, facing +x: the garment.
void small_triangle(const Eigen::Vector3d& centre, Eigen::MatrixX3d& x, Eigen::MatrixX3i& faces) {
  x.resize(3, 3);
  x << 0, 0.01, 0, 0, -0.005, 0.008, 0, -0.005, -0.008;
  x.rowwise() += centre.transpose();
  faces.resize(1, 3);
  faces << 0, 1, 2;
}

// A ring of n points of radius r at height y, as a closed band of triangles
// one centimetre tall: a hem.
void band(double r, double y, int n, Eigen::MatrixX3d& x, Eigen::MatrixX3i& faces) {
  x.resize(2 * n, 3);
  faces.resize(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    x.row(i) << r * std::cos(a), y - 0.005, r * std::sin(a);
    x.row(n + i) << r * std::cos(a), y + 0.005, r * std::sin(a);
    const int j = (i + 1) % n;
    faces.row(2 * i) << i, j, n + j;
    faces.row(2 * i + 1) << i, n + j, n + i;
  }
}

}  // namespace

TEST_CASE("separated start: a body shrunk inside out does not enclose what lies beyond it", "[barrier][start]") {
  const Mesh ball = test::uv_sphere(0.1, 16, 24);
  const geometry::BodySurface sphere(ball.vertices, ball.faces);
  // 15 cm along the inward normals: a sphere of radius 5 cm, inside out.
  const Eigen::MatrixX3d shrunk = ball.vertices - 0.15 * sphere.vertex_normals();
  const geometry::BodySurface inverted(shrunk, ball.faces);
  Eigen::MatrixX3d x;
  Eigen::MatrixX3i faces;
  small_triangle(Eigen::Vector3d(0.08, 0.003, 0.002), x, faces);  // 3 cm beyond the small sphere
  CHECK(inverted.signed_distances(x).maxCoeff() < 0);  // the distance's sign calls it inside...
  CHECK(scene_detail::separation_problem(x, inverted, faces).empty());  // ...but nothing encloses it
  small_triangle(Eigen::Vector3d(0.01, 0.003, 0.002), x, faces);  // within the small sphere
  CHECK_THAT(scene_detail::separation_problem(x, inverted, faces), Catch::Contains("starts inside the body (3 garment vertices"));
}

TEST_CASE("separated start: a body with a hole is judged by the distance's sign", "[barrier][start]") {
  const Mesh ball = test::uv_sphere(0.1, 16, 24);
  // A hole where the sphere meets +x, where the winding number's first ray
  // from a point inside would leave through it and count nothing.
  std::vector<Eigen::Vector3i> kept;
  for (Eigen::Index f = 0; f < ball.faces.rows(); ++f) {
    Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) centroid += ball.vertices.row(ball.faces(f, k)).transpose() / 3;
    if (centroid.x() < 0.09) kept.push_back(ball.faces.row(f).transpose());
  }
  REQUIRE(kept.size() < static_cast<std::size_t>(ball.faces.rows()));
  Eigen::MatrixX3i open(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t i = 0; i < kept.size(); ++i) open.row(static_cast<Eigen::Index>(i)) = kept[i].transpose();
  const geometry::BodySurface body(ball.vertices, open);
  Eigen::MatrixX3d x;
  Eigen::MatrixX3i faces;
  small_triangle(Eigen::Vector3d(-0.05, 0.001, 0.002), x, faces);
  CHECK_THAT(scene_detail::separation_problem(x, body, faces), Catch::Contains("starts inside the body (3 garment vertices"));
  small_triangle(Eigen::Vector3d(-0.15, -0.03, 0.01), x, faces);
  CHECK(scene_detail::separation_problem(x, body, faces).empty());
}

TEST_CASE("separated start: the least shrink that frees a band pushed 2.5 cm into the body", "[barrier][start]") {
  const Mesh ball = test::uv_sphere(0.1, 32, 48);
  Eigen::MatrixX3d x;
  Eigen::MatrixX3i faces;
  band(0.075, 0.0, 48, x, faces);  // 2.5 cm inside the sphere at its equator
  double shrink = -1;
  const Eigen::MatrixX3d start = scene_detail::separated_start_body(x, ball.vertices, ball.faces, faces, &shrink);
  CHECK(shrink == Approx(0.03));  // 2 cm is not enough, 3 cm is: the list is 0, 0.5, 1, 2, 3, 4, 6 cm
  CHECK(scene_detail::separation_problem(x, geometry::BodySurface(start, ball.faces), faces).empty());
  // A band 7 cm inside (3 cm from the centre) is beyond every shrink.
  band(0.03, 0.0, 48, x, faces);
  CHECK_THROWS_WITH(scene_detail::separated_start_body(x, ball.vertices, ball.faces, faces),
                    Catch::Contains("the garment starts inside the body (96 garment vertices") &&
                        Catch::Contains("a start body shrunk by up to 6 cm was tried too"));
  // A scene without morph steps tries no shrunk body, and says so, naming the setting.
  CHECK_THROWS_WITH(scene_detail::check_separated_start(x, geometry::BodySurface(ball.vertices, ball.faces), faces, false),
                    Catch::Contains("the garment starts inside the body") && Catch::Contains("morph_steps: 0") &&
                        !Catch::Contains("was tried too"));
}
