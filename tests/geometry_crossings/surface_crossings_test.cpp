// Surface crossings: the segment-triangle test on hand-made cases (through,
// beside, touching, in the plane, parallel), a sheet through a box with counts
// worked out by hand, the grid against a brute-force count, and bad input.
#include <drape/energy.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/surface_crossings.hpp>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <set>
#include <string>

using drape::geometry::segment_pierces_triangle;
using drape::geometry::surface_crossings;
using drape::geometry::SurfaceCrossings;
using V = Eigen::Vector3d;

namespace {

// The triangle most cases use: the corner of the unit square in the plane z = 0.
const V a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);

bool pierces(const V& p, const V& q) { return segment_pierces_triangle(p, q, a, b, c); }

// The cube [-0.5, 0.5]^3: vertex i at (+-0.5, +-0.5, +-0.5) by the bits of i
// (x: 1, y: 2, z: 4); each square face split by one diagonal, so 12 triangles
// and 18 edges (12 box edges, 6 face diagonals). The diagonals of the four
// side faces run from z = -0.5 to z = 0.5: 0-6 (x = -0.5), 1-7 (x = +0.5),
// 0-5 (y = -0.5), 2-7 (y = +0.5); the bottom's is 0-3, the top's 4-7.
Eigen::MatrixX3d cube_vertices() {
  Eigen::MatrixX3d v(8, 3);
  for (int i = 0; i < 8; ++i) v.row(i) << (i & 1 ? 0.5 : -0.5), (i & 2 ? 0.5 : -0.5), (i & 4 ? 0.5 : -0.5);
  return v;
}
Eigen::MatrixX3i cube_faces() {
  Eigen::MatrixX3i f(12, 3);
  f << 0, 2, 3, 0, 3, 1,  // z = -0.5
      4, 5, 7, 4, 7, 6,   // z = +0.5
      0, 4, 6, 0, 6, 2,   // x = -0.5
      1, 3, 7, 1, 7, 5,   // x = +0.5
      0, 1, 5, 0, 5, 4,   // y = -0.5
      2, 6, 7, 2, 7, 3;   // y = +0.5
  return f;
}

// A square sheet over [-2, 2]^2 at height z: 5 x 5 vertices, vertex r * 5 + col
// at (col - 2, r - 2, z), 4 x 4 squares each split by a diagonal chosen so
// that the four squares around the centre (vertex 12, at the origin) have
// theirs through the centre: the centre has 8 edges, to its 8 neighbours
// 6, 7, 8, 11, 13, 16, 17, 18 at x, y in {-1, 0, 1}.
struct Sheet {
  Eigen::MatrixX3d vertices{25, 3};
  Eigen::MatrixX3i faces{32, 3};
};
Sheet sheet(double z, double shift_x = 0) {
  Sheet s;
  for (int r = 0; r < 5; ++r)
    for (int col = 0; col < 5; ++col) s.vertices.row(r * 5 + col) << col - 2 + shift_x, r - 2, z;
  int f = 0;
  for (int r = 0; r < 4; ++r)
    for (int col = 0; col < 4; ++col) {
      const int v00 = r * 5 + col, v10 = v00 + 1, v01 = v00 + 5, v11 = v00 + 6;
      if ((r + col) % 2 == 0) {
        s.faces.row(f++) << v00, v10, v11;
        s.faces.row(f++) << v00, v11, v01;
      } else {
        s.faces.row(f++) << v00, v10, v01;
        s.faces.row(f++) << v10, v11, v01;
      }
    }
  return s;
}
const std::vector<int> kCentreAndNeighbours{6, 7, 8, 11, 12, 13, 16, 17, 18};

