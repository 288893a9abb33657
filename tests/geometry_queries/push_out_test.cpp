// push_out: vertices inside or too near a body end `margin` outside it,
// checked with the box's signed distance written out by hand (no BodySurface).
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/push_out.hpp>

#include <drape/geometry/closed_shapes.hpp>
#include <drape/geometry/surface_crossings.hpp>

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace drape;
using namespace drape::geometry;

namespace {

// The cube [-1, 1]^3 as 12 outward triangles.
BodySurface unit_cube() {
  Eigen::MatrixX3d v(8, 3);
  v << -1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1;
  Eigen::MatrixX3i f(12, 3);
  f << 0, 1, 5, 0, 5, 4, 3, 7, 6, 3, 6, 2, 4, 5, 6, 4, 6, 7, 0, 3, 2, 0, 2, 1, 1, 2, 6, 1, 6, 5, 0, 4, 7, 0, 7, 3;
  return BodySurface(v, f);
}

// The exact signed distance to the box [-1, 1]^3 (Quilez's sdBox).
double pushed_box_distance(const Eigen::Vector3d& p) {
  const Eigen::Vector3d q = p.cwiseAbs() - Eigen::Vector3d::Ones();
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

// The triangles of an n x n grid of vertices numbered row by row.
Eigen::MatrixX3i grid_faces(int n) {
  Eigen::MatrixX3i faces(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const int a = i * n + j;
      faces.row(f++) << a, a + 1, a + n + 1;
      faces.row(f++) << a, a + n + 1, a + n;
    }
  return faces;
}

}  // namespace

TEST_CASE("push_out moves the vertices inside or within the margin to the margin, and no other", "[geometry][push_out]") {
  const BodySurface cube = unit_cube();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-1.3, 1.3);
  Eigen::MatrixX3d x(400, 3);
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    for (int k = 0; k < 3; ++k) x(i, k) = coordinate(rng);
  const Eigen::MatrixX3d before = x;
  const double margin = 0.01;
  const PushOutReport report = push_out(cube, x, margin);
  int inside_before = 0, moved = 0;
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    const double d0 = pushed_box_distance(before.row(i).transpose()), d1 = pushed_box_distance(x.row(i).transpose());
    inside_before += d0 < 0;
    INFO("vertex " << i << " from distance " << d0);
    if (d0 >= margin) {
      CHECK(x.row(i) == before.row(i));
    } else {
      ++moved;
      // Inside: straight out through the nearest face, to the margin. Outside
      // within it: away from the closest point (face, edge or corner), to the margin.
      CHECK(d1 == Approx(margin).margin(1e-9));
    }
  }
  CHECK(inside_before > 100);
  CHECK(report.moved == moved);
  CHECK(report.still_within == 0);
  CHECK(report.passes == 2);  // one to move, one to find nothing left
  CHECK(report.largest_move <= 1.0 + margin + 1e-9);
  CHECK(report.largest_move > 0.5);

  Eigen::MatrixX3d bad = before;
  bad(3, 1) = NAN;
  CHECK_THROWS_WITH(push_out(cube, bad, margin), Catch::Contains("non-finite"));
  CHECK_THROWS_WITH(push_out(cube, x, -1.0), Catch::Contains("margin"));
}

TEST_CASE("push_out: a vertex under a tent's ridge goes out through the nearer roof", "[geometry][push_out]") {
  Eigen::MatrixX3d v(6, 3);
  // A triangular prism (tent): ridge along z at y = 1, feet at x = +-1, y = 0.
  v << -1, 0, -1, 1, 0, -1, 0, 1, -1, -1, 0, 1, 1, 0, 1, 0, 1, 1;
  Eigen::MatrixX3i f(8, 3);
  f << 0, 2, 1, 3, 4, 5,  // the two ends (z = -1 facing -z, z = 1 facing +z)
      0, 1, 4, 0, 4, 3,   // the floor, facing -y
      1, 2, 5, 1, 5, 4,   // the right roof
      2, 0, 3, 2, 3, 5;   // the left roof
  const BodySurface tent(v, f);
  // Inside, just under the ridge and right of it: the right roof (y = 1 - x)
  // is nearest; pushed along its normal (1, 1, 0) / sqrt(2) to 1 cm outside it.
  Eigen::MatrixX3d x(1, 3);
  x << 0.05, 0.9, 0.0;
  const PushOutReport r = push_out(tent, x, 0.01);
  CHECK(r.still_within == 0);
  const double right_roof = (x(0, 0) + x(0, 1) - 1.0) / std::sqrt(2.0);  // signed distance to the plane x + y = 1
  CHECK(right_roof == Approx(0.01).margin(1e-12));
  CHECK(x(0, 0) - x(0, 1) == Approx(0.05 - 0.9).margin(1e-12));  // moved along the normal only
  CHECK(x(0, 2) == 0.0);
}

