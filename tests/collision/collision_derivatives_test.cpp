// Finite-difference checks of the collision energy's gradient and exact Hessian,
// PSD projection, a stiff case, the linear tail of max_depth, and the constant
// sparsity pattern the solver relies on.
#include "collision_test_util.hpp"

#include <catch2/catch.hpp>

#include <drape/energy.hpp>
#include <drape/physics/solver.hpp>

#include <Eigen/Eigenvalues>

#include <set>

using namespace drape;
using namespace drape::test;
using geometry::TriangleFeature;

namespace {

// Points near a body, a step of length |t|, t in [lo, hi], from a random face
// point: into the body (t < 0) along the face normal from a face interior; out
// of it (t > 0) along the normal from a face interior, tilted over an edge from
// a point on that edge, about the vertex normal from a corner (in turn). On
// convex parts the outward steps from edges and corners end nearest that edge or
// corner, and the inward ones stay off the medial axis (where the distance has
// a kink: a step in from an edge would land on it). The actual closest feature
// is whatever the body says.
Eigen::MatrixX3d points_near_faces(const geometry::BodySurface& body, int count, double lo, double hi,
                                   std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> face(0, static_cast<int>(body.faces().rows()) - 1);
  std::uniform_real_distribution<double> u(0, 1), offset(lo, hi), tilt(0.1, 0.8);
  Eigen::MatrixX3d x(count, 3);
  for (int i = 0; i < count; ++i) {
    const int f = face(rng);
    Eigen::Vector3d corner[3];
    for (int k = 0; k < 3; ++k) corner[k] = body.vertices().row(body.faces()(f, k));
    const Eigen::Vector3d n = (corner[1] - corner[0]).cross(corner[2] - corner[0]).normalized();
    const double t = offset(rng);
    Eigen::Vector3d w(u(rng), u(rng), u(rng));
    if (t > 0 && i % 3 > 0) w[2] = 0;  // on edge ab
    if (t > 0 && i % 3 > 1) w[1] = 0;  // at corner a
    w /= w.sum();
    const Eigen::Vector3d p = w[0] * corner[0] + w[1] * corner[1] + w[2] * corner[2];
    Eigen::Vector3d dir = n;
    if (t > 0 && i % 3 == 1) {
      const Eigen::Vector3d edge = (corner[1] - corner[0]).normalized();
      Eigen::Vector3d away = p - corner[2];
      away = (away - away.dot(edge) * edge).normalized();
      dir = (n + tilt(rng) * away).normalized();
    } else if (t > 0 && i % 3 == 2) {
      // Off the vertex normal: on a symmetric mesh it lies in a mirror plane, and
      // outside a concave vertex that plane is where two faces are equally near.
      const Eigen::Vector3d jitter(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5);
      dir = (body.vertex_normals().row(body.faces()(f, 0)).transpose() + 0.4 * jitter).normalized();
    }
    x.row(i) = p + t * dir;
  }
  return x;
}

struct FeatureCounts {
  int interior = 0, edge = 0, vertex = 0, inside = 0, in_margin = 0;
  int inside_off_face = 0;  // inside, nearest an edge or a vertex: a concave part of the body
};

FeatureCounts count_features(const geometry::BodySurface& body, const Eigen::MatrixX3d& x, double margin) {
  FeatureCounts c;
  for (const auto& s : body.locate_all(x)) {
    if (s.signed_distance >= margin) continue;
    ++c.in_margin;
    if (s.signed_distance < 0) ++c.inside;
    if (s.signed_distance < 0 && s.feature != TriangleFeature::interior) ++c.inside_off_face;
    if (s.feature == TriangleFeature::interior) ++c.interior;
    else if (s.feature == TriangleFeature::edge_ab || s.feature == TriangleFeature::edge_bc ||
             s.feature == TriangleFeature::edge_ca) ++c.edge;
    else ++c.vertex;
  }
  return c;
}

Eigen::MatrixXd dense_hessian(const Energy& e, const Eigen::MatrixX3d& x, bool project) {
  Triplets t;
  e.add_hessian(x, t, project);
  Eigen::SparseMatrix<double> h(3 * x.rows(), 3 * x.rows());
  h.setFromTriplets(t.begin(), t.end());
  return Eigen::MatrixXd(h);
}

}  // namespace

