// Closest points without signs (NearestTriangles) and searches started from a
// hint face (here and in BodySurface::locate_near): the same points as an
// exhaustive search, whatever the hint, also after the mesh moved; and the
// cache of data-only closest points keeps entries by content within its budget.
#include "reference.hpp"

#include <drape/errors.hpp>
#include <drape/geometry/closed_shapes.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/nearest_triangles.hpp>
#include <drape/geometry/surface_cache.hpp>

#include <catch2/catch.hpp>

#include <cstring>
#include <limits>
#include <random>
#include <utility>

using drape::Mesh;
using namespace drape::geometry;

namespace {

// A bumpy, non-convex closed surface: an icosphere with its vertices pushed in and out.
Mesh bumpy_sphere(unsigned seed) {
  Mesh m = icosphere(3);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> scale(0.8, 1.2);
  for (int v = 0; v < m.num_vertices(); ++v) m.vertices.row(v) *= scale(rng);
  return m;
}

std::vector<Eigen::Vector3d> spread_points(std::mt19937& rng, int count) {
  std::uniform_real_distribution<double> u(-1.6, 1.6);
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < count; ++i) out.emplace_back(u(rng), u(rng), u(rng));
  return out;
}

}  // namespace

TEST_CASE("nearest triangles and hinted searches find the exhaustive search's closest point", "[geometry][nearest]") {
  Mesh m = bumpy_sphere(4);
  NearestTriangles nearest(m.vertices, m.faces);
  BodySurface surface(m);
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> any_face(0, m.num_faces() - 1);
  for (int round = 0; round < 2; ++round) {
    if (round == 1) {  // the mesh moves: both refit
      m = bumpy_sphere(6);
      nearest.update(m.vertices);
      surface.update(m.vertices);
    }
    for (const Eigen::Vector3d& p : spread_points(rng, 400)) {
      const double reference = drape::test::mesh_distance(m, p);
      const SurfacePoint plain = surface.locate(p);
      // Hints: none, the answer itself, a random (mostly far) face, an out-of-range one.
      for (const int hint : {-1, plain.face, any_face(rng), m.num_faces() + 5}) {
        const SurfacePoint n = nearest.nearest(p, hint < m.num_faces() ? hint : -1);
        const SurfacePoint s = surface.locate_near(p, hint);
        CHECK(n.signed_distance == Approx(reference).margin(1e-12));
        CHECK((n.point - p).norm() == Approx(reference).margin(1e-12));
        CHECK((s.point - p).norm() == Approx(reference).margin(1e-12));
        // Bit for bit, whatever the hint: of faces at one distance the lowest-numbered wins.
        CHECK(n.face == plain.face);
        CHECK(s.face == plain.face);
        CHECK(n.point == plain.point);
        CHECK(s.point == plain.point);
        // The signed query keeps its sign and normal with a hint.
        CHECK(s.signed_distance == Approx(plain.signed_distance).margin(1e-12));
        CHECK((s.normal - plain.normal).norm() < 1e-9);
        // The barycentric weights give the point on the face found.
        const Eigen::Vector3d from_weights = n.barycentric[0] * m.vertices.row(m.faces(n.face, 0)).transpose() +
                                             n.barycentric[1] * m.vertices.row(m.faces(n.face, 1)).transpose() +
                                             n.barycentric[2] * m.vertices.row(m.faces(n.face, 2)).transpose();
        CHECK((from_weights - n.point).norm() < 1e-12);
      }
    }
  }
  // Points outside a vertex have their closest point there, at the same
  // distance (up to rounding) from every face around it: the same face and
  // bits from any start.
  for (int v = 0; v < m.num_vertices(); v += 7) {
    const Eigen::Vector3d p = m.vertices.row(v).transpose() * 1.3;
    const SurfacePoint plain = nearest.nearest(p);
    CHECK((plain.point - p).norm() == Approx(drape::test::mesh_distance(m, p)).margin(1e-12));
    for (int hint = 0; hint < m.num_faces(); hint += 97) {
      const SurfacePoint n = nearest.nearest(p, hint);
      CHECK(n.face == plain.face);
      CHECK(n.point == plain.point);
    }
  }
  const Eigen::MatrixX3d points = Eigen::MatrixX3d::Random(20, 3);
  const auto all = nearest.nearest_all(points);
  for (int i = 0; i < 20; ++i) CHECK((all[i].point - surface.locate(points.row(i).transpose()).point).norm() < 1e-12);
  CHECK_THROWS_WITH(nearest.nearest_all(points, std::vector<int>(3, 0)), Catch::Contains("3 hints for 20 points"));
  CHECK_THROWS_WITH(nearest.update(Eigen::MatrixX3d::Zero(4, 3)), Catch::Contains("4 vertices given"));
  CHECK_THROWS_WITH(NearestTriangles(m.vertices, Eigen::MatrixX3i::Constant(1, 3, 99999)), Catch::Contains("face 0 uses vertex 99999"));
}