// Every edge against every triangle, for the grid to agree with.
SurfaceCrossings brute_force(const Eigen::MatrixX3d& gv, const Eigen::MatrixX3i& gf, const Eigen::MatrixX3d& bv,
                             const Eigen::MatrixX3i& bf) {
  SurfaceCrossings out;
  std::set<int> marked;
  auto tri = [](const Eigen::MatrixX3d& v, const Eigen::MatrixX3i& f, int i, int k) -> V { return v.row(f(i, k)); };
  for (const auto& e : drape::geometry::edge_list(gf)) {
    bool hit = false;
    for (int f = 0; f < bf.rows() && !hit; ++f)
      hit = segment_pierces_triangle(gv.row(e[0]), gv.row(e[1]), tri(bv, bf, f, 0), tri(bv, bf, f, 1), tri(bv, bf, f, 2));
    if (hit) ++out.garment_edges_through_body, marked.insert(e[0]), marked.insert(e[1]);
  }
  for (const auto& e : drape::geometry::edge_list(bf)) {
    bool hit = false;
    for (int f = 0; f < gf.rows(); ++f)
      if (segment_pierces_triangle(bv.row(e[0]), bv.row(e[1]), tri(gv, gf, f, 0), tri(gv, gf, f, 1), tri(gv, gf, f, 2))) {
        hit = true;
        for (int k = 0; k < 3; ++k) marked.insert(gf(f, k));
      }
    if (hit) ++out.body_edges_through_garment;
  }
  out.garment_vertices.assign(marked.begin(), marked.end());
  return out;
}

// A crumpled grid sheet: n x n vertices over [-1, 1]^2 in the plane of axes
// (u, v), the third coordinate noisy; with `snap` every coordinate is a
// multiple of 1/4, so touching (vertices on faces, edges on edges) is common.
Sheet crumpled(std::mt19937& rng, int n, int u, int v, double noise, bool snap) {
  std::uniform_real_distribution<double> jitter(-noise, noise);
  Sheet s;
  s.vertices.resize(n * n, 3);
  s.faces.resize(2 * (n - 1) * (n - 1), 3);
  const int w = 3 - u - v;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      V p;
      p[u] = -1 + 2.0 * i / (n - 1) + jitter(rng) / 4, p[v] = -1 + 2.0 * j / (n - 1) + jitter(rng) / 4, p[w] = jitter(rng);
      if (snap) p = (p * 4).array().round() / 4;
      s.vertices.row(i * n + j) = p;
    }
  int f = 0;
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const int v00 = i * n + j;
      s.faces.row(f++) << v00, v00 + n, v00 + n + 1;
      s.faces.row(f++) << v00, v00 + n + 1, v00 + 1;
    }
  return s;
}

}  // namespace

TEST_CASE("a segment through a triangle's interior pierces it, either way round", "[geometry][crossings]") {
  CHECK(pierces(V(0.2, 0.2, -1), V(0.2, 0.2, 1)));
  CHECK(pierces(V(0.2, 0.2, 1), V(0.2, 0.2, -1)));
  CHECK(segment_pierces_triangle(V(0.2, 0.2, 1), V(0.2, 0.2, -1), a, c, b));  // the other orientation
  CHECK(pierces(V(-0.3, 0.1, -1), V(0.7, 0.3, 2)));                            // slanted: z = 0 at (0.0333, 0.1667)
  CHECK_FALSE(pierces(V(0.2, 0.2, 0.5), V(0.2, 0.2, 1)));                     // stops above
  CHECK_FALSE(pierces(V(0.6, 0.6, -1), V(0.6, 0.6, 1)));                      // beside the hypotenuse
}

TEST_CASE("a segment 1e-9 beside an edge misses, one on the edge touches", "[geometry][crossings]") {
  CHECK_FALSE(pierces(V(0.5, -1e-9, -1), V(0.5, -1e-9, 1)));      // beside the edge a-b (y = 0)
  CHECK(pierces(V(0.5, 0, -1), V(0.5, 0, 1)));                    // on it
  CHECK_FALSE(pierces(V(0.5 + 1e-9, 0.5, -1), V(0.5 + 1e-9, 0.5, 1)));  // beside the hypotenuse x + y = 1
  CHECK(pierces(V(0.5, 0.5, -1), V(0.5, 0.5, 1)));                // on it
  CHECK_FALSE(pierces(V(0.2, 0.2, 1e-9), V(0.2, 0.2, 1)));        // ends 1e-9 above the plane
  CHECK(pierces(V(0.2, 0.2, 0), V(0.2, 0.2, 1)));                 // ends on it
}