TEST_CASE("collision derivatives match finite differences where closest points are inside faces", "[collision][gradcheck]") {
  // A large, finely tessellated sphere: points within a few mm of it project
  // into face interiors, where the tangent-plane Hessian is exact.
  const geometry::BodySurface body = sphere_body(3, 0.5);
  const auto garment = grid_garment(6, 0.02);
  const Eigen::Vector3d center(1.0 / 3, 1.0 / 3, 1.0 / 3);
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> face(0, static_cast<int>(body.faces().rows()) - 1);
  Eigen::MatrixX3d x(36, 3);
  for (int v = 0; v < 36; ++v) {
    const double offset = -0.006 + 0.011 * (v + 0.5) / 36;  // inside the body, in the margin and beyond
    x.row(v) = off_face(body, face(rng), center, offset);
  }
  const FeatureCounts c = count_features(body, x, 0.003);
  REQUIRE(c.interior == c.in_margin);
  REQUIRE(c.inside >= 5);
  REQUIRE(c.in_margin - c.inside >= 5);
  REQUIRE(c.in_margin < 36);  // some beyond the margin too
  const auto e = collision_energy("{}", *garment, &body);
  const GradCheckReport r = check_energy_derivatives(*e, x);
  INFO(r.str());
  CHECK(r.entries.size() == 4);
  CHECK(r.ok(1e-6));
}

TEST_CASE("collision's exact Hessian includes the body's curvature at edges and vertices", "[collision][gradcheck]") {
  // A coarse icosahedron: points outside it are mostly nearest an edge or a
  // vertex, where the signed distance is curved (distance to a line or point).
  const geometry::BodySurface body = sphere_body(0, 0.2);
  const auto garment = grid_garment(7, 0.02);
  const Eigen::MatrixX3d x = points_near_faces(body, 49, -0.01, 0.006, 21);
  const FeatureCounts c = count_features(body, x, 0.01);
  INFO("interior " << c.interior << ", edge " << c.edge << ", vertex " << c.vertex);
  REQUIRE(c.edge >= 3);
  REQUIRE(c.vertex >= 1);
  const auto e = collision_energy("{margin: 0.01}", *garment, &body);
  const GradCheckReport r = check_energy_derivatives(*e, x);
  INFO(r.str());
  CHECK(r.ok(1e-5));
  // Outside a convex body the curvature term is negative in the tangent
  // directions: the exact Hessian is indefinite and the projection matters.
  const Eigen::MatrixXd exact = dense_hessian(*e, x, false);
  CHECK(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(exact).eigenvalues().minCoeff() < 0);
}

TEST_CASE("collision derivatives and PSD projection on a torus, with concave and saddle regions", "[collision][gradcheck]") {
  const geometry::BodySurface body(geometry::torus(0.3, 0.1, 24, 12));
  const auto garment = grid_garment(8, 0.02);
  const Eigen::MatrixX3d x = points_near_faces(body, 64, -0.015, 0.008, 5);
  const FeatureCounts c = count_features(body, x, 0.01);
  INFO("interior " << c.interior << ", edge " << c.edge << ", vertex " << c.vertex << ", inside " << c.inside);
  REQUIRE(c.inside >= 10);
  REQUIRE(c.edge + c.vertex >= 5);
  const auto e = collision_energy("{margin: 0.01}", *garment, &body);
  const GradCheckReport r = check_energy_derivatives(*e, x);
  INFO(r.str());
  CHECK(r.ok(1e-5));
}