namespace {

// The argmin of (distance, face) over every face, by brute force.
std::pair<int, Eigen::Vector3d> exhaustive_nearest(const Mesh& m, const Eigen::Vector3d& p) {
  int best_face = -1;
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector3d best_point = Eigen::Vector3d::Zero();
  for (int f = 0; f < m.num_faces(); ++f) {
    const TrianglePoint q = closest_point_on_triangle(p, m.vertices.row(m.faces(f, 0)).transpose(),
                                                      m.vertices.row(m.faces(f, 1)).transpose(),
                                                      m.vertices.row(m.faces(f, 2)).transpose());
    const double d2 = (q.point - p).squaredNorm();
    if (d2 < best) best = d2, best_face = f, best_point = q.point;
  }
  return {best_face, best_point};
}

}  // namespace

// The hierarchy keeps its boxes in float (rounded outwards, the query's own
// rounding subtracted): far from the origin, where a float ulp is millimetres,
// at points on the surface and among thin, crowded triangles it must still
// find exactly what brute force finds in double.
TEST_CASE("the float-boxed hierarchy finds the brute-force argmin far from the origin and on slivers",
          "[geometry][nearest]") {
  std::mt19937 rng(11);
  for (const double offset : {0.0, 1e3, 1e5}) {
    Mesh m = bumpy_sphere(7);
    m.vertices.rowwise() += Eigen::RowVector3d(offset, -0.5 * offset, 0.25 * offset);
    // Squash one axis by 1e-4: a near-flat surface of slivers whose boxes overlap everywhere.
    Mesh flat = m;
    flat.vertices.col(1) = (flat.vertices.col(1).array() - flat.vertices.col(1).mean()) * 1e-4 +
                           flat.vertices.col(1).mean();
    for (const Mesh* mesh : {&m, &flat}) {
      NearestTriangles nearest(mesh->vertices, mesh->faces);
      const Eigen::Vector3d centre = mesh->vertices.colwise().mean().transpose();
      std::vector<Eigen::Vector3d> points;
      for (const Eigen::Vector3d& p : spread_points(rng, 150)) points.push_back(centre + p);
      // Points on the surface itself (a corner, an edge's midpoint, a face's centroid)
      // and 1e-9 above it.
      for (int f = 0; f < mesh->num_faces(); f += 37) {
        const Eigen::Vector3d a = mesh->vertices.row(mesh->faces(f, 0)), b = mesh->vertices.row(mesh->faces(f, 1)),
                              c = mesh->vertices.row(mesh->faces(f, 2));
        points.push_back(a);
        points.push_back(0.5 * (a + b));
        points.push_back((a + b + c) / 3);
        points.push_back((a + b + c) / 3 + Eigen::Vector3d(0, 1e-9, 0));
      }
      for (const Eigen::Vector3d& p : points) {
        const auto [face, point] = exhaustive_nearest(*mesh, p);
        const SurfacePoint n = nearest.nearest(p);
        CHECK(n.face == face);
        CHECK(n.point == point);
      }
    }
  }
}

TEST_CASE("the surface cache finds entries by content and stops growing at its budget", "[geometry][nearest]") {
  const Mesh m = icosphere(1);
  const std::uint64_t topology = topology_hash(m.faces);
  CHECK(topology != topology_hash(icosphere(2).faces));
  std::vector<float> body(30, 0.5f), points(12, 0.25f);
  const SurfaceKey key = surface_key(topology, body.data(), body.size(), points.data(), points.size());
  CHECK(key == surface_key(topology, body.data(), body.size(), points.data(), points.size()));
  points[7] = std::nextafter(points[7], 1.0f);  // one ulp of one coordinate is another sample
  const SurfaceKey other = surface_key(topology, body.data(), body.size(), points.data(), points.size());
  CHECK_FALSE(key == other);
  CHECK_FALSE(key == surface_key(topology + 1, body.data(), body.size(), points.data(), points.size() - 1));

  // Room for two entries of 10 points.
  SurfaceCache cache(2 * (10 * sizeof(SurfacePoint) + 64));
  SurfaceCache::Hits hits(10);
  hits[3].face = 7;
  CHECK(cache.find(key) == nullptr);
  CHECK(cache.insert(key, hits)->at(3).face == 7);
  REQUIRE(cache.find(key) != nullptr);
  CHECK(cache.find(key)->at(3).face == 7);
  CHECK(cache.find(other) == nullptr);
  cache.insert(other, SurfaceCache::Hits(10));
  CHECK(cache.entries() == 2);
  const SurfaceKey third{1, 2};
  CHECK(cache.insert(third, SurfaceCache::Hits(10))->size() == 10);  // handed back, not kept
  CHECK(cache.find(third) == nullptr);
  CHECK(cache.entries() == 2);
  CHECK(cache.bytes() <= cache.budget());
}