TEST_CASE("a segment a few units in the last place beside an edge is decided exactly", "[geometry][crossings]") {
  // The edge a-b lies on the line y = x and the triangle on its side y <= x; a
  // vertical segment at (X, Y) pierces it exactly when Y <= X. Near (0.5, 0.5),
  // 36 units away from a corner, plain double determinants get ~7% of this
  // 64 x 64 pattern wrong (Kettner et al.'s classroom example, lifted to 3D).
  const V ta(12, 12, 0), tb(-24, -24, 0), tc(24, -48, 0);
  int wrong = 0;
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j) {
      const double x = 0.5 + i * std::ldexp(1.0, -53), y = 0.5 + j * std::ldexp(1.0, -53);
      wrong += segment_pierces_triangle(V(x, y, -1.0 / 3), V(x, y, 2.0 / 3), ta, tb, tc) != (y <= x);
    }
  CHECK(wrong == 0);
}

TEST_CASE("a segment touching a corner pierces the triangle", "[geometry][crossings]") {
  CHECK(pierces(V(0, 0, -1), V(0, 0, 1)));     // through corner a
  CHECK(pierces(V(1, 0, -1), V(1, 0, 0)));     // ends on corner b
  CHECK(pierces(V(-1, 2, -1), V(1, 0, 1)));    // slanted through c = (0, 1, 0) at its midpoint
  CHECK_FALSE(pierces(V(-1e-9, 0, -1), V(-1e-9, 0, 1)));
}

TEST_CASE("a segment in the triangle's plane counts when it meets the closed triangle", "[geometry][crossings]") {
  CHECK(pierces(V(-1, 0.25, 0), V(2, 0.25, 0)));    // across it
  CHECK(pierces(V(0.1, 0.1, 0), V(0.2, 0.3, 0)));   // inside it
  CHECK(pierces(V(1, -1, 0), V(1, 1, 0)));          // through corner b only
  CHECK(pierces(V(-1, 0, 0), V(2, 0, 0)));          // along the edge a-b
  CHECK(pierces(V(0.5, 0.5, 0), V(2, 2, 0)));       // starting on the hypotenuse, going out
  CHECK_FALSE(pierces(V(-1, 2, 0), V(2, 2, 0)));    // beyond c
  CHECK_FALSE(pierces(V(0.5 + 1e-9, 0.5 + 1e-9, 0), V(2, 2, 0)));
  CHECK(pierces(V(0.2, 0.2, 0), V(0.2, 0.2, 0)));  // a zero-length edge on the triangle touches it
  // A tilted plane (z = x), so the 2D test must drop an axis other than z.
  const V ta(0, 0, 0), tb(1, 0, 1), tc(0, 1, 0);
  CHECK(segment_pierces_triangle(V(0.25, -1, 0.25), V(0.25, 2, 0.25), ta, tb, tc));
  CHECK_FALSE(segment_pierces_triangle(V(0.75, 0.5, 0.75), V(0.75, 2, 0.75), ta, tb, tc));
  // Zero-area triangles have no inside: never pierced (their neighbours are).
  CHECK_FALSE(segment_pierces_triangle(V(0.5, 0, -1), V(0.5, 0, 1), a, b, V(2, 0, 0)));
}

TEST_CASE("a segment parallel to the triangle, above it, misses", "[geometry][crossings]") {
  CHECK_FALSE(pierces(V(-1, 0.2, 1e-9), V(2, 0.2, 1e-9)));
  CHECK_FALSE(pierces(V(-1, 0.2, 1), V(2, 0.2, 1)));
  CHECK_FALSE(pierces(V(0.1, 0.1, -1e-9), V(0.2, 0.2, -1e-9)));
}