TEST_CASE("collision keeps the body's curvature in the projected Hessian inside concave parts", "[collision][gradcheck]") {
  // An icosahedron turned inside out is a body everywhere concave: the cavity
  // is outside it. Points just outside the original solid are inside this body,
  // nearest its edges and vertices, where -k a phi' D is positive semi-definite:
  // the projection must keep it (tangential stiffness), not drop it.
  const Mesh solid = geometry::icosphere(0, 0.2);
  Eigen::MatrixX3i inverted = solid.faces;
  inverted.col(1).swap(inverted.col(2));
  const geometry::BodySurface cavity(solid.vertices, inverted);
  const geometry::BodySurface convex(solid);
  const Eigen::MatrixX3d x = points_near_faces(convex, 36, 0.0005, 0.006, 9);
  const FeatureCounts c = count_features(cavity, x, 0.003);
  INFO("interior " << c.interior << ", edge " << c.edge << ", vertex " << c.vertex << ", inside " << c.inside);
  REQUIRE(c.inside == 36);
  REQUIRE(c.inside_off_face >= 12);
  const auto garment = grid_garment(6, 0.02);
  const auto e = collision_energy("{}", *garment, &cavity);
  const GradCheckReport r = check_energy_derivatives(*e, x);
  INFO(r.str());
  CHECK(r.ok(1e-5));
  const Eigen::MatrixXd exact = dense_hessian(*e, x, false), projected = dense_hessian(*e, x, true);
  CHECK((exact - projected).norm() <= 1e-12 * exact.norm());
  // Blocks of vertices nearest an edge or a vertex have rank 2 or 3, not 1.
  int curved = 0;
  for (int v = 0; v < 36; ++v) {
    const Eigen::Matrix3d block = projected.block<3, 3>(3 * v, 3 * v);
    const Eigen::Vector3d eig = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(block).eigenvalues();
    CHECK(eig.minCoeff() >= -1e-12 * eig.maxCoeff());
    curved += eig[1] > 1e-6 * eig[2];
  }
  CHECK(curved == c.inside_off_face);
}

TEST_CASE("collision derivatives hold for a very stiff penalty", "[collision][gradcheck]") {
  const geometry::BodySurface body = sphere_body(3, 0.5);
  const auto garment = grid_garment(5, 0.02);
  const Eigen::MatrixX3d x = points_at_distances(body, Eigen::Vector3d::Zero(), 25, -0.004, 0.004, 17);
  const auto e = collision_energy("{stiffness: 1e13}", *garment, &body);
  Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(25, 3);
  e->add_gradient(x, g);
  REQUIRE(g.cwiseAbs().maxCoeff() > 1e3);
  const GradCheckReport r = check_energy_derivatives(*e, x);
  INFO(r.str());
  CHECK(r.ok(1e-5));
}

TEST_CASE("collision with max_depth: linear beyond it, still pushing outward, derivatives exact", "[collision][gradcheck]") {
  const geometry::BodySurface body = sphere_body(3, 0.5);
  const auto garment = grid_garment(5, 0.02);
  // Depths from 0 to 4 cm, on both sides of max_depth = 1 cm.
  const Eigen::MatrixX3d x = points_at_distances(body, Eigen::Vector3d::Zero(), 25, -0.04, 0.0, 23);
  const auto capped = collision_energy("{max_depth: 0.01}", *garment, &body);
  const auto cubic = collision_energy("{}", *garment, &body);
  const GradCheckReport r = check_energy_derivatives(*capped, x);
  INFO(r.str());
  CHECK(r.ok(1e-6));

  Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(25, 3), g_cubic = Eigen::MatrixX3d::Zero(25, 3);
  capped->add_gradient(x, g);
  cubic->add_gradient(x, g_cubic);
  const Eigen::VectorXd area = [&] {
    Eigen::VectorXd a = Eigen::VectorXd::Zero(25);
    const Mesh& m = garment->mesh;
    for (int f = 0; f < m.num_faces(); ++f)
      for (int k = 0; k < 3; ++k) a[m.faces(f, k)] += 0.02 * 0.02 / 6;
    return a;
  }();
  int deep = 0;
  for (int v = 0; v < 25; ++v) {
    const auto s = body.locate(x.row(v).transpose());
    const double delta = 0.003 - s.signed_distance;
    const double push = -g.row(v).dot(s.normal);  // outward force
    if (s.signed_distance < -0.01) {
      ++deep;
      CHECK(push == Approx(1e7 * area[v] * 0.013 * 0.013).epsilon(1e-9));  // capped at the max_depth pressure
      CHECK(push < -g_cubic.row(v).dot(s.normal));
    } else {
      CHECK(push == Approx(1e7 * area[v] * delta * delta).epsilon(1e-9));
    }
    CHECK((g.row(v) + push * s.normal.transpose()).norm() <= 1e-9 * push);  // along the normal only
  }
  CHECK(deep >= 10);
  CHECK(capped->value(x) < cubic->value(x));
}

