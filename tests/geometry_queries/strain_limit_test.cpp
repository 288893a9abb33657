// limit_strain (Provot's strain limiting) and material_edge_lengths, checked
// against lengths worked out by hand: no edge beyond its limit afterwards, the
// mesh's centroid where it was (every shortening moves its two ends by equal
// and opposite steps), nothing moved where nothing was too long.
#include <drape/errors.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/strain_limit.hpp>

#include <catch2/catch.hpp>

#include <cmath>

using namespace drape;
using namespace drape::geometry;

namespace {

// An n x n grid of unit squares in the plane z = 0, two triangles each.
Eigen::MatrixX3i limit_sheet_faces(int n) {
  Eigen::MatrixX3i f(2 * (n - 1) * (n - 1), 3);
  int k = 0;
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const int a = i * n + j, b = a + 1, c = a + n, d = c + 1;
      f.row(k++) << a, b, d;
      f.row(k++) << a, d, c;
    }
  return f;
}

Eigen::MatrixX3d limit_sheet_vertices(int n) {
  Eigen::MatrixX3d x(n * n, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) x.row(i * n + j) << j, i, 0.0;
  return x;
}

double limit_test_strain(const Eigen::MatrixX3d& x, const std::vector<std::array<int, 2>>& edges, const std::vector<double>& rest) {
  double worst = -1;
  for (std::size_t e = 0; e < edges.size(); ++e)
    worst = std::max(worst, (x.row(edges[e][0]) - x.row(edges[e][1])).norm() / rest[e] - 1.0);
  return worst;
}

}  // namespace

TEST_CASE("limit_strain shortens a chain's long edge and hands the excess along", "[strain_limit]") {
  // Four vertices on a line, rest 1 apart, the middle edge pulled to 3.
  Eigen::MatrixX3d x(4, 3);
  x << 0, 0, 0, 1, 0, 0, 4, 0, 0, 5, 0, 0;
  const std::vector<std::array<int, 2>> edges{{0, 1}, {1, 2}, {2, 3}};
  const std::vector<double> rest{1, 1, 1};
  const Eigen::RowVector3d centroid = x.colwise().mean();
  const StrainLimitReport r = limit_strain(x, edges, rest, 0.5);
  CHECK(r.worst_before == Approx(2.0));  // 3 / 1 - 1
  CHECK(r.worst_after <= 0.5 + 1e-9);
  CHECK(limit_test_strain(x, edges, rest) <= 0.5 + 1e-9);
  CHECK(r.shortened >= 1);
  // Symmetric moves: the centroid stays; the line stays a line, in order.
  CHECK((x.colwise().mean() - centroid).norm() < 1e-12);
  CHECK(x.col(1).cwiseAbs().maxCoeff() == 0.0);
  CHECK(x.col(2).cwiseAbs().maxCoeff() == 0.0);
  CHECK((x(1, 0) < x(2, 0) && x(0, 0) < x(1, 0) && x(2, 0) < x(3, 0)));
  // The first sweep shortens the middle edge by 1.5 (0.75 off each end), which
  // stretches its neighbours to 1.75; the next shortens them, and so on: the
  // whole chain ends within 3 (1.5) = 4.5 of length, from 5.
  CHECK(x(3, 0) - x(0, 0) <= 4.5 + 1e-9);
}

TEST_CASE("limit_strain flags the vertices it moves, and only those", "[strain_limit]") {
  // Two chains apart: 0-1-2 pulled (the middle edge at 3), 3-4 within its limit.
  Eigen::MatrixX3d x(5, 3);
  x << 0, 0, 0, 3, 0, 0, 4, 0, 0, 10, 0, 0, 11, 0, 0;
  const Eigen::MatrixX3d before = x;
  std::vector<char> moved(5, 0);
  limit_strain(x, {{0, 1}, {1, 2}, {3, 4}}, {1, 1, 1}, 0.5, 50, 0.0, &moved);
  for (int v = 0; v < 5; ++v) {
    INFO("vertex " << v);
    CHECK(bool(moved[static_cast<std::size_t>(v)]) == (x.row(v) != before.row(v)));
  }
  CHECK(std::vector<char>(moved.begin() + 3, moved.end()) == std::vector<char>{0, 0});
  std::vector<char> wrong(4, 0);
  CHECK_THROWS_WITH(limit_strain(x, {{0, 1}}, {1}, 0.5, 50, 0.0, &wrong), Catch::Contains("4 moved flags for 5 vertices"));
}

TEST_CASE("limit_strain leaves a mesh within the limit as it is", "[strain_limit]") {
  Eigen::MatrixX3d x = limit_sheet_vertices(6);
  x.col(2) = 0.3 * x.col(0).array().sin();  // a wave: edges up to 1.04 long
  const Eigen::MatrixX3d before = x;
  const auto edges = edge_list(limit_sheet_faces(6));
  const std::vector<double> rest(edges.size(), 1.0);
  std::vector<double> diagonal_rest = rest;
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (std::abs(edges[e][1] - edges[e][0]) == 7) diagonal_rest[e] = std::sqrt(2.0);
  const StrainLimitReport r = limit_strain(x, edges, diagonal_rest, 0.1);
  CHECK(x == before);
  CHECK(r.shortened == 0);
  CHECK(r.sweeps == 1);
  CHECK(r.worst_after == r.worst_before);
  CHECK(r.worst_before == Approx(limit_test_strain(before, edges, diagonal_rest)));
}