// A garment pushed out of body after body: the closest faces of the last body
// start the next body's searches (hints right, stale, wrong or of the wrong
// count) and the normals are left to the queries; the vertices end on the
// same bits as a push-out from a fresh surface without hints.
TEST_CASE("push_out with the last body's faces as hints moves the vertices to the same bits", "[geometry][push_out]") {
  const BodySurface fresh = unit_cube();
  BodySurface kept = unit_cube();
  Eigen::MatrixX3d stretched = fresh.vertices();
  stretched.col(1) *= 1.2;
  kept.update(stretched);  // another body first, so the hints are stale
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coordinate(-1.3, 1.3);
  Eigen::MatrixX3d x(300, 3);
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    for (int k = 0; k < 3; ++k) x(i, k) = coordinate(rng);
  std::vector<int> hints;
  Eigen::MatrixX3d first = x;
  push_out(kept, first, 0.01, 4, &hints);  // the stretched body's faces
  REQUIRE(hints.size() == 300);
  kept.update(fresh.vertices(), BodySurface::Normals::on_demand);
  Eigen::MatrixX3d expected = x;
  const PushOutReport plain = push_out(fresh, expected, 0.01);
  std::uniform_int_distribution<int> any_face(-1, 11);
  std::vector<int> wrong(300);
  for (int& f : wrong) f = any_face(rng);
  for (std::vector<int> given : {hints, wrong, std::vector<int>(7, 3)}) {
    Eigen::MatrixX3d y = x;
    const PushOutReport r = push_out(kept, y, 0.01, 4, &given);
    CHECK(y == expected);
    CHECK(r.moved == plain.moved);
    CHECK(r.passes == plain.passes);
    REQUIRE(given.size() == 300);
    for (Eigen::Index i = 0; i < y.rows(); ++i) CHECK(given[static_cast<std::size_t>(i)] == fresh.locate(y.row(i).transpose()).face);
  }
}

namespace {

// Garment edges through body triangles, by exact orientation tests
// (surface_crossings.hpp, which shares no code with push_out).
int edges_through(const BodySurface& body, const Eigen::MatrixX3d& x, const std::vector<std::array<int, 2>>& edges) {
  int count = 0;
  for (const auto& [a, b] : edges)
    for (Eigen::Index f = 0; f < body.faces().rows(); ++f)
      if (segment_pierces_triangle(x.row(a), x.row(b), body.vertices().row(body.faces()(f, 0)),
                                   body.vertices().row(body.faces()(f, 1)), body.vertices().row(body.faces()(f, 2)))) {
        ++count;
        break;
      }
  return count;
}

}  // namespace

