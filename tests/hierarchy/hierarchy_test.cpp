// The garment hierarchy on a two-panel sewn tube: level sizes, topology kept,
// charts kept, no UV flips, and up-sampling weights that are barycentric in UV.
#include "sewn_tube.hpp"

#include <drape/errors.hpp>
#include <drape/geometry/hierarchy.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <map>
#include <numeric>
#include <set>

using namespace drape;
using namespace drape::geometry;

namespace {

struct Topology {
  bool manifold = true;  // every edge in <= 2 faces and every vertex a single fan
  int boundary_loops = 0;
  int euler = 0;
};

int root(std::vector<int>& p, int x) {
  while (p[x] != x) x = p[x] = p[p[x]];
  return x;
}

Topology topology(const Mesh& m) {
  Topology t;
  std::map<std::pair<int, int>, int> edge_faces;
  for (int f = 0; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = m.faces(f, k), b = m.faces(f, (k + 1) % 3);
      ++edge_faces[{std::min(a, b), std::max(a, b)}];
    }
  const int n = m.num_vertices();
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::set<int> on_boundary;
  for (const auto& [e, count] : edge_faces) {
    if (count > 2) t.manifold = false;
    if (count == 1) {
      parent[root(parent, e.first)] = root(parent, e.second);
      on_boundary.insert(e.first);
      on_boundary.insert(e.second);
    }
  }
  for (int v : on_boundary) t.boundary_loops += root(parent, v) == v;
  // Single fan per vertex: the link (opposite edges) is connected.
  std::vector<std::vector<std::pair<int, int>>> link(n);
  for (int f = 0; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) link[m.faces(f, k)].push_back({m.faces(f, (k + 1) % 3), m.faces(f, (k + 2) % 3)});
  std::iota(parent.begin(), parent.end(), 0);
  for (int v = 0; v < n; ++v) {
    std::set<int> spokes;
    for (const auto& [a, b] : link[v]) {
      parent[root(parent, a)] = root(parent, b);
      spokes.insert(a);
      spokes.insert(b);
    }
    int roots = 0;
    for (int s : spokes) roots += root(parent, s) == s;
    if (roots > 1) t.manifold = false;
    for (int s : spokes) parent[s] = s;
  }
  t.euler = n - static_cast<int>(edge_faces.size()) + m.num_faces();
  return t;
}

double uv_signed_area(const Mesh& m, int f) {
  const Eigen::Vector2d a = m.uv.row(m.uv_faces(f, 0)), b = m.uv.row(m.uv_faces(f, 1)), c = m.uv.row(m.uv_faces(f, 2));
  const Eigen::Vector2d e0 = b - a, e1 = c - a;
  return e0.x() * e1.y() - e0.y() * e1.x();
}

// The distinct UVs of every vertex.
std::vector<std::set<int>> vertex_uvs(const Mesh& m) {
  std::vector<std::set<int>> out(m.num_vertices());
  for (int f = 0; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) out[m.faces(f, k)].insert(m.uv_faces(f, k));
  return out;
}

const Hierarchy& tube_hierarchy() {
  static const Hierarchy h = build_hierarchy(test::sewn_tube(24, 50));
  return h;
}

}  // namespace

TEST_CASE("the hierarchy has four levels, each about four times smaller") {
  const Hierarchy& h = tube_hierarchy();
  REQUIRE(h.num_levels() == 4);
  REQUIRE(h.levels[0].mesh.num_vertices() == 2400);
  for (int l = 0; l + 1 < 4; ++l) {
    const double ratio = double(h.levels[l].mesh.num_vertices()) / h.levels[l + 1].mesh.num_vertices();
    INFO("level " << l << ": " << h.levels[l].mesh.num_vertices() << " -> " << h.levels[l + 1].mesh.num_vertices());
    CHECK(ratio > 3.5);
    CHECK(ratio < 4.5);
  }
}

TEST_CASE("every level is a manifold tube with the same boundary loops and UV charts") {
  const Hierarchy& h = tube_hierarchy();
  int charts0 = 0;
  uv_charts(h.levels[0].mesh, charts0);
  CHECK(charts0 == 2);
  for (int l = 0; l < h.num_levels(); ++l) {
    INFO("level " << l);
    const Mesh& m = h.levels[l].mesh;
    const Topology t = topology(m);
    CHECK(t.manifold);
    CHECK(t.boundary_loops == 2);
    CHECK(t.euler == 0);  // a tube (annulus)
    int charts = 0;
    uv_charts(m, charts);
    CHECK(charts == 2);
    REQUIRE(h.levels[l].face_chart.size() == m.num_faces());
    CHECK(std::set<int>(h.levels[l].face_chart.data(), h.levels[l].face_chart.data() + m.num_faces()).size() == 2);
    // Counter-clockwise in UV at level 0, so no face may end up clockwise or flat.
    int flipped = 0;
    for (int f = 0; f < m.num_faces(); ++f) flipped += !(uv_signed_area(m, f) > 0);
    CHECK(flipped == 0);
    // Seam vertices keep their two UVs; no vertex gets more.
    int seam_vertices = 0;
    for (const auto& uvs : vertex_uvs(m)) {
      CHECK(uvs.size() <= 2);
      seam_vertices += uvs.size() == 2;
    }
    CHECK(seam_vertices >= 4);  // both seams reach both hems
  }
}

