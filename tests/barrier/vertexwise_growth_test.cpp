// A shrunk body grown back vertex by vertex (scene/vertexwise_growth.hpp), on
// a sphere shrunk by 3 cm with a small garment triangle standing inside where
// the true sphere would be (the cloth a network pushed into the body): the
// far side is back in one call, every vertex moves along its own way back and
// never past it, the side under the triangle approaches it but stops at the
// floor, and the body's distance to the triangle -- measured here by sampling
// both surfaces, no code shared with the growth -- never falls below a tenth
// of what it was in one call.
#include <catch2/catch.hpp>

#include "../../framework/src/scene/vertexwise_growth.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

using namespace drape;

namespace {

// Points spread over a triangle by an n x n barycentric grid (corners included).
std::vector<Eigen::Vector3d> samples(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, int n) {
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const double u = double(i) / n, v = double(j) / n;
      out.push_back(a + u * (b - a) + v * (c - a));
    }
  return out;
}

// The least distance between sample points of the garment triangle and of
// every body face near it: at least the true surface distance, and at most
// that plus ~1 mm (the spacing of the samples).
double sampled_distance(const Eigen::MatrixX3d& body, const Eigen::MatrixX3i& faces, const Eigen::MatrixX3d& tri) {
  const std::vector<Eigen::Vector3d> cloth = samples(tri.row(0), tri.row(1), tri.row(2), 20);
  const Eigen::Vector3d centre = tri.colwise().mean();
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = body.row(faces(f, 0)), b = body.row(faces(f, 1)), c = body.row(faces(f, 2));
    if ((a - centre).norm() > 0.06) continue;
    for (const Eigen::Vector3d& p : samples(a, b, c, 20))
      for (const Eigen::Vector3d& q : cloth) best = std::min(best, (p - q).norm());
  }
  return best;
}

}  // namespace

TEST_CASE("VertexwiseGrowth brings a shrunk body back where the garment is far and stops at the floor where it is not",
          "[barrier][vertexwise_growth]") {
  const Mesh sphere = test::uv_sphere(0.1, 16, 24);
  const Eigen::MatrixX3d target = sphere.vertices;
  const Eigen::MatrixX3d shrunk = 0.7 * target;  // 3 cm in along the normals
  // A 1.6 cm triangle facing +x, 5 mm inside the true sphere: the body cannot
  // reach its true shape there without passing through it.
  Eigen::MatrixX3d tri(3, 3);
  tri << 0.095, 0.01, 0, 0.095, -0.005, 0.008, 0.095, -0.005, -0.008;
  Eigen::MatrixX3i tri_faces(1, 3);
  tri_faces << 0, 1, 2;
  const double floor = 0.004;

  Eigen::MatrixX3d now = shrunk;
  double gap = sampled_distance(now, sphere.faces, tri);
  REQUIRE(gap > 0.02);
  for (int call = 0; call < 40; ++call) {
    const Eigen::MatrixX3d moved = scene_detail::VertexwiseGrowth(sphere.faces, tri_faces).step(now, target, tri, floor);
    for (Eigen::Index v = 0; v < now.rows(); ++v) {
      const Eigen::RowVector3d way = target.row(v) - now.row(v), step = moved.row(v) - now.row(v);
      // Along its own way back, never past it.
      REQUIRE(step.norm() <= way.norm() + 1e-15);
      REQUIRE((step - step.dot(way) / std::max(way.squaredNorm(), 1e-300) * way).norm() <= 1e-12);
    }
    const double after = sampled_distance(moved, sphere.faces, tri);
    REQUIRE(after >= 0.1 * gap - 1e-3);
    // The floor: sampling never reads less than the true distance.
    REQUIRE(after >= floor);
    now = moved;
    gap = after;
    if (call == 0) {
      // The far side is back in one call, exactly.
      for (Eigen::Index v = 0; v < now.rows(); ++v)
        if (target(v, 0) < 0) REQUIRE(now.row(v) == target.row(v));
    }
  }
  // The body came up to the triangle (from 3.5 cm to within the floor plus the
  // sampling's error and a body edge's bend), and is held only around it.
  CHECK(gap < floor + 0.006);
  int held = 0;
  for (Eigen::Index v = 0; v < now.rows(); ++v)
    if (now.row(v) != target.row(v)) {
      ++held;
      REQUIRE((target.row(v) - Eigen::RowVector3d(0.1, 0, 0)).norm() < 0.06);
    }
  REQUIRE(held > 0);
}

TEST_CASE("VertexwiseGrowth lets a body whose way ends short of the garment arrive", "[barrier][vertexwise_growth]") {
  // The triangle 3 mm outside the true sphere, a floor of 4 mm: near the end of
  // its way the floor gives way to the remaining distance, and every vertex
  // arrives at its target exactly.
  const Mesh sphere = test::uv_sphere(0.1, 16, 24);
  Eigen::MatrixX3d tri(3, 3);
  tri << 0.103, 0.01, 0, 0.103, -0.005, 0.008, 0.103, -0.005, -0.008;
  Eigen::MatrixX3i tri_faces(1, 3);
  tri_faces << 0, 1, 2;
  Eigen::MatrixX3d now = 0.9 * sphere.vertices;
  int calls = 0;
  while (now != sphere.vertices && calls < 200) {
    now = scene_detail::VertexwiseGrowth(sphere.faces, tri_faces).step(now, sphere.vertices, tri, 0.004);
    ++calls;
  }
  REQUIRE(now == sphere.vertices);
  REQUIRE(calls > 1);  // the side under the triangle took more than one call
}
