// Closest points and inside/outside on closed meshes, against exhaustive search,
// the winding number and the analytic shapes; refitting against rebuilding.
#include "reference.hpp"

#include <drape/errors.hpp>
#include <drape/geometry/closed_shapes.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/pseudo_normals.hpp>
#include <drape/geometry/surface_crossings.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

using drape::Mesh;
using drape::geometry::BodySurface;
using drape::geometry::SurfacePoint;

namespace {

Eigen::Vector3d random_direction(std::mt19937& rng) {
  std::normal_distribution<double> g;
  return Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
}

double mean_edge(const Mesh& m) {
  double sum = 0;
  for (int f = 0; f < m.num_faces(); ++f) sum += (m.vertices.row(m.faces(f, 0)) - m.vertices.row(m.faces(f, 1))).norm();
  return sum / m.num_faces();
}

// Points where sign errors happen: right next to vertices and edges (a tiny
// offset in a random direction), plus a spread of points in and around the mesh.
std::vector<Eigen::Vector3d> hard_points(const Mesh& m, std::mt19937& rng, int count) {
  std::uniform_real_distribution<double> unit(0, 1);
  std::uniform_int_distribution<int> face(0, m.num_faces() - 1);
  const double h = mean_edge(m);
  const Eigen::Vector3d lo = m.vertices.colwise().minCoeff(), hi = m.vertices.colwise().maxCoeff();
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < count; ++i) {
    const int f = face(rng), k = i % 3;
    const Eigen::Vector3d a = m.vertices.row(m.faces(f, k)), b = m.vertices.row(m.faces(f, (k + 1) % 3));
    const double offset = h * std::pow(10.0, -7 + 6 * unit(rng));
    switch (i % 3) {
      case 0: out.push_back(a + offset * random_direction(rng)); break;
      case 1: out.push_back(a + unit(rng) * (b - a) + offset * random_direction(rng)); break;
      default:
        out.push_back(lo - 0.2 * (hi - lo) + 1.4 * (hi - lo).cwiseProduct(Eigen::Vector3d(unit(rng), unit(rng), unit(rng))));
    }
  }
  return out;
}

// Exhaustive distance and winding-number sign for every point.
void check_against_reference(const BodySurface& surface, const Mesh& m, const std::vector<Eigen::Vector3d>& points) {
  const double h = mean_edge(m);
  for (const Eigen::Vector3d& p : points) {
    const SurfacePoint s = surface.locate(p);
    INFO("p = " << p.transpose());
    REQUIRE(s.face >= 0);
    const double reference = drape::test::mesh_distance(m, p);
    CHECK(std::abs(std::abs(s.signed_distance) - reference) <= 1e-12 * h);
    CHECK(std::abs((s.point - p).norm() - reference) <= 1e-12 * h);
    // The point lies on its face at its barycentric weights.
    Eigen::Vector3d on_face = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) on_face += s.barycentric[k] * Eigen::Vector3d(m.vertices.row(m.faces(s.face, k)));
    CHECK((on_face - s.point).norm() <= 1e-12 * h);
    CHECK(s.normal.norm() == Approx(1).epsilon(1e-12));
    const bool inside = drape::test::winding_number(m, p) > 0.5;
    CHECK((s.signed_distance < 0) == inside);
  }
}

Mesh bumpy_torus() {
  Mesh m = drape::geometry::torus(1.0, 0.35, 40, 20);
  // Bumps make concave and saddle regions with uneven triangles.
  for (int i = 0; i < m.num_vertices(); ++i) {
    const Eigen::Vector3d p = m.vertices.row(i);
    m.vertices.row(i) *= 1 + 0.08 * std::sin(5 * p.x()) * std::cos(4 * p.z() + 1);
  }
  return m;
}

}  // namespace

TEST_CASE("test shapes are closed and counter-clockwise") {
  const Mesh sphere = drape::geometry::icosphere(2);
  CHECK(sphere.num_vertices() == 162);
  CHECK(sphere.num_faces() == 320);
  CHECK(drape::test::signed_volume(sphere) == Approx(4.0 / 3 * M_PI).epsilon(0.05));
  const Mesh ring = drape::geometry::torus(1.0, 0.25, 32, 16);
  CHECK(drape::test::signed_volume(ring) == Approx(2 * M_PI * M_PI * 1.0 * 0.25 * 0.25).epsilon(0.05));
}