// A chord across a ball of radius 10 cm: both ends 12 mm out (beyond the
// 10 mm margin, so no vertex moves), its middle 3 mm inside. With the edges
// given it is lifted along the ball's normal until its midpoint is 5 mm out,
// and no longer passes through the ball's triangles.
TEST_CASE("push_out with edges lifts an edge whose middle lies in the body", "[geometry][push_out]") {
  const BodySurface ball(icosphere(4, 0.1));
  const double angle = 30.0 * M_PI / 180.0, out = 0.112;
  Eigen::MatrixX3d x(2, 3);
  x << -out * std::sin(angle), out * std::cos(angle), 0.0, out * std::sin(angle), out * std::cos(angle), 0.0;
  const std::vector<std::array<int, 2>> edges = {{0, 1}};
  Eigen::MatrixX3d plain = x;
  const PushOutReport without = push_out(ball, plain, 0.01);
  CHECK(plain == x);  // both vertices beyond the margin
  CHECK(without.moved == 0);
  CHECK(edges_through(ball, plain, edges) == 1);

  PushOutOptions options{.margin = 0.01, .edges = &edges};
  const PushOutReport with = push_out(ball, x, options);
  CHECK(with.edges_lifted == 1);
  CHECK(with.moved == 2);
  CHECK(edges_through(ball, x, edges) == 0);
  const Eigen::Vector3d mid = 0.5 * (x.row(0) + x.row(1)).transpose();
  CHECK(ball.locate(mid).signed_distance == Approx(0.005).margin(1e-9));  // margin / 2 out
  CHECK(x(0, 0) - x(1, 0) == Approx(-2 * out * std::sin(angle)).margin(1e-12));  // lifted, not stretched

  // An edge far from the ball is not searched (the Lipschitz bound clears it).
  Eigen::MatrixX3d far(2, 3);
  far << 0.3, 0.0, 0.0, 0.3, 0.05, 0.0;
  const PushOutReport skipped = push_out(ball, far, options);
  CHECK(skipped.edges_searched == 0);

  const std::vector<std::array<int, 2>> bad = {{0, 2}};
  options.edges = &bad;
  CHECK_THROWS_WITH(push_out(ball, x, options), Catch::Contains("edge (0, 2)"));
}

// A sheet pressed onto a knob (a ball of 1.5 cm radius, a ridge's
// curvature) 5 mm through its top: a grid of 2.5 cm squares, the coarse
// shirt's edge length. The vertices alone, pushed out to the margin, leave
// the knob through the sheet between them; with the edges, no edge passes
// through it and no knob edge through the sheet (surface_crossings, exact
// orientation tests that share no code with push_out), every vertex at
// least the margin out.
TEST_CASE("push_out with edges leaves a sheet pressed onto a knob uncrossed", "[geometry][push_out]") {
  const BodySurface knob(icosphere(4, 0.015));
  const int n = 7;
  Eigen::MatrixX3d sheet(n * n, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) sheet.row(i * n + j) << 0.025 * (i - n / 2) + 0.004, 0.010, 0.025 * (j - n / 2) + 0.007;
  const Eigen::MatrixX3i faces = grid_faces(n);
  const std::vector<std::array<int, 2>> edges = edge_list(faces);
  CHECK(edges.size() == static_cast<std::size_t>(2 * n * (n - 1) + (n - 1) * (n - 1)));
  auto crossings = [&](const Eigen::MatrixX3d& x) { return surface_crossings(x, faces, knob.vertices(), knob.faces()).total(); };
  REQUIRE(crossings(sheet) > 0);
  Eigen::MatrixX3d vertices_only = sheet;
  push_out(knob, vertices_only, 0.006);
  const int left = crossings(vertices_only);
  CHECK(left > 0);
  PushOutOptions options{.margin = 0.006, .edges = &edges};
  Eigen::MatrixX3d with_edges = sheet;
  const PushOutReport r = push_out(knob, with_edges, options);
  INFO(left << " crossings with the vertices alone; " << r.edges_lifted << " lifts, " << r.passes << " passes");
  CHECK(r.edges_lifted > 0);
  CHECK(crossings(with_edges) == 0);
  CHECK(knob.signed_distances(with_edges).minCoeff() >= 0.006 - 1e-9);
}