TEST_CASE("collision emits one 3x3 diagonal block per vertex whatever the contact state", "[collision]") {
  const geometry::BodySurface body = sphere_body(3, 0.2);
  const auto garment = grid_garment(5, 0.02);
  const auto e = collision_energy("{}", *garment, &body);
  const Eigen::MatrixX3d far = points_at_distances(body, Eigen::Vector3d::Zero(), 25, 0.01, 0.05, 1);
  const Eigen::MatrixX3d mixed = points_at_distances(body, Eigen::Vector3d::Zero(), 25, -0.01, 0.01, 2);
  auto pattern = [&](const Eigen::MatrixX3d& x, bool project) {
    Triplets h = {{0, 0, 1.0}};  // appended to, never cleared
    e->add_hessian(x, h, project);
    std::vector<std::pair<int, int>> p;
    for (std::size_t i = 1; i < h.size(); ++i) p.emplace_back(h[i].row(), h[i].col());
    REQUIRE(h[0].value() == 1.0);
    return p;
  };
  const auto reference = pattern(far, true);
  REQUIRE(reference.size() == 9 * 25);
  std::set<std::pair<int, int>> distinct(reference.begin(), reference.end());
  CHECK(distinct.size() == 9 * 25);
  for (const auto& [r, c] : reference) CHECK(r / 3 == c / 3);
  CHECK(pattern(mixed, true) == reference);
  CHECK(pattern(mixed, false) == reference);
  CHECK(dense_hessian(*e, far, true).isZero(0.0));
  CHECK(!dense_hessian(*e, mixed, true).isZero(0.0));
}

TEST_CASE("smooth collision derivatives match finite differences on a torus, across its creases and saddles",
          "[collision][gradcheck][smooth]") {
  // Points within the margin of the torus, inside it, and beyond: with
  // smoothing every vertex within R blends in, so no face or edge is special.
  const geometry::BodySurface body(geometry::torus(0.3, 0.1, 24, 12));
  const auto garment = grid_garment(8, 0.02);
  const Eigen::MatrixX3d x = points_near_faces(body, 64, -0.015, 0.008, 5);
  const auto e = collision_energy("{margin: 0.01, smoothing: 0.06}", *garment, &body);
  const GradCheckReport r = check_energy_derivatives(*e, x);
  INFO(r.str());
  CHECK(r.entries.size() == 4);
  CHECK(r.ok(1e-5));
  // The projected Hessian is PSD; the exact one is not (the blended surface curves).
  const Eigen::MatrixXd projected = dense_hessian(*e, x, true);
  CHECK(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(projected).eigenvalues().minCoeff() > -1e-9 * projected.norm());
  const Eigen::MatrixXd exact = dense_hessian(*e, x, false);
  CHECK(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(exact).eigenvalues().minCoeff() < 0);
}