TEST_CASE("closest points and signs on an icosphere match exhaustive search and the winding number") {
  const Mesh m = drape::geometry::icosphere(2);
  const BodySurface surface(m);
  std::mt19937 rng(3);
  check_against_reference(surface, m, hard_points(m, rng, 1500));
}

TEST_CASE("closest points and signs on a bumpy torus match exhaustive search and the winding number") {
  const Mesh m = bumpy_torus();
  const BodySurface surface(m);
  std::mt19937 rng(5);
  check_against_reference(surface, m, hard_points(m, rng, 1500));
}

namespace {

// On a convex polyhedron "behind every face plane" is the exact truth for
// inside, even a hair's breadth from a vertex or an edge. Returns how many
// points the plain normal of the face found would have misclassified.
int check_convex(const Mesh& m, std::mt19937& rng) {
  const BodySurface surface(m);
  std::uniform_real_distribution<double> unit(0, 1);
  int on_feature = 0, face_normal_wrong = 0;
  const int count = 3000;
  for (int i = 0; i < count; ++i) {
    const int f0 = i % m.num_faces();
    const Eigen::Vector3d v = m.vertices.row(m.faces(f0, 0)), w = m.vertices.row(m.faces(f0, 1));
    // A third of the points near vertices, a third near edge points, a third
    // leaving a vertex outward (into the cone where the vertex is the closest point).
    const Eigen::Vector3d base = i % 3 == 1 ? Eigen::Vector3d(v + unit(rng) * (w - v)) : v;
    const Eigen::Vector3d direction =
        i % 3 == 2 ? Eigen::Vector3d(v.normalized() + 0.5 * random_direction(rng)).normalized() : random_direction(rng);
    const Eigen::Vector3d p = base + std::pow(10.0, -9 + 7 * unit(rng)) * direction;
    bool inside = true;
    for (int f = 0; f < m.num_faces() && inside; ++f) {
      const Eigen::Vector3d a = m.vertices.row(m.faces(f, 0)), b = m.vertices.row(m.faces(f, 1)),
                            c = m.vertices.row(m.faces(f, 2));
      inside = (p - a).dot((b - a).cross(c - a)) < 0;
    }
    const SurfacePoint s = surface.locate(p);
    INFO("p = " << p.transpose());
    CHECK((s.signed_distance < 0) == inside);
    on_feature += s.feature != drape::geometry::TriangleFeature::interior;
    const Eigen::Vector3d a = m.vertices.row(m.faces(s.face, 0)), b = m.vertices.row(m.faces(s.face, 1)),
                          c = m.vertices.row(m.faces(s.face, 2));
    face_normal_wrong += ((p - s.point).dot((b - a).cross(c - a)) < 0) != inside;
  }
  // Most points must really meet the surface at a vertex or an edge, the case
  // that needs the pseudo-normals.
  CHECK(on_feature > count / 3);
  return face_normal_wrong;
}

Mesh tetrahedron() {
  Mesh m;
  m.vertices.resize(4, 3);
  m.vertices << 1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1;
  m.faces.resize(4, 3);
  m.faces << 0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2;
  return m;
}

}  // namespace

TEST_CASE("convex meshes: inside exactly when behind every face plane, next to vertices and edges") {
  std::mt19937 rng(9);
  const Mesh tet = tetrahedron();
  REQUIRE(drape::test::signed_volume(tet) > 0);
  // Face normals 109 degrees apart: plain face normals fail here, pseudo-normals must not.
  CHECK(check_convex(tet, rng) > 50);
  check_convex(drape::geometry::icosphere(1), rng);
}