// A ridge that crosses an edge a quarter of the way along (the human rig's
// thinnest shoulders): a prism whose cross-section rises along a slope of
// 0.62 to a ridge 0.5 mm above the edge and drops by a vertical wall. The
// edge's ends are 6.7 and 10.8 mm out (beyond the 6 mm margin: no vertex
// moves) and its middle 3.4 mm out, beyond half the margin: only the quarter
// point, 0.3 mm inside, shows the crossing.
TEST_CASE("push_out with edges lifts an edge that a ridge crosses off its middle", "[geometry][push_out]") {
  // Cross-section (x, z) in metres: ridge top, foot of the slope, two bottom corners; extruded along y.
  const double top = 0.0005, slope = 0.62;
  const double xs[4] = {0.0, 0.05, 0.05, 0.0}, zs[4] = {top, top - slope * 0.05, -0.05, -0.05};
  Eigen::MatrixX3d v(8, 3);
  for (int k = 0; k < 4; ++k) {
    v.row(k) << xs[k], -0.05, zs[k];
    v.row(4 + k) << xs[k], 0.05, zs[k];
  }
  Eigen::MatrixX3i f(12, 3);
  // Sides (k -> k+1 around the section), then the two caps.
  f << 0, 4, 5, 0, 5, 1, 1, 5, 6, 1, 6, 2, 2, 6, 7, 2, 7, 3, 3, 7, 4, 3, 4, 0, 0, 1, 2, 0, 2, 3, 4, 7, 6, 4, 6, 5;
  f.col(1).swap(f.col(2));  // listed inward above: turned outward
  const BodySurface ridge(v, f);
  Eigen::MatrixX3d x(2, 3);
  x << -0.0067, 0.0, 0.0, 0.0213, 0.0, 0.0;  // the quarter point under the ridge top
  const Eigen::Vector3d quarter = (0.75 * x.row(0) + 0.25 * x.row(1)).transpose();
  REQUIRE(ridge.locate(quarter).signed_distance < -0.0002);  // the edge crosses the prism there
  REQUIRE(ridge.locate(x.row(0).transpose()).signed_distance > 0.006);
  REQUIRE(ridge.locate(x.row(1).transpose()).signed_distance > 0.006);
  const double middle = ridge.locate((0.5 * (x.row(0) + x.row(1))).transpose()).signed_distance;
  REQUIRE(middle > 0.003);   // beyond half the margin: the middle alone sees nothing
  REQUIRE(middle < 0.0036);  // within the band whose quarter points are searched
  const std::vector<std::array<int, 2>> edges = {{0, 1}};
  REQUIRE(edges_through(ridge, x, edges) == 1);
  PushOutOptions options{.margin = 0.006, .edges = &edges};
  Eigen::MatrixX3d y = x;
  const PushOutReport r = push_out(ridge, y, options);
  CHECK(r.edges_lifted >= 1);
  CHECK(edges_through(ridge, y, edges) == 0);
  // Lifted along the normal at its closest point to half the margin out, about: past the ridge's
  // corner the closest point moves as it rises (2.95 mm).
  CHECK(ridge.locate(Eigen::Vector3d(0.75 * y.row(0) + 0.25 * y.row(1))).signed_distance > 0.0025);
}