namespace {

// Two faces meeting at a 90-degree concave crease along z (an L-shaped
// trough, the body below/left): floor y = 0 for x in [0, 1], wall x = 0 for
// y in [0, 1], z in [-1, 1], on a fine grid, faces oriented into the trough.
geometry::BodySurface crease_body() {
  const double s = 0.05;
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> f;
  const int n = 20;
  auto add_quad_grid = [&](auto at) {
    const int base = static_cast<int>(v.size());
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) v.push_back(at(double(i) / n, double(j) / n));
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const int a = base + i * (n + 1) + j, b = a + 1, c = a + n + 1, d = c + 1;
        f.emplace_back(a, c, b);
        f.emplace_back(b, c, d);
      }
  };
  add_quad_grid([&](double u, double w) { return Eigen::Vector3d(u * 20 * s, 0, (2 * w - 1) * 20 * s); });  // floor
  add_quad_grid([&](double u, double w) { return Eigen::Vector3d(0, u * 20 * s, (2 * w - 1) * 20 * s); });  // wall
  Eigen::MatrixX3d vertices(static_cast<Eigen::Index>(v.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i) vertices.row(static_cast<Eigen::Index>(i)) = v[i];
  Eigen::MatrixX3i faces(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < f.size(); ++i) faces.row(static_cast<Eigen::Index>(i)) = f[i];
  // Orient every face towards +x +y (into the trough, "outside" the body).
  for (Eigen::Index i = 0; i < faces.rows(); ++i) {
    const Eigen::Vector3d a = vertices.row(faces(i, 0)), b = vertices.row(faces(i, 1)), c = vertices.row(faces(i, 2));
    if ((b - a).cross(c - a).dot(Eigen::Vector3d(1, 1, 0)) < 0) std::swap(faces(i, 1), faces(i, 2));
  }
  return geometry::BodySurface(vertices, faces);
}

}  // namespace

namespace {

// The collision's push (its gradient) on two points a and b near a body, with
// the one-sided distance (creases off) and with the crease contact; the
// garment's other two vertices are far from the body. Margin 2 cm.
struct CreasePushes {
  Eigen::MatrixX3d one_sided, two_sided;  // rows 0 and 1: a and b
  double one_sided_energy = 0, two_sided_energy = 0;
  // How far the push turns from a to b (|difference of the unit pushes|).
  double turn_one_sided() const { return (one_sided.row(0).normalized() - one_sided.row(1).normalized()).norm(); }
  double turn_two_sided() const { return (two_sided.row(0).normalized() - two_sided.row(1).normalized()).norm(); }
};

CreasePushes crease_pushes(const geometry::BodySurface& body, const Eigen::RowVector3d& a, const Eigen::RowVector3d& b,
                           const Eigen::RowVector3d& far) {
  const auto garment = grid_garment(2, 0.02);
  const auto one_sided = collision_energy("{margin: 0.02, creases: false}", *garment, &body);
  const auto two_sided = collision_energy("{margin: 0.02}", *garment, &body);
  Eigen::MatrixX3d x(4, 3);
  x << a, b, far, far + Eigen::RowVector3d(0.05, 0, 0);
  CreasePushes out;
  out.one_sided = out.two_sided = Eigen::MatrixX3d::Zero(4, 3);
  out.one_sided_energy = one_sided->add_gradient(x, out.one_sided);
  out.two_sided_energy = two_sided->add_gradient(x, out.two_sided);
  return out;
}

}  // namespace

TEST_CASE("smooth collision has no kink in a concave crease, where the exact distance switches faces",
          "[collision][smooth]") {
  // Two faces meeting at a 90-degree concave crease along z (an L-shaped
  // trough, the body below/left). Along the bisector the closest face of the
  // exact distance switches; its gradient jumps there. The smooth distance's
  // gradient is continuous across it.
  const geometry::BodySurface body = crease_body();
  const auto garment = grid_garment(2, 0.02);  // 4 vertices, the points below
  const auto exact = collision_energy("{margin: 0.02, creases: false}", *garment, &body);
  const auto smooth = collision_energy("{margin: 0.02, smoothing: 0.08}", *garment, &body);
  // Two points 1 mm either side of the bisector x = y, 1 cm from the crease line, well inside the margin.
  const double h = 1e-3, r = 0.01;
  Eigen::MatrixX3d x(4, 3);
  x.row(0) << r + h, r - h, 0.0;
  x.row(1) << r - h, r + h, 0.0;
  x.row(2) << 0.5, 0.5, 0.0;  // far away, no contact
  x.row(3) << 0.6, 0.5, 0.0;
  auto grad = [&](const Energy& e) {
    Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(4, 3);
    e.add_gradient(x, g);
    return g;
  };
  const Eigen::MatrixX3d ge = grad(*exact), gs = grad(*smooth);
  // The push on the two points, 2 mm apart (their lumped areas differ, so compare directions).
  const double turn_exact = (ge.row(0).normalized() - ge.row(1).normalized()).norm();
  const double turn_smooth = (gs.row(0).normalized() - gs.row(1).normalized()).norm();
  INFO("exact " << ge.row(0) << " | " << ge.row(1) << "; smooth " << gs.row(0) << " | " << gs.row(1));
  CHECK(turn_exact > 1.4);    // 90 degrees: the exact push flips from one wall to the other
  CHECK(turn_smooth < 0.15);  // under 9 degrees: the smooth push turns gradually
  CHECK(ge.row(2).norm() == 0.0);
  CHECK(gs.row(2).norm() == 0.0);
}

