// A tape measure around a mesh (geometry::horizontal_girth): against the
// circumference of a sphere's and a cylinder's cross-sections computed by
// hand, a star-shaped prism whose tape spans its hollows, a second body beside
// the measured one, and a plane through a vertex.
#include <drape/geometry/closed_shapes.hpp>
#include <drape/geometry/girth.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace drape;
using namespace drape::geometry;

namespace {

// A closed prism of height 2 (y in [-1, 1]) over a polygon of n corners at
// radius r(k) around the origin; caps as fans from their centres.
Mesh prism(int n, double r_even, double r_odd) {
  Mesh m;
  m.vertices.resize(2 * n + 2, 3);
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n, r = k % 2 ? r_odd : r_even;
    m.vertices.row(k) << r * std::cos(a), -1.0, r * std::sin(a);
    m.vertices.row(n + k) << r * std::cos(a), 1.0, r * std::sin(a);
  }
  m.vertices.row(2 * n) << 0, -1, 0;
  m.vertices.row(2 * n + 1) << 0, 1, 0;
  m.faces.resize(4 * n, 3);
  for (int k = 0; k < n; ++k) {
    const int a = k, b = (k + 1) % n;
    m.faces.row(4 * k) << a, n + b, b;
    m.faces.row(4 * k + 1) << a, n + a, n + b;
    m.faces.row(4 * k + 2) << 2 * n, a, b;
    m.faces.row(4 * k + 3) << 2 * n + 1, n + b, n + a;
  }
  return m;
}

}  // namespace

TEST_CASE("girth: a regular prism's cross-section is its polygon's perimeter, tape and fabric alike", "[geometry][girth]") {
  const int n = 40;
  const double r = 0.3;
  const Mesh m = prism(n, r, r);
  const double perimeter = n * 2 * r * std::sin(M_PI / n);  // by hand: n chords of the circle
  for (const double y : {-0.5, 0.0, 0.9}) {
    const Girth g = horizontal_girth(m.vertices, m.faces, y, {0.0, 0.0});
    REQUIRE(g.found);
    CHECK(g.loops == 1);
    CHECK(g.length == Approx(perimeter).epsilon(1e-9));
    CHECK(g.tape == Approx(perimeter).epsilon(1e-9));
  }
  // Above the top: nothing to measure.
  CHECK_FALSE(horizontal_girth(m.vertices, m.faces, 1.5, {0.0, 0.0}).found);
  // Off-centre: the loop does not enclose the line.
  CHECK_FALSE(horizontal_girth(m.vertices, m.faces, 0.0, {1.0, 0.0}).found);
}

TEST_CASE("girth: the tape spans a star's hollows, the fabric follows them", "[geometry][girth]") {
  const int n = 12;
  const Mesh m = prism(n, 0.3, 0.15);  // a six-pointed star
  const Girth g = horizontal_girth(m.vertices, m.faces, 0.2, {0.0, 0.0});
  REQUIRE(g.found);
  // By hand: the tape is the hexagon of the points (side 0.3), the fabric the star's 12 edges.
  const double hexagon = 6 * 0.3;
  const double edge = std::sqrt(0.3 * 0.3 + 0.15 * 0.15 - 2 * 0.3 * 0.15 * std::cos(2 * M_PI / n));
  CHECK(g.tape == Approx(hexagon).epsilon(1e-9));
  CHECK(g.length == Approx(n * edge).epsilon(1e-9));
  CHECK(g.length > g.tape);
}

TEST_CASE("girth: the loop around the centre is measured, not an arm beside it: a plane through a vertex still cuts", "[geometry][girth]") {
  Mesh torso = prism(24, 0.2, 0.2);
  Mesh arm = prism(16, 0.05, 0.05);
  arm.vertices.col(0).array() += 0.4;  // beside the torso
  Mesh both;
  both.vertices.resize(torso.vertices.rows() + arm.vertices.rows(), 3);
  both.vertices << torso.vertices, arm.vertices;
  both.faces.resize(torso.faces.rows() + arm.faces.rows(), 3);
  both.faces << torso.faces, (arm.faces.array() + static_cast<int>(torso.vertices.rows())).matrix();
  const Girth g = horizontal_girth(both.vertices, both.faces, 0.0, {0.0, 0.0});
  REQUIRE(g.found);
  CHECK(g.loops == 2);
  CHECK(g.length == Approx(24 * 2 * 0.2 * std::sin(M_PI / 24)).epsilon(1e-9));
  // The plane y = -1 holds the bottom ring's vertices: nudged 1e-9 m up off them, it cuts the sides just above.
  const Girth top = horizontal_girth(torso.vertices, torso.faces, -1.0, {0.0, 0.0});
  CHECK(top.found);
  CHECK(top.length == Approx(24 * 2 * 0.2 * std::sin(M_PI / 24)).epsilon(1e-6));
}