// The first searches cut at each vertex's reach (PushOutOptions::cut_at_reach)
// give the same bits as searches in full, on sheets of 1.2 cm triangles laid
// through a ball (10 cm radius) at random heights and tilts: parts far
// outside (never searched in full), parts near the surface (stepped, lifted)
// and parts deep inside, beyond their reach (their side from their
// neighbours, or, for a patch wholly inside, from a search in full).
TEST_CASE("push_out cut at each vertex's reach gives the bits of searches in full", "[geometry][push_out]") {
  const BodySurface ball(icosphere(4, 0.1));
  const int n = 30;
  const Eigen::MatrixX3i faces = grid_faces(n);
  const std::vector<std::array<int, 2>> edges = edge_list(faces);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> height(-0.11, 0.11), tilt(-0.4, 0.4), jitter(-0.002, 0.002);
  int beyond = 0, inside_far = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const double y0 = height(rng), tx = tilt(rng), tz = tilt(rng);
    Eigen::MatrixX3d sheet(n * n, 3);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double x = 0.012 * (i - n / 2) + jitter(rng), z = 0.012 * (j - n / 2) + jitter(rng);
        sheet.row(i * n + j) << x, y0 + tx * x + tz * z + jitter(rng), z;
      }
    for (Eigen::Index i = 0; i < sheet.rows(); ++i) inside_far += ball.locate(sheet.row(i).transpose()).signed_distance < -0.02;
    PushOutOptions options{.margin = 0.006, .edges = &edges};
    Eigen::MatrixX3d cut = sheet, full = sheet;
    const PushOutReport rc = push_out(ball, cut, options);
    options.cut_at_reach = false;
    const PushOutReport rf = push_out(ball, full, options);
    INFO("trial " << trial << " at height " << y0);
    CHECK(cut == full);
    CHECK(rc.moved == rf.moved);
    CHECK(rc.edges_searched == rf.edges_searched);
    CHECK(rc.edges_lifted == rf.edges_lifted);
    CHECK(rc.passes == rf.passes);
    CHECK(rf.beyond_reach == 0);
    CHECK(rc.moved > 0);
    CHECK(ball.signed_distances(cut).minCoeff() >= 0.006 - 1e-9);
    beyond += rc.beyond_reach;
  }
  CHECK(beyond > 1000);     // most of each sheet lies outside the ball, beyond its reach
  CHECK(inside_far > 500);  // and the sheets through the ball leave vertices 2 cm deep

  // A patch wholly inside, every vertex beyond its reach: no neighbour knows
  // its side; searched in full, it is pushed out like a patch without edges.
  Eigen::MatrixX3d patch(4, 3);
  patch << 0, 0, 0, 0.01, 0, 0, 0, 0, 0.01, 0.01, 0, 0.01;
  const std::vector<std::array<int, 2>> patch_edges = {{0, 1}, {0, 2}, {1, 3}, {2, 3}, {1, 2}};
  PushOutOptions options{.margin = 0.006, .edges = &patch_edges};
  const PushOutReport r = push_out(ball, patch, options);
  CHECK(r.beyond_reach == 0);
  CHECK(r.moved == 4);
  CHECK(ball.signed_distances(patch).minCoeff() >= 0.006 - 1e-9);
}

// Each face of a convex solid turned away from its centre.
void turn_outward(const Eigen::MatrixX3d& v, Eigen::MatrixX3i& f) {
  const Eigen::Vector3d centre = v.colwise().mean().transpose();
  for (Eigen::Index i = 0; i < f.rows(); ++i) {
    const Eigen::Vector3d a = v.row(f(i, 0)), b = v.row(f(i, 1)), c = v.row(f(i, 2));
    if ((b - a).cross(c - a).dot((a + b + c) / 3 - centre) < 0) std::swap(f(i, 1), f(i, 2));
  }
}

TEST_CASE("push_out with edges moves an edge off a thin fold of the body it passes through", "[geometry][push_out]") {
  // A fin pointing down -y (a thin man's underarm fold, in small): a prism
  // whose section is a wedge of 30 degrees half-angle with its tip at
  // y = -4 cm, extruded along z. An edge 6 cm long crosses it 1 cm above
  // the tip, both ends 1.1 cm out. Lifting along one side's normal moves
  // the edge mostly along itself; with one lift pass it still crosses.
  // (Its base 10 cm above the tip, so that the way out is past the tip.)
  const double half_width = 0.1 * std::tan(M_PI / 6);
  const double xs[3] = {-half_width, half_width, 0.0}, ys[3] = {0.06, 0.06, -0.04};
  Eigen::MatrixX3d v(6, 3);
  for (int k = 0; k < 3; ++k) {
    v.row(k) << xs[k], ys[k], -0.1;
    v.row(3 + k) << xs[k], ys[k], 0.1;
  }
  Eigen::MatrixX3i f(8, 3);
  f << 0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4, 2, 0, 3, 2, 3, 5, 0, 2, 1, 3, 4, 5;
  turn_outward(v, f);  // (the prism is convex)
  const BodySurface fin(v, f);
  Eigen::MatrixX3d x(2, 3);
  x << -0.03, -0.01, 0.0, 0.03, -0.01, 0.0;
  REQUIRE(fin.locate(x.row(0).transpose()).signed_distance > 0.01);
  REQUIRE(fin.locate(x.row(1).transpose()).signed_distance > 0.01);
  const std::vector<std::array<int, 2>> edges = {{0, 1}};
  REQUIRE(edges_through(fin, x, edges) == 1);
  PushOutOptions options{.margin = 0.006, .max_passes = 2, .edges = &edges};
  Eigen::MatrixX3d y = x;
  const PushOutReport r = push_out(fin, y, options);
  CHECK(r.edges_lifted == 1);
  CHECK(r.fins_cleared == 1);
  CHECK(edges_through(fin, y, edges) == 0);
  // Off the fold's edge: below the tip, each end still a margin out.
  CHECK(y(0, 1) < -0.03);
  CHECK(fin.locate(y.row(0).transpose()).signed_distance >= 0.006 - 1e-9);
  CHECK(fin.locate(y.row(1).transpose()).signed_distance >= 0.006 - 1e-9);
}