TEST_CASE("with creases on (the default) both walls of a concave crease push, and the push turns smoothly",
          "[collision][crease]") {
  // The trough above: the floor's faces point up, the wall's along +x, so they
  // fall in different normal groups and each is the other's far side.
  const double h = 1e-5, r = 0.01;
  const CreasePushes push = crease_pushes(crease_body(), {r + h, r - h, 0.013},  // nearer the floor (y = 0)
                                          {r - h, r + h, 0.013},                 // nearer the wall (x = 0)
                                          {0.5, 0.5, 0.0});
  const Eigen::MatrixX3d& g2 = push.two_sided;
  INFO("one-sided " << push.one_sided.topRows(2) << "; two-sided " << g2.topRows(2));
  // 20 um apart across the bisector the one-sided push flips by 90 degrees; the
  // sum of both walls' pushes hardly turns.
  CHECK(push.turn_one_sided() > 1.4);
  CHECK(push.turn_two_sided() < 1e-2);
  // Point 0: the floor pushes up (its near side) and the wall along +x (c = 0.7 here, weight 1).
  const double floor = std::pow(0.02 - (r - h), 2), wall = std::pow(0.02 - (r + h), 2);
  CHECK(-g2(0, 1) / -g2(0, 0) == Approx(floor / wall).epsilon(1e-9));
  CHECK(push.two_sided_energy > push.one_sided_energy);
}

TEST_CASE("crease collision derivatives match finite differences in the gap of a crease", "[collision][crease][gradcheck]") {
  // Points all over the trough's gap: on and off its bisector, near one wall
  // (where the far wall's weight w(c) is between 0 and 1), slightly inside a
  // wall (where the far term fades out) and beyond the margin.
  const geometry::BodySurface body = crease_body();
  const auto garment = grid_garment(5, 0.02);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-0.004, 0.02), z(-0.05, 0.05);
  Eigen::MatrixX3d x(25, 3);
  for (int v = 0; v < 25; ++v) x.row(v) << u(rng), u(rng), z(rng);
  // z = 0 is a line of the grid: points there project onto an edge of the flat
  // floor, where the one-sided distance's Hessian is that of a line (a set of
  // measure zero that the other collision tests avoid too).
  x.row(0) << 0.008, 0.008, 0.013;   // on the bisector
  x.row(1) << 0.012, 0.002, 0.01;    // near the floor: c ~ 0.16 to 0.5 across its neighbourhood
  x.row(2) << 0.015, 0.004, 0.02;
  x.row(3) << 0.009, -0.0005, 0.013;  // just inside the floor
  for (int v = 0; v < 25; ++v)  // keep out of the trough's solid corner x, y < 0
    if (x(v, 0) < 0 && x(v, 1) < 0) x(v, 0) = -x(v, 0);
  const auto e = collision_energy("{margin: 0.02}", *garment, &body);
  const auto off = collision_energy("{margin: 0.02, creases: false}", *garment, &body);
  REQUIRE(e->value(x) > off->value(x));  // the far side counts somewhere
  const GradCheckReport r = check_energy_derivatives(*e, x);
  INFO(r.str());
  CHECK(r.ok(1e-5));
}

