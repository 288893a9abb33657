// separate_layers (drape/garment_layers.hpp): the pieces of a garment fitted
// through each other are laid one outside the other; one piece is untouched.
#include "test_support.hpp"

#include <drape/garment_dressing.hpp>
#include <drape/garment_layers.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/surface_crossings.hpp>

#include <catch2/catch.hpp>

using namespace drape;

namespace {

// An n x n grid over x, y in [-h, h] at z = z0 + tilt * x, its vertices from `first` on.
void add_sheet(Garment& g, int n, double h, double z0, double tilt) {
  const int first = static_cast<int>(g.mesh.vertices.rows()), f0 = static_cast<int>(g.mesh.faces.rows());
  g.mesh.vertices.conservativeResize(first + n * n, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = -h + 2 * h * i / (n - 1.0), y = -h + 2 * h * j / (n - 1.0);
      g.mesh.vertices.row(first + i * n + j) << x, y, z0 + tilt * x;
    }
  g.mesh.faces.conservativeResize(f0 + 2 * (n - 1) * (n - 1), 3);
  int f = f0;
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const int a = first + i * n + j;
      g.mesh.faces.row(f++) << a, a + n, a + n + 1;
      g.mesh.faces.row(f++) << a, a + n + 1, a + 1;
    }
}

Eigen::MatrixX3i rows_of(const Eigen::MatrixX3i& faces, int first, int count) { return faces.middleRows(first, count); }

}  // namespace

TEST_CASE("garment layers: a sheet dipping under another is laid outside it", "[garments][dressing]") {
  // The body: a ball of 0.3 m in front of which two sheets hang, 4-5 cm off it.
  // The second sheet is tilted through the first (crossing it along x = -0.05).
  Mesh ball = test::uv_sphere(0.3, 30, 60);
  Garment g;
  add_sheet(g, 15, 0.1, 0.34, 0.0);
  add_sheet(g, 15, 0.1, 0.345, 0.1);
  const int half = static_cast<int>(g.mesh.faces.rows()) / 2, n = 225;
  REQUIRE(geometry::surface_crossings(g.mesh.vertices, rows_of(g.mesh.faces, half, half), g.mesh.vertices,
                                      rows_of(g.mesh.faces, 0, half)).total() > 0);
  const std::vector<int> pieces = garment_pieces(g.mesh.faces, static_cast<int>(g.mesh.vertices.rows()));
  CHECK(pieces.front() == 0);
  CHECK(pieces.back() == 1);

  const Eigen::MatrixX3d inner_before = g.mesh.vertices.topRows(n);
  DressOptions layers_only;  // the layering alone: dress's own untangling would smooth the crossing sheets about first
  layers_only.untangle_rounds = 0;
  const DressReport r = dress(g, ball, layers_only);
  CHECK(r.layers.pieces == 2);
  CHECK(r.layers.moved > 0);
  CHECK(r.layers.crossings == 0);
  // The inner sheet (closer to the ball) stays within 2 mm of its plane z =
  // 0.34 (dress's own untangling may smooth it a little); every vertex of the
  // outer one above it lies at least the margin in front of the inner
  // sheet's highest point, checked without the code's own distances.
  const double inner_top = g.mesh.vertices.topRows(n).col(2).maxCoeff();
  CHECK((g.mesh.vertices.topRows(n).col(2).array() - 0.34).abs().maxCoeff() < 0.002);
  CHECK(g.mesh.vertices.topRows(n) == inner_before);
  for (int v = n; v < 2 * n; ++v) {
    const Eigen::RowVector3d p = g.mesh.vertices.row(v);
    if (std::abs(p.x()) <= 0.09 && std::abs(p.y()) <= 0.09) CHECK(p.z() >= inner_top + LayerOptions{}.margin - 2e-3);
  }
  CHECK(geometry::surface_crossings(g.mesh.vertices, rows_of(g.mesh.faces, half, half), g.mesh.vertices,
                                    rows_of(g.mesh.faces, 0, half)).total() == 0);
}

TEST_CASE("garment layers: a garment of one piece and pieces apart are not touched", "[garments][dressing]") {
  Mesh ball = test::uv_sphere(0.3, 30, 60);
  Garment one;
  add_sheet(one, 10, 0.1, 0.36, 0.0);
  const Eigen::MatrixX3d before = one.mesh.vertices;
  CHECK(dress(one, ball).layers.pieces == 1);
  CHECK(one.mesh.vertices == before);
  Garment apart;  // two sheets 10 cm apart: farther than the reach
  add_sheet(apart, 10, 0.1, 0.36, 0.0);
  add_sheet(apart, 10, 0.1, 0.46, 0.0);
  const Eigen::MatrixX3d both = apart.mesh.vertices;
  const DressReport r = dress(apart, ball);
  CHECK(r.layers.pieces == 2);
  CHECK(r.layers.moved == 0);
  CHECK(apart.mesh.vertices == both);
}