TEST_CASE("push_out with edges clears an edge a sharp ridge crosses between two ends over flat body",
          "[geometry][push_out]") {
  // A slab with a flat top at y = 0 and a ridge along z on it (a thin man's
  // acromion, in small): 1 cm wide at its base, 1 cm tall, apex at x = -3
  // mm. A 3.2 cm edge over the flat top, its ends 6.8 and 12.5 mm out, both
  // closest to the top (the same normal: the rise between them estimated
  // nil), passes 9.1 mm high over the apex's x: the spike goes through it.
  // The ends' balls (6.8 + 12.5 mm < 3.2 cm) do not cover the edge, so it is
  // tested end to end; the fold's normals point up, and it is moved up.
  const std::vector<Eigen::Vector2d> section = {{-0.05, -0.05}, {0.05, -0.05}, {0.05, 0.0},    {0.002, 0.0},
                                                {-0.003, 0.010}, {-0.008, 0.0}, {-0.05, 0.0}};  // counter-clockwise
  const int n = static_cast<int>(section.size());
  Eigen::MatrixX3d v(2 * n + 2, 3);
  for (int k = 0; k < n; ++k) {
    v.row(k) << section[k].x(), section[k].y(), -0.1;
    v.row(n + k) << section[k].x(), section[k].y(), 0.1;
  }
  // Each cap a fan from a point every side of the section is seen from.
  v.row(2 * n) << -0.003, -0.025, -0.1;
  v.row(2 * n + 1) << -0.003, -0.025, 0.1;
  Eigen::MatrixX3i f(4 * n, 3);
  for (int k = 0; k < n; ++k) {
    const int j = (k + 1) % n;
    f.row(4 * k) << k, j, n + j;
    f.row(4 * k + 1) << k, n + j, n + k;
    f.row(4 * k + 2) << 2 * n + 1, n + k, n + j;
    f.row(4 * k + 3) << 2 * n, j, k;
  }
  const BodySurface ridge(v, f);
  Eigen::MatrixX3d x(2, 3);
  x << -0.016, 0.0068, 0.0, 0.016, 0.0125, 0.0;
  const SurfacePoint sa = ridge.locate(x.row(0).transpose()), sb = ridge.locate(x.row(1).transpose());
  REQUIRE(sa.signed_distance == Approx(0.0068));
  REQUIRE(sb.signed_distance == Approx(0.0125));
  REQUIRE(sa.normal.dot(sb.normal) == Approx(1.0));
  const std::vector<std::array<int, 2>> edges = {{0, 1}};
  REQUIRE(edges_through(ridge, x, edges) == 1);
  PushOutOptions options{.margin = 0.005, .edges = &edges};
  Eigen::MatrixX3d y = x;
  const PushOutReport r = push_out(ridge, y, options);
  CHECK(r.edges_searched == 0);  // (the estimate cleared it: only the test end to end found it)
  CHECK(r.fins_cleared == 1);
  CHECK(edges_through(ridge, y, edges) == 0);
  CHECK(y(0, 1) > x(0, 1));
  CHECK(ridge.locate(y.row(0).transpose()).signed_distance >= 0.005 - 1e-9);
  CHECK(ridge.locate(y.row(1).transpose()).signed_distance >= 0.005 - 1e-9);

  // Both ends' balls covering the edge (ends 2.5 cm over the top, 2 and 2.4
  // cm from the apex): not tested end to end, and nothing moves.
  Eigen::MatrixX3d high = x;
  high.col(1).setConstant(0.025);
  const PushOutReport clear = push_out(ridge, high, options);
  CHECK(clear.edges_tested_whole == 0);
  CHECK(clear.moved == 0);
}