TEST_CASE("surface cache entries travel between processes as bytes and come back the same", "[geometry][nearest]") {
  SurfaceCache cache(std::size_t{1} << 20);
  SurfaceCache::Hits hits(3);
  for (int i = 0; i < 3; ++i) {
    hits[i].face = 10 + i;
    hits[i].barycentric = Eigen::Vector3d(0.25, 0.5, 0.25) * (i + 1);
    hits[i].point = Eigen::Vector3d(1.0 / 3, -2.5e-7, 1e300) * (i + 1);
    hits[i].normal = Eigen::Vector3d(0, 0, -1);
    hits[i].signed_distance = -0.125 * i;
    hits[i].feature = i == 2 ? TriangleFeature::edge_ca : TriangleFeature::interior;
  }
  // Nearby lists travel with the points: point 0 lists two faces, 1 none, 2 one.
  NearbyFaces near;
  near.start = {0, 2, 2, 3};
  near.face = {10, 4, 12};
  near.reach = {0.0f, 0.03125f, 1e-7f};
  near.complete = {0.5f, 0.0f, 0.25f};
  const SurfaceKey k1{1, 2}, k2{3, 4}, k3{5, 6};
  cache.insert(k1, SurfaceEntry{hits, near});
  cache.insert(k2, SurfaceCache::Hits{});
  REQUIRE(cache.find_nearby(k1) != nullptr);
  CHECK(cache.find_nearby(k2) == nullptr);  // an entry without lists
  const auto computed = cache.take_computed();
  REQUIRE(computed.size() == 2);
  CHECK(cache.take_computed().empty());  // handed out once
  const auto bytes = pack_surface_entries(computed);
  // 40 bytes of head, 88 a point, and the lists: 4 (points + 1) + 8 per face + 4 per point.
  CHECK(bytes.size() == (40 + 3 * 88 + 4 * 4 + 3 * 8 + 3 * 4) + 40);
  CHECK(packed_entry_bytes(*computed[0].second) == 40 + 3 * 88 + 4 * 4 + 3 * 8 + 3 * 4);
  const auto back = unpack_surface_entries(bytes.data(), bytes.size());
  REQUIRE(back.size() == 2);
  CHECK(back[0].first == k1);
  REQUIRE(back[0].second.hits.size() == 3);
  CHECK(back[0].second.nearby.start == near.start);
  CHECK(back[0].second.nearby.face == near.face);
  CHECK(back[0].second.nearby.reach == near.reach);
  CHECK(back[0].second.nearby.complete == near.complete);
  CHECK(back[1].second.nearby.points() == 0);
  for (int i = 0; i < 3; ++i) {
    const SurfacePoint &a = back[0].second.hits[i], &b = hits[i];
    CHECK(a.face == b.face);
    CHECK(a.barycentric == b.barycentric);
    CHECK(a.point == b.point);
    CHECK(a.normal == b.normal);
    CHECK(a.signed_distance == b.signed_distance);
    CHECK(a.feature == b.feature);
  }
  CHECK(back[1].first == k2);
  CHECK(back[1].second.hits.empty());
  // Adopted entries are found but not handed out again as this process's own.
  SurfaceCache other(std::size_t{1} << 20);
  other.adopt(k3, back[0].second);
  REQUIRE(other.find(k3) != nullptr);
  CHECK(other.find(k3)->at(2).feature == TriangleFeature::edge_ca);
  REQUIRE(other.find_nearby(k3) != nullptr);
  CHECK(other.find_nearby(k3)->face == near.face);
  CHECK(other.take_computed().empty());
  // A cut buffer is refused, not read past its end.
  CHECK_THROWS_WITH(unpack_surface_entries(bytes.data(), bytes.size() - 1), Catch::Contains("surface cache entries"));
  CHECK_THROWS_WITH(unpack_surface_entries(bytes.data(), 10), Catch::Contains("10 bytes left"));
  CHECK_THROWS_WITH(unpack_surface_entries(bytes.data(), 40 + 3 * 88 + 20), Catch::Contains("run past the end"));
  std::vector<std::uint8_t> bad = bytes;
  const std::int32_t wrong = 5;  // point 1's offset past the faces listed
  std::memcpy(bad.data() + 40 + 3 * 88 + 4, &wrong, sizeof wrong);
  CHECK_THROWS_WITH(unpack_surface_entries(bad.data(), bad.size()), Catch::Contains("do not add up"));
}