namespace {

// A shallow V-shaped valley along z, the body below: one welded grid over
// u in [-0.2, 0.2] m, each side rising at 12 degrees, so the two sides'
// normals are 24 degrees apart and fall in one normal group (both nearest
// +y of the 26 directions). The faces next to the valley line share its edges.
geometry::BodySurface valley_body() {
  const int n = 20;
  const double slope = std::tan(12.0 * M_PI / 180);
  Eigen::MatrixX3d vertices((n + 1) * (n + 1), 3);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double u = (2.0 * i / n - 1) * 0.2, z = (2.0 * j / n - 1) * 0.2;
      vertices.row(i * (n + 1) + j) << u, std::abs(u) * slope, z;
    }
  Eigen::MatrixX3i faces(2 * n * n, 3);
  for (int i = 0, k = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j, b = a + 1, c = a + n + 1, d = c + 1;
      faces.row(k++) << a, c, b;
      faces.row(k++) << b, c, d;
    }
  for (Eigen::Index i = 0; i < faces.rows(); ++i) {  // face up (+y, "outside")
    const Eigen::Vector3d a = vertices.row(faces(i, 0)), b = vertices.row(faces(i, 1)), c = vertices.row(faces(i, 2));
    if ((b - a).cross(c - a).y() < 0) std::swap(faces(i, 1), faces(i, 2));
  }
  return geometry::BodySurface(vertices, faces);
}

}  // namespace

TEST_CASE("in a mild crease between adjacent faces of one normal group both faces push, and the push turns smoothly",
          "[collision][crease]") {
  // Where a heavy body's armpit folds by ~24 degrees, both faces are in one
  // normal group, so no far wall is found outside it; the face across the near
  // face's edge is the far side (c = sin 12 deg = 0.21 on the bisector: full weight).
  const geometry::BodySurface body = valley_body();
  // 10 um either side of the bisector x = 0, 1 cm above the valley line.
  const CreasePushes push = crease_pushes(body, {1e-5, 0.01, 0.013}, {-1e-5, 0.01, 0.013}, {0.1, 0.5, 0.0});
  const Eigen::MatrixX3d& g2 = push.two_sided;
  INFO("one-sided " << push.one_sided.topRows(2) << "; two-sided " << g2.topRows(2));
  CHECK(push.turn_one_sided() > 0.4);   // 24 degrees: the one-sided push flips between the sides
  CHECK(push.turn_two_sided() < 1e-3);  // both sides push on both sides of the bisector
  CHECK(std::abs(g2(0, 0)) < 1e-2 * std::abs(g2(0, 1)));  // straight up: the sideways pushes cancel
  CHECK(push.two_sided_energy > 1.9 * push.one_sided_energy);  // both sides' penalties, nearly equal there

  // Gradient and Hessian against finite differences all over the valley:
  // on and near the bisector, where the weight is partial, beyond the feet's faces.
  const auto grid = grid_garment(5, 0.02);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> across(-0.03, 0.03), up(0.002, 0.018), along(-0.015, 0.035);
  Eigen::MatrixX3d y(25, 3);
  for (int v = 0; v < 25; ++v) y.row(v) << across(rng), std::abs(y(v, 0)) * std::tan(12.0 * M_PI / 180) + up(rng), along(rng);
  y.row(0) << 0.0, 0.008, 0.013;  // on the bisector
  y.row(1) << 0.003, 0.006, 0.011;
  const auto e = collision_energy("{margin: 0.02}", *grid, &body);
  const auto off = collision_energy("{margin: 0.02, creases: false}", *grid, &body);
  REQUIRE(e->value(y) > off->value(y));
  const GradCheckReport r = check_energy_derivatives(*e, y);
  INFO(r.str());
  CHECK(r.ok(1e-5));
}

TEST_CASE("smooth collision refuses a radius within the margin", "[collision][smooth]") {
  const geometry::BodySurface body = sphere_body(2, 0.2);
  const auto garment = grid_garment(2, 0.02);
  CHECK_THROWS_WITH(collision_energy("{margin: 0.01, smoothing: 0.005}", *garment, &body),
                    Catch::Contains("must exceed the margin"));
}

