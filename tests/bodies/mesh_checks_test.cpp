// The framework's mesh checks on meshes whose answers are known by construction.
#include <catch2/catch.hpp>

#include <random>

#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/face_quality.hpp>
#include <drape/geometry/index_locality.hpp>
#include <drape/geometry/self_intersection.hpp>
#include <drape/geometry/topology.hpp>
#include <drape/geometry/volume.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace {

using namespace drape::geometry;

// An axis-aligned box [0,a]x[0,b]x[0,c], faces counter-clockwise seen from outside.
void box(double a, double b, double c, Eigen::MatrixX3d& v, Eigen::MatrixX3i& f) {
  v.resize(8, 3);
  for (int i = 0; i < 8; ++i) v.row(i) << (i & 1) * a, ((i >> 1) & 1) * b, ((i >> 2) & 1) * c;
  f.resize(12, 3);
  f << 0, 2, 1, 1, 2, 3,  // z = 0, normal -z
      4, 5, 6, 5, 7, 6,   // z = c
      0, 1, 4, 1, 5, 4,   // y = 0
      2, 6, 3, 3, 6, 7,   // y = b
      0, 4, 2, 2, 4, 6,   // x = 0
      1, 3, 5, 3, 7, 5;   // x = a
}

TEST_CASE("mesh volume and area of a box") {
  Eigen::MatrixX3d v;
  Eigen::MatrixX3i f;
  box(2, 3, 0.5, v, f);
  CHECK(mesh_volume(v, f) == Approx(3.0));
  CHECK(mesh_area(v, f) == Approx(2 * (6 + 1 + 1.5)));
  // Translation does not change a closed mesh's volume.
  v.rowwise() += Eigen::RowVector3d(5, -7, 11);
  CHECK(mesh_volume(v, f) == Approx(3.0));
}

TEST_CASE("topology of a closed box, an open box and a non-manifold pair") {
  Eigen::MatrixX3d v;
  Eigen::MatrixX3i f;
  box(1, 1, 1, v, f);
  auto t = check_topology(f, 8);
  CHECK(t.closed_manifold());
  CHECK(t.euler_characteristic == 2);
  CHECK(edge_list(f).size() == 18);
  CHECK(vertex_neighbours(f, 8)[0] == std::vector<int>{1, 2, 4});

  const Eigen::MatrixX3i open = f.bottomRows(10);  // drop the z = 0 side
  t = check_topology(open, 8);
  CHECK(t.boundary_edges == 4);
  CHECK(t.boundary_loops == 1);
  CHECK(!t.watertight());
  CHECK(t.manifold());

  Eigen::MatrixX3i flipped = f;
  flipped.row(0) << 0, 1, 2;
  CHECK(check_topology(flipped, 8).misoriented_edges == 3);

  // Two boxes touching at one corner vertex: a non-manifold vertex.
  Eigen::MatrixX3i two(24, 3);
  two << f, (f.array() + 7).matrix();  // the second box's vertex 0 is the first's vertex 7
  t = check_topology(two, 15);
  CHECK(t.nonmanifold_vertices == 1);
  CHECK(t.nonmanifold_edges == 0);
  // A fin: a third face on an edge.
  Eigen::MatrixX3i fin(13, 3);
  fin << f, Eigen::RowVector3i(0, 1, 7);
  CHECK(check_topology(fin, 8).nonmanifold_edges == 1);
  CHECK(check_topology(fin, 8).first_nonmanifold_edge == std::array<int, 2>{0, 1});  // the fin's edge, named
  CHECK(t.first_nonmanifold_edge == std::array<int, 2>{-1, -1});
}