TEST_CASE("inside/outside matches the analytic sphere and torus away from the chord error") {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> unit(-1.5, 1.5);
  const double radius = 1.0;
  const Mesh sphere = drape::geometry::icosphere(3, radius);
  const BodySurface sphere_surface(sphere);
  // The mesh lies between the sphere and the sphere shrunk by its largest sagitta.
  const double sagitta = 0.01;
  for (int i = 0; i < 3000; ++i) {
    const Eigen::Vector3d p(unit(rng), unit(rng), unit(rng));
    const double analytic = p.norm() - radius;
    if (std::abs(analytic) < 2 * sagitta) continue;
    const SurfacePoint s = sphere_surface.locate(p);
    CHECK((s.signed_distance < 0) == (analytic < 0));
    CHECK(s.signed_distance == Approx(analytic).margin(sagitta));
  }
  const double major = 1.0, minor = 0.3;
  const int nu = 64, nv = 32;
  const Mesh ring = drape::geometry::torus(major, minor, nu, nv);
  const BodySurface ring_surface(ring);
  const double ring_sagitta = (major + minor) * (1 - std::cos(M_PI / nu)) + minor * (1 - std::cos(M_PI / nv));
  int tested = 0;
  for (int i = 0; i < 3000; ++i) {
    const Eigen::Vector3d p(unit(rng), 0.3 * unit(rng), unit(rng));
    const double analytic = std::hypot(std::hypot(p.x(), p.z()) - major, p.y()) - minor;
    if (std::abs(analytic) < 2 * ring_sagitta) continue;
    ++tested;
    const SurfacePoint s = ring_surface.locate(p);
    CHECK((s.signed_distance < 0) == (analytic < 0));
    CHECK(s.signed_distance == Approx(analytic).margin(ring_sagitta));
  }
  CHECK(tested > 2000);
}

TEST_CASE("the normal is the unit gradient of the signed distance") {
  const Mesh m = bumpy_torus();
  const BodySurface surface(m);
  std::mt19937 rng(17);
  for (const Eigen::Vector3d& p : hard_points(m, rng, 300)) {
    const SurfacePoint s = surface.locate(p);
    if (std::abs(s.signed_distance) < 1e-3) continue;  // finite differences need room
    const double h = 1e-6;
    Eigen::Vector3d g;
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      e[k] = h;
      g[k] = (surface.locate(p + e).signed_distance - surface.locate(p - e).signed_distance) / (2 * h);
    }
    INFO("p = " << p.transpose());
    CHECK((g - s.normal).norm() < 1e-4);
  }
}

TEST_CASE("refitting after moving the vertices answers like a rebuild") {
  const Mesh m = bumpy_torus();
  BodySurface refitted(m);
  Mesh moved = m;
  // A smooth, large deformation: twist, stretch and shift.
  for (int i = 0; i < moved.num_vertices(); ++i) {
    const Eigen::Vector3d p = m.vertices.row(i);
    const double angle = 0.8 * p.y();
    moved.vertices.row(i) << 1.3 * (std::cos(angle) * p.x() - std::sin(angle) * p.z()) + 0.2, 0.7 * p.y(),
        std::sin(angle) * p.x() + std::cos(angle) * p.z();
  }
  refitted.update(moved.vertices);
  const BodySurface rebuilt(moved);
  std::mt19937 rng(19);
  const std::vector<Eigen::Vector3d> points = hard_points(moved, rng, 1500);
  for (const Eigen::Vector3d& p : points) {
    const SurfacePoint a = refitted.locate(p), b = rebuilt.locate(p);
    INFO("p = " << p.transpose());
    // Exact ties (a point equally close to two faces) may pick either face,
    // whose closest points then differ by rounding only.
    CHECK(a.signed_distance == Approx(b.signed_distance).margin(1e-14));
    CHECK((a.point - b.point).norm() <= 1e-14);
  }
  check_against_reference(refitted, moved, {points.begin(), points.begin() + 300});
  CHECK(refitted.vertex_normals().isApprox(rebuilt.vertex_normals()));
}

// Normals left to the queries: each query's pseudo-normal computed from the
// features it lands on gives the same bits as the whole body's normals
// (vertices, edges and faces hit: the hard points sit on all three), and the
// whole-body accessors refuse until an update computes them again.
TEST_CASE("an update that leaves normals to the queries answers with the same bits") {
  const Mesh m = bumpy_torus();
  Mesh moved = m;
  for (int i = 0; i < moved.num_vertices(); ++i) moved.vertices.row(i) *= 1.0 + 0.1 * std::sin(3.0 * m.vertices(i, 0));
  BodySurface all(m), on_demand(m);
  all.update(moved.vertices);
  on_demand.update(moved.vertices, BodySurface::Normals::on_demand);
  std::mt19937 rng(29);
  const std::vector<Eigen::Vector3d> points = hard_points(moved, rng, 1500);
  int on_vertex = 0, on_edge = 0;
  for (const Eigen::Vector3d& p : points) {
    const SurfacePoint a = all.locate(p), b = on_demand.locate(p);
    INFO("p = " << p.transpose());
    CHECK(a.face == b.face);
    CHECK(a.signed_distance == b.signed_distance);
    CHECK(a.normal == b.normal);
    on_vertex += b.feature <= drape::geometry::TriangleFeature::vertex_c;
    on_edge += b.feature >= drape::geometry::TriangleFeature::edge_ab && b.feature <= drape::geometry::TriangleFeature::edge_ca;
  }
  CHECK(on_vertex > 10);
  CHECK(on_edge > 10);
  CHECK_THROWS_WITH(on_demand.vertex_normals(), Catch::Contains("left to the queries"));
  CHECK_THROWS_WITH(on_demand.face_normals(), Catch::Contains("left to the queries"));
  on_demand.update(moved.vertices);
  CHECK(on_demand.vertex_normals() == all.vertex_normals());
}

