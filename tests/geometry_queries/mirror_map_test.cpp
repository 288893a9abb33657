// A mesh's mirror map (geometry::mirror_map) on meshes whose mirror is known
// by construction: a symmetric grid numbered without symmetry maps each
// vertex onto its twin, and a strip whose reflection falls inside faces
// carries an affine drape exactly (barycentric weights reproduce affine maps).
#include <catch2/catch.hpp>

#include <drape/geometry/mirror_map.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

namespace {

using namespace drape;

// A (cols x rows) grid over x in [-1, 1], y in [0, 1], on z = 0.3 x^2 (a
// trough symmetric about x = 0), its vertices numbered in a shuffled order.
struct Grid {
  Eigen::MatrixX3d vertices;
  Eigen::MatrixX3i faces;
  std::vector<int> slot;  // the shuffled number of grid point (i, j): slot[j * cols + i]
};

Grid trough(int cols, int rows, std::uint32_t seed) {
  Grid g;
  const int n = cols * rows;
  g.slot.resize(static_cast<std::size_t>(n));
  std::iota(g.slot.begin(), g.slot.end(), 0);
  std::mt19937 rng(seed);
  std::shuffle(g.slot.begin(), g.slot.end(), rng);
  g.vertices.resize(n, 3);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      const double x = -1.0 + 2.0 * i / (cols - 1), y = static_cast<double>(j) / (rows - 1);
      g.vertices.row(g.slot[static_cast<std::size_t>(j * cols + i)]) << x, y, 0.3 * x * x;
    }
  std::vector<Eigen::Vector3i> faces;
  for (int j = 0; j + 1 < rows; ++j)
    for (int i = 0; i + 1 < cols; ++i) {
      const auto at = [&](int a, int b) { return g.slot[static_cast<std::size_t>(b * cols + a)]; };
      faces.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      faces.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  g.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) g.faces.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  return g;
}

}  // namespace

TEST_CASE("mirror map: a symmetric grid numbered at random maps each vertex onto its twin", "[geometry][mirror]") {
  const int cols = 9, rows = 5;
  const Grid g = trough(cols, rows, 7);
  const geometry::MirrorMap map = geometry::mirror_map(g.vertices, g.faces);
  CHECK(map.distance.maxCoeff() < 1e-12);
  // A drape: each vertex moved by a function of where it is; its mirror read
  // through the map is, at the twin's slot, the reflection of the twin's value.
  Eigen::MatrixX3d drape(g.vertices.rows(), 3);
  for (Eigen::Index v = 0; v < g.vertices.rows(); ++v) {
    const Eigen::RowVector3d p = g.vertices.row(v);
    drape.row(v) << p[0] + 0.1 * std::sin(3 * p[0]) + 0.05 * p[1], p[1] - 0.2 * p[0] * p[0], p[2] + 0.02 * p[0];
  }
  const Eigen::MatrixX3d m = geometry::mirrored(map, drape);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      const int v = g.slot[static_cast<std::size_t>(j * cols + i)];
      const int twin = g.slot[static_cast<std::size_t>(j * cols + (cols - 1 - i))];
      const Eigen::RowVector3d expected(-drape(twin, 0), drape(twin, 1), drape(twin, 2));
      CHECK((m.row(v) - expected).norm() < 1e-12);
    }
}