// The training losses find the prediction's closest points among the faces
// listed near the ground truth's vertex (NearbyFaces): the same face and point
// bits as the tree search, for predictions next to the ground truth (the list
// proves the answer), far from it (the tree is searched), on a vertex where
// faces tie, and with lists cut short.
TEST_CASE("nearby-face lists give the tree search's closest point, bit for bit", "[geometry][nearest]") {
  const Mesh m = bumpy_sphere(9);
  NearestTriangles nearest(m.vertices, m.faces);
  std::mt19937 rng(13);
  std::normal_distribution<double> gauss(0.0, 1.0);
  // Ground truth: points 0-5 cm off the surface (the sphere's radius is ~1 m), and points right above vertices.
  std::vector<Eigen::Vector3d> truth;
  std::uniform_real_distribution<double> height(0.0, 0.05);
  for (int f = 0; f < m.num_faces(); f += 3) {
    const Eigen::Vector3d c = (m.vertices.row(m.faces(f, 0)) + m.vertices.row(m.faces(f, 1)) +
                               m.vertices.row(m.faces(f, 2))).transpose() / 3;
    truth.push_back(c * (1.0 + height(rng)));
  }
  for (int v = 0; v < m.num_vertices(); v += 5) truth.push_back(m.vertices.row(v).transpose() * 1.02);
  Eigen::MatrixX3d y(static_cast<Eigen::Index>(truth.size()), 3);
  for (std::size_t i = 0; i < truth.size(); ++i) y.row(static_cast<Eigen::Index>(i)) = truth[i].transpose();
  const std::vector<SurfacePoint> hits = nearest.nearest_all(y);

  int listed = 0, searched = 0;
  for (const auto& [slack, max_faces] : {std::pair{0.02, 16}, std::pair{0.02, 2}, std::pair{0.0, 1}, std::pair{0.3, 64}}) {
    const NearbyFaces near = nearest.nearby(y, hits, slack, max_faces);
    REQUIRE(near.points() == y.rows());
    for (Eigen::Index i = 0; i < y.rows(); ++i) {
      const int begin = near.start[i], end = near.start[i + 1];
      CHECK(end - begin <= max_faces);
      CHECK(end > begin);  // the ground truth's own face at least
      for (int k = begin + 1; k < end; ++k) CHECK(near.reach[k - 1] <= near.reach[k]);
      // Predictions: the ground truth itself, then further and further away, and straight onto a vertex.
      for (const double step : {0.0, 1e-4, 2e-3, 1e-2, 5e-2, 0.3}) {
        const Eigen::Vector3d dir(gauss(rng), gauss(rng), gauss(rng));
        const Eigen::Vector3d x = y.row(i).transpose() + step * dir.normalized();
        const SurfacePoint tree = nearest.nearest(x);
        const SurfacePoint listed_point = nearest.nearest_from(x, y.row(i).transpose(), near, static_cast<int>(i));
        CHECK(listed_point.face == tree.face);
        CHECK(listed_point.point == tree.point);
        CHECK(listed_point.feature == tree.feature);
        CHECK(listed_point.signed_distance == tree.signed_distance);
        // How often the list alone proved it: compared with the tree's work below.
        const double best = (tree.point - x).norm(), moved = (x - y.row(i).transpose()).norm();
        (double(near.complete[i]) - moved > best + 1e-9 ? listed : searched) += 1;
      }
      const Eigen::Vector3d corner = m.vertices.row(m.faces(hits[i].face, 0)).transpose() * 1.01;
      CHECK(nearest.nearest_from(corner, y.row(i).transpose(), near, static_cast<int>(i)).face ==
            nearest.nearest(corner).face);
    }
  }
  // Both ways were taken: proofs from the lists, and searches of the tree.
  CHECK(listed > 100);
  CHECK(searched > 100);
  const NearbyFaces near = nearest.nearby(y, hits, 0.02, 4);
  CHECK_THROWS_WITH(nearest.nearest_from(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), near, -1),
                    Catch::Contains("no nearby list -1"));
  CHECK_THROWS_WITH(nearest.nearby(y, std::vector<SurfacePoint>(2), 0.02, 4), Catch::Contains("2 closest points for"));
  CHECK_THROWS_WITH(nearest.nearby(y, hits, 0.02, 0), Catch::Contains("max_faces >= 1"));
}
