// The procedural T-shirt template: topology, UV charts, sizes, resolutions,
// print materials.
#include "tshirt_support.hpp"

#include <drape/energy.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/index_locality.hpp>
#include <drape/geometry/polygon2d.hpp>
#include <drape/geometry/topology.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>

using namespace drape;
using drape::test::build_tshirt;
using drape::test::uv_chart_of_faces;

namespace {

double uv_twice_area(const Mesh& m, int f) {
  const Eigen::Vector2d a = m.uv.row(m.uv_faces(f, 0)), b = m.uv.row(m.uv_faces(f, 1)), c = m.uv.row(m.uv_faces(f, 2));
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

// The pattern's measurements as docs/garments.md gives them: the regular's,
// or a size's, graded by its chest factor g (girths by g, lengths by 1 + 0.3
// (g - 1), the neck's width by 1 + 0.8 (g - 1); the sleeve's top seam long
// enough to pass the armpit by the regular's 0.098 m of free sleeve graded as
// a length), written out here apart from the plugin's code.
struct Measures {
  double W = 0.27, L = 0.70, nw = 0.085, su = 0.22, sl = 0.22, so = 0.19, front = 0.10, back = 0.025;
};
const double kSlope = 18 * M_PI / 180, kAlpha = 20 * M_PI / 180;
double armpit_distance(const Measures& m) { return (m.W - m.su + m.so * std::sin(kAlpha)) / std::cos(kAlpha); }
Measures measures_of(double g) {
  const Measures r;
  const double l = 1 + 0.3 * (g - 1);
  Measures m;
  m.W = g * r.W, m.su = g * r.su, m.so = (1 + 0.5 * (g - 1)) * r.so;
  m.L = l * r.L, m.front = l * r.front, m.back = l * r.back;
  m.nw = (1 + 0.8 * (g - 1)) * r.nw;
  m.sl = armpit_distance(m) + l * (r.sl - armpit_distance(r));
  return m;
}

// The pattern's area from those measurements: the T outline minus the
// neckline's half ellipse.
double pattern_area(const Measures& m, bool front) {
  const Eigen::Vector2d d(std::cos(kAlpha), -std::sin(kAlpha)), n(-std::sin(kAlpha), -std::cos(kAlpha));
  const Eigen::Vector2d S(m.su, m.L - (m.su - m.nw) * std::tan(kSlope));
  const double t = armpit_distance(m);
  const geometry::Polygon2 right{{0, 0}, {m.W, 0}, S + m.so * n + t * d, S + m.sl * d + m.so * n, S + m.sl * d, S, {m.nw, m.L}, {0, m.L}};
  return 2 * geometry::signed_area(right) - M_PI / 2 * m.nw * (front ? m.front : m.back);
}
double pattern_area(double neck_depth) { return pattern_area(Measures{}, neck_depth == Measures{}.front); }

}  // namespace

TEST_CASE("tshirt: default and coarse resolutions have the documented vertex counts", "[garments][tshirt]") {
  const Garment fine = build_tshirt();
  const Garment coarse = build_tshirt("{resolution: coarse}");
  INFO("default " << fine.mesh.num_vertices() << " vertices, " << fine.mesh.num_faces() << " faces; coarse "
                  << coarse.mesh.num_vertices() << ", " << coarse.mesh.num_faces());
  CHECK(fine.mesh.num_vertices() >= 3000);
  CHECK(fine.mesh.num_vertices() <= 4000);
  CHECK(coarse.mesh.num_vertices() >= 800);
  CHECK(coarse.mesh.num_vertices() <= 1200);
  const Garment counted = build_tshirt("{resolution: '2000'}");
  CHECK(counted.mesh.num_vertices() == Approx(2000).epsilon(0.1));
}

TEST_CASE("tshirt: a bad resolution or print polygon is one clear config error", "[garments][tshirt]") {
  CHECK_THROWS_WITH(build_tshirt("{resolution: fine}"), Catch::Contains("resolution 'fine'"));
  CHECK_THROWS_AS(build_tshirt("{resolution: '12'}"), ConfigError);
  CHECK_THROWS_WITH(build_tshirt("{print: true, print_polygon: [0.1, 0.1, 0.5]}"), Catch::Contains("print_polygon"));
  CHECK_THROWS_AS(build_tshirt("{size: huge}"), ConfigError);
  // An outside check's degenerate polygons were taken without a word: a bow tie (which side is the print?), a
  // loop of no area, and one too small to hold a face's centre.
  CHECK_THROWS_WITH(build_tshirt("{print: true, print_polygon: [0.3, 0.5, 0.7, 0.7, 0.7, 0.5, 0.3, 0.7]}"),
                    Catch::Contains("print_polygon: the loop crosses itself"));
  CHECK_THROWS_WITH(build_tshirt("{print: true, print_polygon: [0.3, 0.5, 0.5, 0.5, 0.7, 0.5]}"),
                    Catch::Contains("encloses no area"));
  CHECK_THROWS_WITH(build_tshirt("{print: true, print_polygon: [0.5, 0.5, 0.5001, 0.5, 0.5, 0.5001]}"),
                    Catch::Contains("holds the centre of no face"));
  CHECK_NOTHROW(build_tshirt("{print: true, print_polygon: [0.3, 0.5, 0.7, 0.5, 0.7, 0.7, 0.3, 0.7]}"));
}

TEST_CASE("tshirt: one manifold surface with collar, two sleeve and hem openings", "[garments][tshirt]") {
  for (const char* yaml : {"{}", "{resolution: coarse}", "{size: small}"}) {
    const Garment g = build_tshirt(yaml);
    const geometry::TopologyReport t = geometry::check_topology(g.mesh.faces, g.mesh.num_vertices());
    INFO(yaml << ": " << t.str());
    CHECK(t.manifold());
    CHECK(t.oriented());
    CHECK(t.unreferenced_vertices == 0);
    CHECK(t.boundary_loops == 4);
    CHECK(t.euler_characteristic == -2);
  }
}

TEST_CASE("tshirt: every graded size is the same mesh on its graded pattern", "[garments][tshirt]") {
  const Garment regular = build_tshirt();
  const double height_regular = regular.mesh.uv.col(1).maxCoeff() - regular.mesh.uv.col(1).minCoeff();
  for (const auto& [size, grade] : {std::pair<std::string, double>{"3xsmall", 0.6}, {"2xsmall", 0.7}, {"xsmall", 0.8}, {"small", 0.9}, {"large", 1.12}, {"xlarge", 1.25},
                                    {"3xlarge", 1.55}, {"5xlarge", 1.85}, {"6xlarge", 2.0}}) {
    INFO(size);
    const Garment graded = build_tshirt("{size: " + size + "}");
    REQUIRE(regular.mesh.num_vertices() == graded.mesh.num_vertices());
    CHECK(regular.mesh.faces == graded.mesh.faces);
    CHECK(regular.mesh.uv_faces == graded.mesh.uv_faces);
    CHECK(graded.fit_grade == grade);  // dressed on the body of that girth (fit_body.hpp)
    // Each chart covers its graded pattern, with no triangle turned over or crushed.
    const std::vector<int> chart = uv_chart_of_faces(graded.mesh);
    double area[2] = {0, 0}, min_angle = 180;
    for (int f = 0; f < graded.mesh.num_faces(); ++f) {
      const double twice = uv_twice_area(graded.mesh, f);
      REQUIRE(twice > 0);
      area[chart[f]] += twice / 2;
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector2d u = graded.mesh.uv.row(graded.mesh.uv_faces(f, (k + 1) % 3)) - graded.mesh.uv.row(graded.mesh.uv_faces(f, k));
        const Eigen::Vector2d w = graded.mesh.uv.row(graded.mesh.uv_faces(f, (k + 2) % 3)) - graded.mesh.uv.row(graded.mesh.uv_faces(f, k));
        min_angle = std::min(min_angle, std::atan2(std::abs(u.x() * w.y() - u.y() * w.x()), u.dot(w)) * 180 / M_PI);
      }
    }
    CHECK(area[0] == Approx(pattern_area(measures_of(grade), true)).epsilon(0.005));
    CHECK(area[1] == Approx(pattern_area(measures_of(grade), false)).epsilon(0.005));
    CHECK(min_angle > 15);
    // Lengths grow 0.3 times as fast as the chest: a 6xlarge is 30 % longer, not twice.
    const double height = graded.mesh.uv.col(1).maxCoeff() - graded.mesh.uv.col(1).minCoeff();
    CHECK(height / height_regular == Approx(1 + 0.3 * (grade - 1)).epsilon(1e-9));
    // The hem (v = 0 on the front chart) is the chest's width: g times the regular's 0.54 m.
    double hem_lo = INFINITY, hem_hi = -INFINITY;
    for (int f = 0; f < graded.mesh.num_faces(); ++f)
      for (int k = 0; k < 3; ++k)
        if (chart[f] == 0 && std::abs(graded.mesh.uv(graded.mesh.uv_faces(f, k), 1)) < 1e-12)
          hem_lo = std::min(hem_lo, graded.mesh.uv(graded.mesh.uv_faces(f, k), 0)),
          hem_hi = std::max(hem_hi, graded.mesh.uv(graded.mesh.uv_faces(f, k), 0));
    CHECK(hem_hi - hem_lo == Approx(grade * 0.54).epsilon(1e-9));
  }
}