TEST_CASE("limit_strain on a grid with a vertex torn a metre away: every edge back within its limit", "[strain_limit]") {
  const int n = 12;
  Eigen::MatrixX3d x = limit_sheet_vertices(n);
  const auto edges = edge_list(limit_sheet_faces(n));
  std::vector<double> rest(edges.size(), 1.0);
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (std::abs(edges[e][1] - edges[e][0]) == n + 1) rest[e] = std::sqrt(2.0);
  const int torn = 5 * n + 6;
  x.row(torn) += Eigen::RowVector3d(0.3, -0.2, 100.0);  // a hundred rest lengths off the sheet
  const Eigen::RowVector3d centroid = x.colwise().mean();
  SECTION("exactly") {
    const StrainLimitReport r = limit_strain(x, edges, rest, 0.2, 10000);
    CHECK(r.worst_before > 90.0);
    CHECK(r.worst_after <= 0.2 + 1e-9);
    CHECK(limit_test_strain(x, edges, rest) <= 0.2 + 1e-9);
  }
  SECTION("with slack: within limit + slack, in fewer sweeps") {
    Eigen::MatrixX3d y = x;
    const StrainLimitReport exact = limit_strain(y, edges, rest, 0.2, 10000);
    const StrainLimitReport r = limit_strain(x, edges, rest, 0.2, 10000, 0.05);
    CHECK(r.worst_after <= 0.25 + 1e-9);
    CHECK(r.sweeps < exact.sweeps);
  }
  CHECK(x.allFinite());
  CHECK((x.colwise().mean() - centroid).norm() < 1e-9);
}

TEST_CASE("limit_strain stops at its sweeps and says how far it got", "[strain_limit]") {
  Eigen::MatrixX3d x = limit_sheet_vertices(8);
  const auto edges = edge_list(limit_sheet_faces(8));
  std::vector<double> rest(edges.size(), 1.0);
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (std::abs(edges[e][1] - edges[e][0]) == 9) rest[e] = std::sqrt(2.0);
  x.row(27).z() += 50.0;
  const StrainLimitReport r = limit_strain(x, edges, rest, 0.1, 2);
  CHECK(r.sweeps == 2);
  CHECK(r.worst_after == Approx(limit_test_strain(x, edges, rest)));
  CHECK(r.worst_after > 0.1);  // two sweeps do not undo a 50 m tear
  CHECK(r.worst_after < r.worst_before);
}

TEST_CASE("limit_strain refuses what it cannot measure", "[strain_limit]") {
  Eigen::MatrixX3d x = limit_sheet_vertices(3);
  const auto edges = edge_list(limit_sheet_faces(3));
  std::vector<double> rest(edges.size(), 1.0);
  CHECK_THROWS_WITH(limit_strain(x, edges, std::vector<double>(edges.size() - 1, 1.0), 0.1), Catch::Contains("rest lengths for"));
  rest[3] = 0.0;
  CHECK_THROWS_WITH(limit_strain(x, edges, rest, 0.1), Catch::Contains("edge 3 has rest length"));
  rest[3] = 1.0;
  CHECK_THROWS_AS(limit_strain(x, edges, rest, -0.1), Error);
  CHECK_THROWS_AS(limit_strain(x, edges, rest, 0.1, 0), Error);
  CHECK_THROWS_AS(limit_strain(x, edges, rest, 0.1, 5, -1.0), Error);
  CHECK_THROWS_WITH(limit_strain(x, {{0, 9}}, {1.0}, 0.1), Catch::Contains("names vertex 9"));
}

TEST_CASE("material_edge_lengths: an edge's length in the pattern, averaged over a seam's two sides", "[strain_limit]") {
  // Two triangles sharing the edge (1, 2); each has its own UV corners, the
  // seam's sides 1.0 and 1.2 long in them.
  Mesh m;
  m.vertices.resize(4, 3);
  m.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0;
  m.faces.resize(2, 3);
  m.faces << 0, 1, 2, 1, 3, 2;
  m.uv.resize(6, 2);
  m.uv << 0, 0, 1, 0, 1, 1,   // face 0: (1, 2) from (1, 0) to (1, 1): 1.0
      5, 0, 6, 0, 5, 1.2;     // face 1: (1, 2) from (5, 0) to (5, 1.2): 1.2
  m.uv_faces.resize(2, 3);
  m.uv_faces << 0, 1, 2, 3, 4, 5;
  const auto edges = edge_list(m.faces);  // (0,1) (0,2) (1,2) (1,3) (2,3)
  REQUIRE(edges.size() == 5);
  const std::vector<double> l = material_edge_lengths(m, edges);
  CHECK(l[0] == Approx(1.0));              // (0, 1): uv 0 -> 1
  CHECK(l[1] == Approx(std::sqrt(2.0)));   // (0, 2): uv 0 -> 2
  CHECK(l[2] == Approx(1.1));              // (1, 2): 1.0 and 1.2
  CHECK(l[3] == Approx(1.0));              // (1, 3): uv 3 -> 4
  CHECK(l[4] == Approx(std::sqrt(1.0 + 1.44)));  // (2, 3): uv 5 -> 4
  CHECK_THROWS_WITH(material_edge_lengths(m, {{0, 3}}), Catch::Contains("no face holds edge (0, 3)"));
  Mesh bare = m;
  bare.uv.resize(0, 2);
  CHECK_THROWS_AS(material_edge_lengths(bare, edges), ConfigError);
}