TEST_CASE("an edge through the common edge of two triangles is seen by at least one", "[geometry][crossings]") {
  // The volume sign of the shared edge is exactly opposite for the two
  // triangles, so no rounding can let the edge fall through the crack.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int both = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const V p0(u(rng), u(rng), 0), p1(u(rng), u(rng), 0);
    const V mid = 0.5 * (p0 + p1), side = V(0, 0, 1).cross(p1 - p0);
    const V left = mid + side, right = mid - side;
    const V up(u(rng) * 1e-3, u(rng) * 1e-3, 1), from = mid + up, to = mid - (0.5 + std::abs(u(rng))) * up;
    const bool l = segment_pierces_triangle(from, to, p0, p1, left), r = segment_pierces_triangle(from, to, p1, p0, right);
    INFO("trial " << trial);
    REQUIRE((l || r));
    both += l && r;
  }
  CHECK(both < 20000);  // mostly one of them: the edge is hit exactly only now and then
}

TEST_CASE("a sheet through a box: counts worked out by hand", "[geometry][crossings]") {
  const Eigen::MatrixX3d box = cube_vertices();
  const Eigen::MatrixX3i box_faces = cube_faces();

  SECTION("cutting it at z = 0.25") {
    // Garment edges: the box's cross-section is [-0.5, 0.5]^2 and only the
    // centre vertex is inside, so exactly the centre's 8 edges leave it: the 4
    // along the axes through a side face (x = 0.5 at (0.5, 0, 0.25), inside
    // triangle 1-7-5), the 4 diagonals through the box's vertical edges at
    // (+-0.5, +-0.5, 0.25). Every other sheet edge has |x| >= 1 or |y| >= 1.
    // Body edges: those spanning z = -0.5 .. 0.5, the 4 vertical edges and the
    // 4 side-face diagonals, all cross z = 0.25 inside [-0.5, 0.5]^2 (within
    // the sheet); the top and bottom faces' 10 edges stay at z = +-0.5.
    const Sheet s = sheet(0.25);
    const SurfaceCrossings x = surface_crossings(s.vertices, s.faces, box, box_faces);
    CHECK(x.garment_edges_through_body == 8);
    CHECK(x.body_edges_through_garment == 8);
    CHECK(x.total() == 16);
    CHECK(x.garment_vertices == kCentreAndNeighbours);
  }
  SECTION("at z = 0, through the side faces' diagonals") {
    // The same counts: the axis edges now meet each side face at its centre,
    // on its diagonal (both triangles touched, the edge counted once); the
    // side diagonals meet the sheet on the centre's axis edges.
    const Sheet s = sheet(0);
    const SurfaceCrossings x = surface_crossings(s.vertices, s.faces, box, box_faces);
    CHECK(x.garment_edges_through_body == 8);
    CHECK(x.body_edges_through_garment == 8);
    CHECK(x.garment_vertices == kCentreAndNeighbours);
  }
  SECTION("lying on the top face (z = 0.5): touching counts") {
    // Garment: the centre (0, 0, 0.5) is on the top face, so its 8 edges touch
    // it; no other edge reaches [-0.5, 0.5]^2. Body: the top face's 5 edges lie
    // in the sheet (coplanar, inside it), and the 4 vertical edges and 4 side
    // diagonals end on it: 5 + 8 = 13. The bottom's 5 edges are 1 m below.
    const Sheet s = sheet(0.5);
    const SurfaceCrossings x = surface_crossings(s.vertices, s.faces, box, box_faces);
    CHECK(x.garment_edges_through_body == 8);
    CHECK(x.body_edges_through_garment == 13);
    CHECK(x.garment_vertices == kCentreAndNeighbours);
  }
  SECTION("above it, or beside it: nothing") {
    for (const Sheet& s : {sheet(0.75), sheet(-0.5 - 1e-9), sheet(0.25, 10.0)}) {
      const SurfaceCrossings x = surface_crossings(s.vertices, s.faces, box, box_faces);
      CHECK(x.total() == 0);
      CHECK(x.garment_vertices.empty());
    }
  }
  SECTION("one large garment triangle with the box poking through: no garment vertex is inside") {
    // What p misses: no garment edge meets the box; the 8 body edges spanning
    // z = -0.5 .. 0.5 pierce the triangle, whose 3 vertices are reported.
    Eigen::MatrixX3d big(3, 3);
    big << -5, -5, 0.25, 5, -5, 0.25, 0, 5, 0.25;
    const Eigen::MatrixX3i one = (Eigen::MatrixX3i(1, 3) << 0, 1, 2).finished();
    const SurfaceCrossings x = surface_crossings(big, one, box, box_faces);
    CHECK(x.garment_edges_through_body == 0);
    CHECK(x.body_edges_through_garment == 8);
    CHECK(x.garment_vertices == std::vector<int>{0, 1, 2});
  }
}