TEST_CASE("tshirt: an unknown size is refused with the known ones", "[garments][tshirt]") {
  CHECK_THROWS_WITH(build_tshirt("{size: medium}"), Catch::Matchers::Contains("small") && Catch::Matchers::Contains("xlarge"));
}

TEST_CASE("tshirt: two UV charts in meters, counter-clockwise, covering the pattern", "[garments][tshirt]") {
  const Garment g = build_tshirt();
  const Mesh& m = g.mesh;
  REQUIRE(m.has_uv());
  const std::vector<int> chart = uv_chart_of_faces(m);
  double area[2] = {0, 0};
  double min_angle = 180;
  int nonpositive = 0;
  for (int f = 0; f < m.num_faces(); ++f) {
    const double twice = uv_twice_area(m, f);
    if (twice <= 0) ++nonpositive;
    area[chart[f]] += twice / 2;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d u = m.uv.row(m.uv_faces(f, (k + 1) % 3)) - m.uv.row(m.uv_faces(f, k));
      const Eigen::Vector2d w = m.uv.row(m.uv_faces(f, (k + 2) % 3)) - m.uv.row(m.uv_faces(f, k));
      min_angle = std::min(min_angle, std::atan2(std::abs(u.x() * w.y() - u.y() * w.x()), u.dot(w)) * 180 / M_PI);
    }
  }
  WARN("tshirt default: " << m.num_vertices() << " vertices, " << m.num_faces() << " faces, min UV angle "
                          << min_angle << " deg, front " << area[0] << " m2, back " << area[1] << " m2");
  CHECK(nonpositive == 0);
  CHECK(min_angle > 20);
  CHECK(std::count(chart.begin(), chart.end(), 0) > 0);
  CHECK(std::count(chart.begin(), chart.end(), 1) > 0);
  // The chords of the sampled neckline cut a little of the curve off.
  CHECK(area[0] == Approx(pattern_area(0.10)).epsilon(0.005));
  CHECK(area[1] == Approx(pattern_area(0.025)).epsilon(0.005));
}