TEST_CASE("batch queries equal single queries: max_distance limits the search") {
  const Mesh m = drape::geometry::icosphere(3);
  const BodySurface surface(m);
  std::mt19937 rng(23);
  Eigen::MatrixX3d points(2000, 3);
  for (int i = 0; i < points.rows(); ++i) points.row(i) = (0.5 + std::abs(random_direction(rng)[0])) * random_direction(rng);
  const std::vector<SurfacePoint> batch = surface.locate_all(points);
  const Eigen::VectorXd distances = surface.signed_distances(points);
  for (int i = 0; i < points.rows(); ++i) {
    const SurfacePoint s = surface.locate(points.row(i).transpose());
    CHECK(batch[i].face == s.face);
    CHECK(batch[i].signed_distance == s.signed_distance);
    CHECK(distances[i] == s.signed_distance);
    const drape::BodyQuery::Hit hit = surface.closest(points.row(i).transpose());
    CHECK(hit.signed_distance == s.signed_distance);
    const SurfacePoint limited = surface.locate(points.row(i).transpose(), 0.2);
    if (std::abs(s.signed_distance) < 0.2 * (1 - 1e-12)) CHECK(limited.signed_distance == s.signed_distance);
    if (std::abs(s.signed_distance) > 0.2 * (1 + 1e-12)) CHECK(limited.face == -1);
  }
}

TEST_CASE("faces_crossed finds every face a segment pierces, as a test of every face does") {
  // Segments of every length and slant over the bumpy torus, some along an
  // axis (a zero direction component in the slab test), some with an end on
  // a vertex: the hierarchy's segment walk must not lose a face.
  const Mesh m = bumpy_torus();
  const BodySurface surface(m.vertices, m.faces);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  const std::vector<Eigen::Vector3d> starts = hard_points(m, rng, 600);
  int pierced = 0;
  for (std::size_t i = 0; i < starts.size(); ++i) {
    const Eigen::Vector3d p = starts[i];
    Eigen::Vector3d d = random_direction(rng);
    if (i % 5 == 0) d = Eigen::Vector3d::Unit(static_cast<int>(i / 5 % 3));
    const Eigen::Vector3d q = p + std::pow(10.0, -3 + 3.5 * unit(rng)) * d;
    std::vector<int> found;
    surface.faces_crossed(p, q, found);
    std::sort(found.begin(), found.end());
    std::vector<int> every;
    for (int f = 0; f < m.num_faces(); ++f)
      if (drape::geometry::segment_pierces_triangle(p, q, m.vertices.row(m.faces(f, 0)), m.vertices.row(m.faces(f, 1)),
                                                    m.vertices.row(m.faces(f, 2))))
        every.push_back(f);
    INFO("p = " << p.transpose() << ", q = " << q.transpose());
    CHECK(found == every);
    pierced += !every.empty();
  }
  CHECK(pierced > 150);  // (the sample crosses the surface often enough to mean something)
}

TEST_CASE("bad body meshes are refused with a message naming the problem") {
  Mesh m = drape::geometry::icosphere(0);
  m.faces(7, 1) = 12;
  CHECK_THROWS_WITH(BodySurface(m), Catch::Contains("face 7") && Catch::Contains("vertex 12"));
  const Mesh ok = drape::geometry::icosphere(0);
  BodySurface surface(ok);
  CHECK_THROWS_WITH(surface.update(Eigen::MatrixX3d::Zero(5, 3)), Catch::Contains("5 vertices") && Catch::Contains("12"));
  CHECK_THROWS_AS(BodySurface(Eigen::MatrixX3d::Zero(3, 3), Eigen::MatrixX3i(0, 3)), drape::Error);
}