TEST_CASE("coarse vertices are fine vertices with the same positions and UVs") {
  const Hierarchy& h = tube_hierarchy();
  const Mesh& m0 = h.levels[0].mesh;
  for (int l = 1; l < h.num_levels(); ++l) {
    const HierarchyLevel& level = h.levels[l];
    const HierarchyLevel& finer = h.levels[l - 1];
    REQUIRE(level.fine_index.size() == level.mesh.num_vertices());
    REQUIRE(level.uv_fine_index.size() == level.mesh.uv.rows());
    for (int i = 0; i < level.fine_index.size(); ++i)
      CHECK(level.mesh.vertices.row(i) == m0.vertices.row(level.fine_index[i]));
    for (int t = 0; t < level.uv_fine_index.size(); ++t) CHECK(level.mesh.uv.row(t) == m0.uv.row(level.uv_fine_index[t]));
    const std::set<int> finer_set(finer.fine_index.data(), finer.fine_index.data() + finer.fine_index.size());
    for (int i = 0; i < level.fine_index.size(); ++i) CHECK(finer_set.count(level.fine_index[i]) == 1);
  }
}

TEST_CASE("up-sampling rows are convex combinations that reproduce UV-linear functions") {
  const Hierarchy& h = tube_hierarchy();
  CHECK(h.levels.back().upsample.size() == 0);
  for (int l = 0; l + 1 < h.num_levels(); ++l) {
    INFO("level " << l);
    const Mesh& fine = h.levels[l].mesh;
    const Mesh& coarse = h.levels[l + 1].mesh;
    const auto& U = h.levels[l].upsample;
    REQUIRE(U.rows() == fine.num_vertices());
    REQUIRE(U.cols() == coarse.num_vertices());
    Eigen::VectorXd row_sum = Eigen::VectorXd::Zero(U.rows());
    double min_weight = 1;
    for (int i = 0; i < U.outerSize(); ++i)
      for (Eigen::SparseMatrix<float, Eigen::RowMajor>::InnerIterator it(U, i); it; ++it) {
        row_sum[i] += it.value();
        min_weight = std::min(min_weight, double(it.value()));
      }
    CHECK((row_sum.array() - 1.0).abs().maxCoeff() < 1e-6);
    CHECK(min_weight >= 0);

    // Height (UV v) is the same in both charts, so it is one function on the
    // vertices and must come back exactly everywhere, seams included.
    Eigen::VectorXf height_coarse(coarse.num_vertices());
    for (int f = 0; f < coarse.num_faces(); ++f)
      for (int k = 0; k < 3; ++k) height_coarse[coarse.faces(f, k)] = float(coarse.uv(coarse.uv_faces(f, k), 1));
    const Eigen::VectorXf height_fine = U * height_coarse;
    double worst = 0;
    for (int f = 0; f < fine.num_faces(); ++f)
      for (int k = 0; k < 3; ++k)
        worst = std::max(worst, std::abs(height_fine[fine.faces(f, k)] - fine.uv(fine.uv_faces(f, k), 1)));
    CHECK(worst < 1e-6);

    // Full UV reproduction for vertices inside one chart: the weights put on
    // the coarse vertices' UVs in that chart give back the vertex's own UV.
    const Eigen::VectorXi& fine_chart = h.levels[l].face_chart;
    const Eigen::VectorXi& coarse_chart = h.levels[l + 1].face_chart;
    std::vector<int> chart(fine.uv.rows(), -1);  // no UV is shared by two charts here
    for (int f = 0; f < fine.num_faces(); ++f)
      for (int k = 0; k < 3; ++k) chart[fine.uv_faces(f, k)] = fine_chart[f];
    std::map<std::pair<int, int>, Eigen::Vector2d> coarse_uv;  // (coarse vertex, chart) -> uv
    for (int f = 0; f < coarse.num_faces(); ++f)
      for (int k = 0; k < 3; ++k) coarse_uv[{coarse.faces(f, k), coarse_chart[f]}] = coarse.uv.row(coarse.uv_faces(f, k));
    const auto uvs = vertex_uvs(fine);
    int tested = 0;
    double uv_error = 0;
    for (int i = 0; i < fine.num_vertices(); ++i) {
      if (uvs[i].size() != 1) continue;
      const int t = *uvs[i].begin();
      Eigen::Vector2d sum = Eigen::Vector2d::Zero();
      for (Eigen::SparseMatrix<float, Eigen::RowMajor>::InnerIterator it(U, i); it; ++it) {
        const auto found = coarse_uv.find({int(it.col()), chart[t]});
        REQUIRE(found != coarse_uv.end());
        sum += double(it.value()) * found->second;
      }
      uv_error = std::max(uv_error, (sum - fine.uv.row(t).transpose()).norm());
      ++tested;
    }
    CHECK(tested > fine.num_vertices() / 2);
    CHECK(uv_error < 1e-6);
  }
}

TEST_CASE("the number of levels and the ratio are options") {
  const Hierarchy h = build_hierarchy(test::sewn_tube(12, 20), {.levels = 3, .ratio = 2.0});
  REQUIRE(h.num_levels() == 3);
  CHECK(h.levels[1].mesh.num_vertices() == 240);
  CHECK(h.levels[2].mesh.num_vertices() == 120);
}

TEST_CASE("a garment without UVs or with bad indices is refused with a clear message") {
  Mesh m = test::sewn_tube(8, 6);
  Mesh no_uv = m;
  no_uv.uv.resize(0, 2);
  no_uv.uv_faces.resize(0, 3);
  CHECK_THROWS_WITH(build_hierarchy(no_uv), Catch::Contains("no per-corner UVs"));
  Mesh bad = m;
  bad.uv_faces(3, 1) = int(m.uv.rows());
  CHECK_THROWS_AS(build_hierarchy(bad), ConfigError);
  CHECK_THROWS_AS(build_hierarchy(m, {.levels = 0}), ConfigError);
}