TEST_CASE("tshirt: seam vertices are shared and carry one UV per panel", "[garments][tshirt]") {
  const Garment g = build_tshirt("{resolution: coarse}");
  const Mesh& m = g.mesh;
  const std::vector<int> chart = uv_chart_of_faces(m);
  std::vector<std::set<int>> uvs(m.num_vertices());
  std::vector<int> charts_of(m.num_vertices(), 0);
  for (int f = 0; f < m.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) uvs[m.faces(f, k)].insert(m.uv_faces(f, k)), charts_of[m.faces(f, k)] |= 1 << chart[f];
  int seam = 0;
  for (int v = 0; v < m.num_vertices(); ++v) {
    if (charts_of[v] == 3) {
      ++seam;
      REQUIRE(uvs[v].size() == 2);
      CHECK((m.uv.row(*uvs[v].begin()) - m.uv.row(*uvs[v].rbegin())).norm() > 0.01);
    } else {
      CHECK(uvs[v].size() == 1);
    }
  }
  INFO("seam vertices " << seam);
  CHECK(seam > 40);
  // Front and back meet at the same 3D points along the whole seam: no duplicated vertex lies on another.
  int duplicates = 0;
  for (int v = 0; v < m.num_vertices(); ++v)
    for (int w = v + 1; w < m.num_vertices(); ++w)
      if ((m.vertices.row(v) - m.vertices.row(w)).norm() < 1e-9) ++duplicates;
  CHECK(duplicates == 0);
}