namespace {

// A constant force per vertex: E = sum_v g_v . x_v, so grad E = g.
class ConstantGradient final : public Energy {
 public:
  explicit ConstantGradient(Eigen::MatrixX3d g) : g_(std::move(g)) {}
  void bind(const EnergyContext&) override {}
  double value(const Eigen::MatrixX3d& x) const override { return g_.cwiseProduct(x).sum(); }
  double add_gradient(const Eigen::MatrixX3d& x, Eigen::MatrixX3d& g) const override {
    g += g_;
    return value(x);
  }
  void add_hessian(const Eigen::MatrixX3d&, Triplets&, bool) const override {}

 private:
  Eigen::MatrixX3d g_;
};

}  // namespace

TEST_CASE("stationarity counts both faces of a concave crease, where the plain residual cannot fall",
          "[collision][solver]") {
  // Cloth pressed along the bisector into the crease is held by both walls,
  // half each; the exact contact at any one point pushes off one wall only.
  const geometry::BodySurface body = crease_body();
  const auto garment = grid_garment(2, 0.02);
  auto contact = collision_energy("{margin: 0.02, creases: false}", *garment, &body);
  const double r = 0.01;  // every vertex on the bisector x = y, 1 cm from the crease line
  Eigen::MatrixX3d x(4, 3);
  for (int v = 0; v < 4; ++v) x.row(v) << r, r, 0.1 * v;
  Eigen::MatrixX3d push = Eigen::MatrixX3d::Zero(4, 3);
  contact->add_gradient(x, push);
  Eigen::MatrixX3d balanced(4, 3), unbalanced(4, 3);
  for (int v = 0; v < 4; ++v) {
    const double p = push.row(v).norm();  // the one-wall push, -P n
    REQUIRE(p > 0);
    balanced.row(v) << p / 2, p / 2, 0.0;  // pressed into the corner: half of P on each wall
    unbalanced.row(v) << p, p, 0.0;        // twice harder than the walls push there
  }
  auto measure = [&](const Eigen::MatrixX3d& load, double& plain, double& stationary) {
    std::vector<NamedEnergy> energies;
    energies.push_back({"load", std::make_unique<ConstantGradient>(load)});
    energies.push_back({"collision", collision_energy("{margin: 0.02, creases: false}", *garment, &body)});
    ClothSolver solver(*garment, energies, SolverSettings{});
    plain = solver.static_residual(x);
    stationary = solver.stationarity(x, 1e-3);
  };
  double plain = 0, stationary = 0;
  measure(balanced, plain, stationary);
  INFO("balanced: plain " << plain << ", stationarity " << stationary);
  CHECK(plain > 1);                    // |(P/2, P/2) - P n_wall| = P / sqrt(2) per vertex
  CHECK(stationary < 1e-3 * plain);    // the hull holds (P/2, P/2): balanced
  measure(unbalanced, plain, stationary);
  INFO("unbalanced: plain " << plain << ", stationarity " << stationary);
  CHECK(stationary > 0.1 * plain);     // no combination of the walls' pushes balances it
  CHECK(stationary <= plain);

  // The samples are the pushes 1 mm around the vertex: both walls appear.
  std::vector<Eigen::Vector3d> samples;
  REQUIRE(contact->has_kinks());
  contact->vertex_gradient_samples(x, 0, 1e-3, samples);
  REQUIRE(samples.size() == 6);
  bool floor = false, wall = false;
  for (const auto& g : samples) {
    floor = floor || (g.y() < 0 && std::abs(g.x()) < 1e-9 * g.norm());
    wall = wall || (g.x() < 0 && std::abs(g.y()) < 1e-9 * g.norm());
  }
  CHECK(floor);
  CHECK(wall);
  // The smooth distance has no kink: nothing to sample.
  auto smooth = collision_energy("{margin: 0.02, smoothing: 0.08}", *garment, &body);
  samples.clear();
  CHECK_FALSE(smooth->has_kinks());
  smooth->vertex_gradient_samples(x, 0, 1e-3, samples);
  CHECK(samples.empty());
}