TEST_CASE("the grid finds what every edge against every triangle finds", "[geometry][crossings]") {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 12; ++trial) {
    const bool snap = trial % 2 == 1;  // snapped coordinates: many exact touches
    const Sheet garment = crumpled(rng, 9 + trial, 0, 1, 0.4, snap);
    const Sheet body = crumpled(rng, 12, trial % 3, (trial % 3 + 2) % 3, 0.4, snap);
    const SurfaceCrossings fast = surface_crossings(garment.vertices, garment.faces, body.vertices, body.faces);
    const SurfaceCrossings slow = brute_force(garment.vertices, garment.faces, body.vertices, body.faces);
    INFO("trial " << trial);
    CHECK(fast.garment_edges_through_body == slow.garment_edges_through_body);
    CHECK(fast.body_edges_through_garment == slow.body_edges_through_garment);
    CHECK(fast.garment_vertices == slow.garment_vertices);
    CHECK(slow.total() > 0);  // the sheets do cross: the comparison means something
  }
}

TEST_CASE("surface crossings of empty meshes are none", "[geometry][crossings]") {
  const SurfaceCrossings x = surface_crossings(Eigen::MatrixX3d(0, 3), Eigen::MatrixX3i(0, 3), cube_vertices(), cube_faces());
  CHECK(x.total() == 0);
  CHECK(surface_crossings(cube_vertices(), cube_faces(), Eigen::MatrixX3d(0, 3), Eigen::MatrixX3i(0, 3)).total() == 0);
}

TEST_CASE("surface crossings refuse bad faces and non-finite vertices, naming them", "[geometry][crossings]") {
  const Sheet s = sheet(0.25);
  auto message = [](const std::function<void()>& fn) {
    try {
      fn();
    } catch (const drape::Error& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  Eigen::MatrixX3i bad_garment = s.faces;
  bad_garment(3, 1) = 25;
  CHECK_THAT(message([&] { surface_crossings(s.vertices, bad_garment, cube_vertices(), cube_faces()); }),
             Catch::Contains("garment face 3 has vertex index 25") && Catch::Contains("25 vertices"));
  Eigen::MatrixX3i bad_body = cube_faces();
  bad_body(5, 0) = -1;
  CHECK_THAT(message([&] { surface_crossings(s.vertices, s.faces, cube_vertices(), bad_body); }),
             Catch::Contains("body face 5 has vertex index -1"));
  Eigen::MatrixX3d nan_garment = s.vertices;
  nan_garment(7, 2) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THAT(message([&] { surface_crossings(nan_garment, s.faces, cube_vertices(), cube_faces()); }),
             Catch::Contains("garment vertex 7 is not finite"));
  Eigen::MatrixX3d inf_body = cube_vertices();
  inf_body(2, 0) = std::numeric_limits<double>::infinity();
  CHECK_THAT(message([&] { surface_crossings(s.vertices, s.faces, inf_body, cube_faces()); }),
             Catch::Contains("body vertex 2 is not finite"));
}