TEST_CASE("push_out with faces lifts a face that a peak of the body rises through", "[geometry][push_out]") {
  // A double cone drawn with long edges (a heavy woman's breast on the human
  // rig, in small): tips at y = +-10 cm, a ring of 8 vertices of radius 5 cm
  // at y = 0. A garment triangle of circumradius 6 cm lies flat at y = 9.5
  // cm: its corners and edges are centimetres out, but the tip pokes 5 mm
  // through its middle.
  Eigen::MatrixX3d v(10, 3);
  v.row(0) << 0, 0.1, 0;
  v.row(1) << 0, -0.1, 0;
  for (int k = 0; k < 8; ++k) v.row(2 + k) << 0.05 * std::cos(k * M_PI / 4), 0, 0.05 * std::sin(k * M_PI / 4);
  Eigen::MatrixX3i f(16, 3);
  for (int k = 0; k < 8; ++k) {
    f.row(k) << 0, 2 + k, 2 + (k + 1) % 8;
    f.row(8 + k) << 1, 2 + (k + 1) % 8, 2 + k;
  }
  turn_outward(v, f);
  const BodySurface cone(v, f);
  Eigen::MatrixX3d x(3, 3);
  for (int k = 0; k < 3; ++k) x.row(k) << 0.06 * std::cos(2 * M_PI * k / 3 + 0.3), 0.095, 0.06 * std::sin(2 * M_PI * k / 3 + 0.3);
  Eigen::MatrixX3i garment(1, 3);
  garment << 0, 1, 2;
  const std::vector<std::array<int, 2>> edges = edge_list(garment);
  // Body edges through the garment's face (exact), both ways round the count.
  const auto body_edges_through = [&](const Eigen::MatrixX3d& y) {
    int n = 0;
    for (const auto& [a, b] : edge_list(f))
      n += segment_pierces_triangle(v.row(a).transpose(), v.row(b).transpose(), y.row(0).transpose(), y.row(1).transpose(),
                                    y.row(2).transpose());
    return n;
  };
  for (int k = 0; k < 3; ++k) REQUIRE(cone.locate(x.row(k).transpose()).signed_distance > 0.02);
  REQUIRE(edges_through(cone, x, edges) == 0);
  REQUIRE(body_edges_through(x) == 8);  // the tip's 8 edges

  // Edges alone leave it: nothing of the garment's edges is near the body.
  Eigen::MatrixX3d y = x;
  PushOutOptions options{.margin = 0.006, .edges = &edges};
  PushOutReport r = push_out(cone, y, options);
  CHECK(r.moved == 0);
  CHECK(body_edges_through(y) == 8);

  // With the faces the triangle is lifted until the tip is half the margin below it.
  y = x;
  options.faces = &garment;
  r = push_out(cone, y, options);
  CHECK(r.peaks_cleared == 1);
  CHECK(body_edges_through(y) == 0);
  for (int k = 0; k < 3; ++k) CHECK(y(k, 1) == Approx(0.1 + 0.003).margin(1e-9));
  CHECK((y.col(0) - x.col(0)).cwiseAbs().maxCoeff() < 1e-12);  // straight up, along the face's normal

  // The same triangle turned over (its normal down) is lifted the same way:
  // the side comes from the body's normals at its corners' closest points.
  Eigen::MatrixX3i turned(1, 3);
  turned << 0, 2, 1;
  y = x;
  options.faces = &turned;
  r = push_out(cone, y, options);
  CHECK(r.peaks_cleared == 1);
  CHECK(y(0, 1) == Approx(0.103).margin(1e-9));

  // Above the tip already: nothing to do.
  y = x;
  y.col(1).setConstant(0.101);
  options.faces = &garment;
  r = push_out(cone, y, options);
  CHECK(r.peaks_cleared == 0);
  CHECK(r.moved == 0);
}