TEST_CASE("tshirt: vertex order follows the rows of the panels", "[garments][tshirt]") {
  const Garment g = build_tshirt();
  const geometry::IndexLocality loc = geometry::index_locality(g.mesh.faces, g.mesh.num_vertices());
  INFO("one hop " << loc.one_hop << ", two hop " << loc.two_hop);
  CHECK(loc.one_hop > 0.85);
}

TEST_CASE("tshirt: materials are knit, plus the print only when asked", "[garments][tshirt]") {
  const Garment plain = build_tshirt();
  REQUIRE(plain.materials.size() == 1);
  CHECK(plain.materials[0].name == "knit");
  // The template's own knit is ArcSim's measured gray-interlock: the numbers
  // below are from ArcSim's materials/gray-interlock.json (its first
  // stretching row, its first bending sample), not from drape's preset file.
  const Material& own = plain.materials[0];
  CHECK(own.model == Material::Model::Arcsim);
  CHECK(own.density == Approx(0.187));
  CHECK(own.arcsim.stretching[0].isApprox(Eigen::Vector4d(16.593832, -14.695990, 34.477123, 36.860302)));
  CHECK(own.arcsim.bending[0][0] == Approx(23.191698e-6));
  CHECK(own.thickness == Approx(4.7e-4));
  for (int f = 0; f < plain.mesh.num_faces(); ++f) REQUIRE(plain.material_of(f) == 0);

  const Garment printed = build_tshirt("{print: true}");
  REQUIRE(printed.materials.size() == 2);
  const Material &knit = printed.materials[0], &print = printed.materials[1];
  CHECK(print.name == "print");
  CHECK(print.density == Approx(2 * knit.density));
  CHECK(print.model == Material::Model::Arcsim);
  for (int k = 0; k < 6; ++k) CHECK(print.arcsim.stretching[k].isApprox(5 * knit.arcsim.stretching[k]));
  for (int b = 0; b < 3; ++b)
    for (int j = 0; j < 5; ++j) CHECK(print.arcsim.bending[b][j] == Approx(10 * knit.arcsim.bending[b][j]));
  CHECK(print.thickness == Approx(2 * knit.thickness));
  CHECK(printed.mesh.faces == plain.mesh.faces);

  // Print faces: front chart only, UV centroid inside the default polygon
  // (normalised to the front chart's bounding box).
  const Mesh& m = printed.mesh;
  const std::vector<int> chart = uv_chart_of_faces(m);
  Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (int f = 0; f < m.num_faces(); ++f)
    if (chart[f] == 0)
      for (int k = 0; k < 3; ++k)
        lo = lo.cwiseMin(m.uv.row(m.uv_faces(f, k)).transpose()), hi = hi.cwiseMax(m.uv.row(m.uv_faces(f, k)).transpose());
  const geometry::Polygon2 region{{0.35, 0.5}, {0.65, 0.5}, {0.65, 0.78}, {0.35, 0.78}};
  int prints = 0, expected = 0;
  for (int f = 0; f < m.num_faces(); ++f) {
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (int k = 0; k < 3; ++k) c += m.uv.row(m.uv_faces(f, k)).transpose() / 3;
    const bool inside = chart[f] == 0 && geometry::point_in_polygon(region, (c - lo).cwiseQuotient(hi - lo));
    expected += inside;
    prints += printed.material_of(f) == 1;
    CHECK(printed.material_of(f) == (inside ? 1 : 0));
  }
  INFO("print faces " << prints);
  CHECK(prints > 50);
  CHECK(prints == expected);

  // A custom polygon moves the print: a triangle low on the left has no face in common with the default.
  const Garment low = build_tshirt("{print: true, print_polygon: [0.3, 0.05, 0.5, 0.05, 0.4, 0.3]}");
  int overlap = 0, low_prints = 0;
  for (int f = 0; f < m.num_faces(); ++f)
    low_prints += low.material_of(f) == 1, overlap += low.material_of(f) == 1 && printed.material_of(f) == 1;
  CHECK(low_prints > 10);
  CHECK(overlap == 0);
}
