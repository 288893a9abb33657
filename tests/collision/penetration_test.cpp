// The framework helpers the collision energy and the seed's metrics use:
// penetration_ratio (the fraction of garment vertices inside the body) and
// vertex_areas (lumped material-space areas).
#include "collision_test_util.hpp"

#include <drape/energy.hpp>
#include <drape/geometry/penetration.hpp>
#include <drape/geometry/vertex_areas.hpp>

#include <catch2/catch.hpp>

using namespace drape;
using namespace drape::test;
using geometry::penetration_ratio;

namespace {

// The unit cube [0, 1]^3, 12 triangles counter-clockwise seen from outside.
geometry::BodySurface unit_cube() {
  Eigen::MatrixX3d v(8, 3);
  for (int i = 0; i < 8; ++i) v.row(i) << (i & 1), (i >> 1) & 1, (i >> 2) & 1;
  Eigen::MatrixX3i f(12, 3);
  f << 0, 2, 1, 1, 2, 3,  // z = 0
      4, 5, 6, 5, 7, 6,   // z = 1
      0, 1, 4, 1, 5, 4,   // y = 0
      2, 6, 3, 3, 6, 7,   // y = 1
      0, 4, 2, 2, 4, 6,   // x = 0
      1, 3, 5, 3, 7, 5;   // x = 1
  return geometry::BodySurface(v, f);
}

}  // namespace

TEST_CASE("penetration_ratio counts the vertices deeper inside than the tolerance", "[collision][penetration]") {
  const geometry::BodySurface cube = unit_cube();
  REQUIRE(cube.locate({0.5, 0.5, 0.5}).signed_distance == Approx(-0.5));  // the hand-built cube is outward
  Eigen::MatrixX3d x(5, 3);
  x << 0.5, 0.5, 0.5,   // centre: 0.5 deep
      0.5, 0.5, 0.99,   // 1 cm under the top face
      0.2, 0.999, 0.3,  // 1 mm under the y = 1 face
      0.5, 0.5, 1.2,    // above the cube
      2.0, -1.0, 3.0;   // far away
  CHECK(penetration_ratio(cube, x) == 3.0 / 5);
  CHECK(penetration_ratio(cube, x, 0.0005) == 3.0 / 5);
  CHECK(penetration_ratio(cube, x, 0.005) == 2.0 / 5);
  CHECK(penetration_ratio(cube, x, 0.02) == 1.0 / 5);
  CHECK(penetration_ratio(cube, x, 0.6) == 0.0);
  CHECK(penetration_ratio(cube, x.bottomRows(2)) == 0.0);
  CHECK(penetration_ratio(cube, x.topRows(3)) == 1.0);
  // On the surface is not inside.
  Eigen::MatrixX3d on(1, 3);
  on << 0.5, 0.5, 1.0;
  CHECK(penetration_ratio(cube, on) == 0.0);
}

TEST_CASE("penetration_ratio rejects empty garments, bad tolerances and non-finite vertices", "[collision][penetration]") {
  const geometry::BodySurface cube = unit_cube();
  CHECK_THAT(message_of([&] { penetration_ratio(cube, Eigen::MatrixX3d(0, 3)); }), Catch::Contains("no vertices"));
  Eigen::MatrixX3d x = Eigen::MatrixX3d::Constant(3, 3, 0.5);
  CHECK_THAT(message_of([&] { penetration_ratio(cube, x, -0.1); }), Catch::Contains("tolerance"));
  CHECK_THAT(message_of([&] { penetration_ratio(cube, x, std::nan("")); }), Catch::Contains("tolerance"));
  x(2, 0) = std::numeric_limits<double>::infinity();
  CHECK_THAT(message_of([&] { penetration_ratio(cube, x); }), Catch::Contains("vertex 2"));
}

TEST_CASE("penetration_ratio agrees with the sphere's analytic inside test", "[collision][penetration]") {
  const geometry::BodySurface sphere = sphere_body(4, 1.0);
  // Radii well clear of the polyhedron's gap to the true sphere (< 0.5 %).
  Eigen::MatrixX3d x(200, 3);
  std::mt19937_64 rng(2);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> r(0.2, 1.8);
  int inside = 0;
  for (int i = 0; i < 200; ++i) {
    double radius = r(rng);
    if (std::abs(radius - 1) < 0.01) radius = 0.5;
    inside += radius < 1;
    x.row(i) = radius * Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
  }
  CHECK(penetration_ratio(sphere, x) == static_cast<double>(inside) / 200);
}

TEST_CASE("vertex_areas lumps a third of each face's material-space area to its corners", "[collision][areas]") {
  // 3 x 3 grid, 0.1 m apart: 8 faces of 0.005 m^2.
  const auto garment = grid_garment(3, 0.1);
  const Eigen::VectorXd a = geometry::vertex_areas(*garment);
  REQUIRE(a.size() == 9);
  CHECK(a.sum() == Approx(0.04).epsilon(1e-12));
  const double third = 0.005 / 3;
  // Faces (a, b, d), (a, d, c) per cell: corner 0 on 2 faces, 1 on 3, 2 on 1, 4 (centre) on 6.
  CHECK(a[0] == Approx(2 * third));
  CHECK(a[1] == Approx(3 * third));
  CHECK(a[2] == Approx(1 * third));
  CHECK(a[4] == Approx(6 * third));
  CHECK(a[8] == Approx(2 * third));
  // Material space, not the 3D state: crumpling the garment changes nothing.
  auto crumpled = *garment;
  crumpled.mesh.vertices = Eigen::MatrixX3d::Random(9, 3);
  CHECK(geometry::vertex_areas(crumpled) == a);
  // Halving the UV layout quarters the areas (UVs are in meters).
  auto small = *garment;
  small.mesh.uv *= 0.5;
  CHECK(geometry::vertex_areas(small).isApprox(a / 4, 1e-14));
}

TEST_CASE("vertex_areas uses UV faces across seams and refuses garments without UVs", "[collision][areas]") {
  // Two triangles sharing an edge in 3D but cut apart in UV (a seam): each UV
  // triangle has its own corners, the areas still land on the shared vertices.
  Garment g;
  g.materials.push_back(Material{});
  g.mesh.vertices.resize(4, 3);
  g.mesh.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0;
  g.mesh.faces.resize(2, 3);
  g.mesh.faces << 0, 1, 3, 0, 3, 2;
  g.mesh.uv.resize(6, 2);
  g.mesh.uv << 0, 0, 0.2, 0, 0.2, 0.1,  // first face: 0.01 m^2
      5, 5, 5.3, 5.3, 5, 5.3;           // second face, elsewhere: 0.045 m^2
  g.mesh.uv_faces.resize(2, 3);
  g.mesh.uv_faces << 0, 1, 2, 3, 4, 5;
  const Eigen::VectorXd a = geometry::vertex_areas(g);
  CHECK(a[0] == Approx((0.01 + 0.045) / 3));
  CHECK(a[1] == Approx(0.01 / 3));
  CHECK(a[2] == Approx(0.045 / 3));
  CHECK(a[3] == Approx((0.01 + 0.045) / 3));

  Garment bad = g;
  bad.mesh.uv_faces(1, 2) = 6;
  CHECK_THAT(message_of([&] { geometry::vertex_areas(bad); }), Catch::Contains("face 1") && Catch::Contains("UV 6"));
  Garment flat = g;
  flat.mesh.uv.resize(0, 2);
  flat.mesh.uv_faces.resize(0, 3);
  CHECK_THROWS_AS(geometry::vertex_areas(flat), ConfigError);
}