TEST_CASE("locate_excluding finds the closest point on the faces outside one label") {
  const Mesh m = drape::geometry::icosphere(2);
  const BodySurface surface(m);
  // Label the faces by the octant of their centroid: 8 labels, each a patch of the sphere.
  std::vector<int> label(static_cast<std::size_t>(m.num_faces()));
  for (int f = 0; f < m.num_faces(); ++f) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) c += m.vertices.row(m.faces(f, k)).transpose();
    label[static_cast<std::size_t>(f)] = (c.x() > 0) + 2 * (c.y() > 0) + 4 * (c.z() > 0);
  }
  std::mt19937 rng(31);
  const std::vector<Eigen::Vector3d> points = hard_points(m, rng, 300);
  for (const Eigen::Vector3d& p : points) {
    const SurfacePoint near = surface.locate(p);
    const int excluded = label[static_cast<std::size_t>(near.face)];
    const SurfacePoint far = surface.locate_excluding(p, label, excluded);
    INFO("p = " << p.transpose());
    REQUIRE(far.face >= 0);
    CHECK(label[static_cast<std::size_t>(far.face)] != excluded);
    // Exhaustively over the faces that are not excluded.
    long double best = INFINITY;
    for (int f = 0; f < m.num_faces(); ++f)
      if (label[static_cast<std::size_t>(f)] != excluded)
        best = std::min(best, drape::test::triangle_distance2(p, m.vertices.row(m.faces(f, 0)), m.vertices.row(m.faces(f, 1)),
                                                             m.vertices.row(m.faces(f, 2))));
    CHECK(std::abs(std::abs(far.signed_distance) - static_cast<double>(std::sqrt(best))) <= 1e-12);
    CHECK(std::abs(far.signed_distance) >= std::abs(near.signed_distance));
    // The sign says which side of the far face's plane the point is on (of its
    // edge's or vertex's pseudo-normal off the face interior, as locate()).
    if (far.feature == drape::geometry::TriangleFeature::interior) {
      const Eigen::Vector3d a = m.vertices.row(m.faces(far.face, 0)), b = m.vertices.row(m.faces(far.face, 1)),
                            c = m.vertices.row(m.faces(far.face, 2));
      CHECK((far.signed_distance < 0) == ((p - a).dot((b - a).cross(c - a)) < 0));
    }
    // Excluding a label no face has is the plain search.
    CHECK(surface.locate_excluding(p, label, -1).signed_distance == near.signed_distance);
  }
  CHECK_THROWS_WITH(surface.locate_excluding(points[0], std::vector<int>(3, 0), 0),
                    Catch::Contains("3 face labels given, the body has 320 faces"));
}

// PseudoNormals signs a closest point found elsewhere from the features it
// needs alone: it must give locate()'s sign and normal bit for bit, next to
// vertices and edges too, on a body that has moved since the surface was built.
TEST_CASE("PseudoNormals signs a closest point exactly as locate does, on a moved body") {
  Mesh m = bumpy_torus();
  const drape::geometry::PseudoNormals signs(m.faces);
  BodySurface surface(m);
  // Move the body: the pseudo-normals are computed from the vertices given.
  for (int i = 0; i < m.num_vertices(); ++i) m.vertices.row(i) *= 1.0 + 0.05 * std::cos(3.0 * m.vertices(i, 1));
  surface.update(m.vertices);
  std::mt19937 rng(5);
  const double tolerance = drape::geometry::on_surface_tolerance(m.vertices);
  int inside = 0, on_features = 0;
  for (const Eigen::Vector3d& p : hard_points(m, rng, 3000)) {
    const SurfacePoint expected = surface.locate(p);
    SurfacePoint unsigned_hit = expected;
    unsigned_hit.signed_distance = 0;
    unsigned_hit.normal.setZero();
    const SurfacePoint got = signs.sign(m.vertices, p, unsigned_hit, tolerance);
    INFO("p = " << p.transpose());
    CHECK(got.signed_distance == expected.signed_distance);
    CHECK(got.normal == expected.normal);
    inside += expected.signed_distance < 0;
    on_features += expected.feature != drape::geometry::TriangleFeature::interior;
  }
  CHECK(inside > 300);
  CHECK(on_features > 500);  // next to vertices and edges: a fifth or more of the points
  CHECK_THROWS_WITH(signs.sign(m.vertices, Eigen::Vector3d::Zero(), SurfacePoint{}, tolerance), Catch::Contains("face -1"));
}