TEST_CASE("vertex adjacency of an edge list: a box's neighbours by hand, and vertex_neighbours' lists") {
  Eigen::MatrixX3d v;
  Eigen::MatrixX3i f;
  box(1, 1, 1, v, f);
  const int n = static_cast<int>(v.rows());
  const VertexAdjacency adjacency = vertex_adjacency(edge_list(f), n);
  REQUIRE(adjacency.start.size() == static_cast<std::size_t>(n) + 1);
  CHECK(adjacency.start.back() == 2 * 18);  // 12 box edges and 6 face diagonals
  const auto lists = vertex_neighbours(f, n);
  for (int i = 0; i < n; ++i) {
    std::vector<int> mine(adjacency.neighbours.begin() + adjacency.start[i], adjacency.neighbours.begin() + adjacency.start[i + 1]);
    std::sort(mine.begin(), mine.end());
    CHECK(mine == lists[static_cast<std::size_t>(i)]);
  }
  // A corner of a triangulated cube meets its 3 edges and 0 to 3 diagonals: 3 to 6 neighbours.
  for (int i = 0; i < n; ++i) CHECK((adjacency.start[i + 1] - adjacency.start[i] >= 3 && adjacency.start[i + 1] - adjacency.start[i] <= 6));
  // A vertex no edge touches has none.
  const VertexAdjacency lone = vertex_adjacency({{0, 1}}, 3);
  CHECK(lone.start == std::vector<int>{0, 1, 2, 2});
  CHECK(lone.neighbours == std::vector<int>{1, 0});
}

TEST_CASE("face neighbours across each edge") {
  Eigen::MatrixX3d v;
  Eigen::MatrixX3i f;
  box(1, 1, 1, v, f);
  const auto across = face_neighbours(f);
  REQUIRE(across.size() == 12);
  // Face 0 (0, 2, 1): edge 0-2 borders face 8 (x = 0), 2-1 the diagonal of
  // the z = 0 side (face 1), 1-0 face 4 (y = 0).
  CHECK(across[0] == std::array<int, 3>{8, 1, 4});
  // Symmetric, and each neighbour really shares the edge.
  for (int g = 0; g < 12; ++g)
    for (int k = 0; k < 3; ++k) {
      const int h = across[static_cast<std::size_t>(g)][static_cast<std::size_t>(k)];
      REQUIRE(h >= 0);
      const auto& back = across[static_cast<std::size_t>(h)];
      CHECK(std::count(back.begin(), back.end(), g) == 1);
      const int a = f(g, k), b = f(g, (k + 1) % 3);
      CHECK(((f.row(h).array() == a).any() && (f.row(h).array() == b).any()));
    }
  // An open box has no neighbour across its rim; a fin (a third face on an
  // edge) leaves that edge without a single neighbour.
  const Eigen::MatrixX3i open = f.bottomRows(10);
  int rim = 0;
  for (const auto& n : face_neighbours(open)) rim += static_cast<int>(std::count(n.begin(), n.end(), -1));
  CHECK(rim == 4);
  Eigen::MatrixX3i fin(13, 3);
  fin << f, Eigen::RowVector3i(0, 1, 7);
  CHECK(face_neighbours(fin)[12][0] == -1);
  CHECK(face_neighbours(fin)[0][2] == -1);
}

TEST_CASE("degenerate, inverted and folded faces") {
  Eigen::MatrixX3d v(4, 3);
  v << 0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0;
  Eigen::MatrixX3i f(2, 3);
  f << 0, 1, 2, 0, 3, 1;  // the second is collinear
  CHECK(degenerate_faces(v, f, 1e-12, 0.01) == std::vector<int>{1});
  Eigen::MatrixX3d up(2, 3);
  up << 0, 0, 1, 0, 0, 1;
  CHECK(inverted_faces(v, f.topRows(1), up.topRows(1)).empty());
  CHECK(inverted_faces(v, f.topRows(1), -up.topRows(1)) == std::vector<int>{0});

  // Two triangles on one edge: flat, then folded onto each other.
  Eigen::MatrixX3d w(4, 3);
  w << 0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0;
  Eigen::MatrixX3i g(2, 3);
  g << 0, 1, 2, 1, 0, 3;
  CHECK(folded_edges(w, g, 0.5 * M_PI).empty());
  w.row(3) << 0.5, 0.9, 0.01;  // folded over the first triangle
  CHECK(folded_edges(w, g, 0.5 * M_PI).size() == 1);
}