TEST_CASE("mirror map: a reflection inside faces carries an affine drape exactly", "[geometry][mirror]") {
  // A flat strip over x in [-1, 1] whose columns are not symmetric: x = -1,
  // -0.55, -0.1, 0.35, 0.8, 1 (each reflected vertex but the ends falls
  // inside a face or on an edge).
  const std::vector<double> xs = {-1.0, -0.55, -0.1, 0.35, 0.8, 1.0};
  const int cols = static_cast<int>(xs.size());
  Eigen::MatrixX3d v(2 * cols, 3);
  for (int i = 0; i < cols; ++i) {
    v.row(i) << xs[static_cast<std::size_t>(i)], 0.0, 0.0;
    v.row(cols + i) << xs[static_cast<std::size_t>(i)], 1.0, 0.0;
  }
  Eigen::MatrixX3i f(2 * (cols - 1), 3);
  for (int i = 0; i + 1 < cols; ++i) {
    f.row(2 * i) << i, i + 1, cols + i + 1;
    f.row(2 * i + 1) << i, cols + i + 1, cols + i;
  }
  const geometry::MirrorMap map = geometry::mirror_map(v, f);
  CHECK(map.distance.maxCoeff() < 1e-12);
  CHECK((map.weights.rowwise().sum().array() - 1.0).abs().maxCoeff() < 1e-12);
  // x = A v + t: the mirror of vertex i is R (A (R v_i) + t), R = diag(-1, 1, 1).
  Eigen::Matrix3d a;
  a << 1.1, 0.2, -0.3, 0.4, 0.9, 0.1, -0.2, 0.3, 1.2;
  const Eigen::RowVector3d t(0.05, -0.02, 0.3);
  const Eigen::MatrixX3d drape = (v * a.transpose()).rowwise() + t;
  const Eigen::MatrixX3d m = geometry::mirrored(map, drape);
  const Eigen::Vector3d r(-1, 1, 1);
  for (Eigen::Index i = 0; i < v.rows(); ++i) {
    const Eigen::Vector3d reflected = r.cwiseProduct(v.row(i).transpose());
    const Eigen::Vector3d expected = r.cwiseProduct(a * reflected + t.transpose());
    CHECK((m.row(i).transpose() - expected).norm() < 1e-12);
  }
}

TEST_CASE("mirror map: the adjoint carries a gradient back (sum g . M x = sum M*g . x)", "[geometry][mirror]") {
  const Grid g = trough(7, 4, 3);
  // Moved off the grid so that the reflections fall inside faces, not on vertices.
  Eigen::MatrixX3d v = g.vertices;
  for (Eigen::Index i = 0; i < v.rows(); ++i) v(i, 0) += 0.03 * std::sin(5.0 * i);
  const geometry::MirrorMap map = geometry::mirror_map(v, g.faces);
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  Eigen::MatrixX3d x(v.rows(), 3), grad(v.rows(), 3);
  for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = normal(rng), grad.data()[i] = normal(rng);
  const double lhs = (grad.array() * geometry::mirrored(map, x).array()).sum();
  const double rhs = (geometry::mirrored_adjoint(map, grad, v.rows()).array() * x.array()).sum();
  CHECK(lhs == Approx(rhs).epsilon(1e-12));
  // By finite differences on one coordinate.
  const double h = 1e-6;
  Eigen::MatrixX3d xp = x, xm = x;
  xp(5, 1) += h, xm(5, 1) -= h;
  const double fd = ((grad.array() * geometry::mirrored(map, xp).array()).sum() -
                     (grad.array() * geometry::mirrored(map, xm).array()).sum()) / (2 * h);
  CHECK(fd == Approx(geometry::mirrored_adjoint(map, grad, v.rows())(5, 1)).epsilon(1e-6));
  CHECK_THROWS_WITH(geometry::mirrored_adjoint(map, grad.topRows(3), v.rows()), Catch::Contains("3 rows"));
}

TEST_CASE("mirror map: bad input", "[geometry][mirror]") {
  CHECK_THROWS_WITH(geometry::mirror_map(Eigen::MatrixX3d::Zero(3, 3), Eigen::MatrixX3i(0, 3)), Catch::Contains("no faces"));
  const Grid g = trough(3, 3, 1);
  const geometry::MirrorMap map = geometry::mirror_map(g.vertices, g.faces);
  CHECK_THROWS_WITH(geometry::mirrored(map, Eigen::MatrixX3d::Zero(4, 3)), Catch::Contains("9 vertices"));
}