TEST_CASE("triangle-triangle intersection") {
  using V = Eigen::Vector3d;
  const V a0(0, 0, 0), a1(1, 0, 0), a2(0, 1, 0);
  CHECK(triangles_intersect(a0, a1, a2, V(0.2, 0.2, -1), V(0.2, 0.2, 1), V(0.3, 0.3, 1)));   // pierces
  CHECK(!triangles_intersect(a0, a1, a2, V(2, 2, -1), V(2, 2, 1), V(3, 3, 1)));               // beside
  CHECK(!triangles_intersect(a0, a1, a2, V(0, 0, 0.1), V(1, 0, 0.1), V(0, 1, 0.1)));          // parallel above
  CHECK(triangles_intersect(a0, a1, a2, V(0.1, 0.1, 0), V(0.5, 0.1, 0), V(0.1, 0.5, 0)));     // coplanar, inside
  CHECK(!triangles_intersect(a0, a1, a2, V(1, 1, 0), V(2, 1, 0), V(1, 2, 0)));                // coplanar, apart
  CHECK(triangles_intersect(a0, a1, a2, V(-0.5, 0.2, 0.5), V(1.5, 0.2, 0.5), V(0.5, 0.2, -0.5)));  // edge through
}

TEST_CASE("self-intersections of a mesh") {
  Eigen::MatrixX3d v;
  Eigen::MatrixX3i f;
  box(1, 1, 1, v, f);
  CHECK(self_intersections(v, f).empty());
  // A second box pushed halfway into the first: its faces cross the first's.
  Eigen::MatrixX3d v2(16, 3);
  v2 << v, (v.rowwise() + Eigen::RowVector3d(0.5, 0.3, 0.2));
  Eigen::MatrixX3i f2(24, 3);
  f2 << f, (f.array() + 8).matrix();
  const auto hits = self_intersections(v2, f2);
  CHECK(!hits.empty());
  for (const auto& [a, b] : hits) CHECK((a < 12) != (b < 12));  // only across the two boxes
  CHECK(self_intersections(v2, f2, 1).size() == 1);
}

TEST_CASE("index locality of a strip") {
  // A strip of triangles over two rows of points: zig-zag order makes every
  // consecutive pair an edge; sorting by row breaks exactly one pair.
  const int n = 10;
  Eigen::MatrixX3i zig(2 * n - 2, 3);
  for (int i = 0; i + 2 < 2 * n; ++i) zig.row(i) << i, i + 1, i + 2;
  auto loc = index_locality(zig, 2 * n);
  CHECK(loc.one_hop == 1.0);
  CHECK(loc.two_hop == 1.0);
  // Relabel: first all even (row 0), then all odd (row 1).
  Eigen::MatrixX3i rows = zig;
  for (int i = 0; i < rows.size(); ++i) rows(i) = rows(i) % 2 == 0 ? rows(i) / 2 : n + rows(i) / 2;
  loc = index_locality(rows, 2 * n);
  CHECK(loc.one_hop == Approx(static_cast<double>(2 * n - 2) / (2 * n - 1)));
  CHECK(loc.two_hop == loc.one_hop);  // the two row ends are far apart
}

}  // namespace

TEST_CASE("self_intersections finds exactly the pairs a brute-force loop finds") {
  // Two crumpled 10 x 10 sheets over the same square (random heights, fixed
  // seed), one mesh: they cross each other in many places.
  const int n = 10, sheet = n * n;
  Eigen::MatrixX3d v(2 * sheet, 3);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> height(-0.5, 0.5), wobble(-0.3, 0.3);
  for (int s = 0; s < 2; ++s)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) v.row(s * sheet + i * n + j) << j + wobble(rng), i + wobble(rng), height(rng);
  Eigen::MatrixX3i f(4 * (n - 1) * (n - 1), 3);
  int k = 0;
  for (int s = 0; s < 2; ++s)
    for (int i = 0; i + 1 < n; ++i)
      for (int j = 0; j + 1 < n; ++j) {
        const int a = s * sheet + i * n + j;
        f.row(k++) << a, a + 1, a + n + 1;
        f.row(k++) << a, a + n + 1, a + n;
      }
  std::vector<std::pair<int, int>> expected;
  for (int a = 0; a < f.rows(); ++a)
    for (int b = a + 1; b < f.rows(); ++b) {
      bool shared = false;
      for (int s = 0; s < 3; ++s)
        for (int t = 0; t < 3; ++t) shared = shared || f(a, s) == f(b, t);
      if (!shared && triangles_intersect(v.row(f(a, 0)), v.row(f(a, 1)), v.row(f(a, 2)), v.row(f(b, 0)), v.row(f(b, 1)),
                                         v.row(f(b, 2))))
        expected.emplace_back(a, b);
    }
  REQUIRE(expected.size() > 20);
  CHECK(self_intersections(v, f, 100000) == expected);
}
