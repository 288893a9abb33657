// The self contact (plugins/energies/self_contact): its derivatives against
// finite differences on two layers of one garment within d_hat, its
// continuous collision bound, the pairs it leaves out (shared vertices,
// slivers at rest), hand-made trajectories (parallel edges passing through
// each other edge on edge, a grazing pass beside an edge), a
// near-degenerate triangle, and a sheet falling onto
// another part of the same garment, which passes through it without the
// energy and never with it (checked with geometry::self_intersections, which
// shares no code with the contact).
#include <drape/energy.hpp>
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/self_intersection.hpp>
#include <drape/gradcheck.hpp>
#include <drape/physics/solver.hpp>

#include <catch2/catch.hpp>

#include <drape/warnings.hpp>

#include <cmath>

#include "../barrier/barrier_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

constexpr double kDhat = 1e-3;

// Appends an n x n grid (spacing s, material space its own flat shape)
// rotated by `angle` about z and moved to `at` to the garment's mesh.
void add_sheet(Garment& g, int n, double s, double angle, const Eigen::Vector3d& at) {
  Mesh& m = g.mesh;
  const Eigen::Index v0 = m.vertices.rows(), f0 = m.faces.rows();
  m.vertices.conservativeResize(v0 + n * n, 3);
  m.uv.conservativeResize(v0 + n * n, 2);
  m.faces.conservativeResize(f0 + 2 * (n - 1) * (n - 1), 3);
  const double c = std::cos(angle), si = std::sin(angle), half = 0.5 * (n - 1) * s;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double u = j * s - half, v = i * s - half;
      m.vertices.row(v0 + i * n + j) << at.x() + c * u - si * v, at.y() + si * u + c * v, at.z();
      m.uv.row(v0 + i * n + j) << j * s + 10.0 * static_cast<double>(v0), i * s;  // charts apart
    }
  Eigen::Index f = f0;
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const int a = static_cast<int>(v0) + i * n + j, b = a + 1, cc = a + n, d = cc + 1;
      m.faces.row(f++) << a, b, d;
      m.faces.row(f++) << a, d, cc;
    }
  m.uv_faces = m.faces;
}

std::shared_ptr<Garment> empty_garment() {
  auto g = std::make_shared<Garment>();
  g->mesh.vertices.resize(0, 3);
  g->mesh.uv.resize(0, 2);
  g->mesh.faces.resize(0, 3);
  g->materials.push_back(Material{});
  g->materials[0].name = "knit";
  return g;
}

// Two sheets of one garment, the upper turned by 0.3 rad and `gap` above.
std::shared_ptr<Garment> two_layers(int n, double s, double gap) {
  auto g = empty_garment();
  add_sheet(*g, n, s, 0.0, {0.0, 0.0, 0.0});
  add_sheet(*g, n - 1, s, 0.3, {0.0013, 0.0007, gap});
  return g;
}

// A strip whose middle triangle is a sliver 0.1 mm high: its apex (vertex 2)
// is within d_hat of the opposite triangle's edge, two mesh edges away.
Garment sliver_strip() {
  Eigen::MatrixX3d v(5, 3);
  v << 0, 0, 0, 0.01, 0, 0, 0.005, 1e-4, 0, 0.005, -0.01, 0, 0.005, 0.01, 0;
  Eigen::MatrixX3i f(3, 3);
  f << 0, 1, 2, 0, 3, 1, 2, 1, 4;
  Eigen::MatrixX2d uv = v.leftCols<2>();
  return small_garment(v, f, uv);
}

std::unique_ptr<Energy> self_contact_on(const Garment& g, const std::string& yaml = "{}") {
  return bound_energy("self_contact", yaml, g);
}

}  // namespace

TEST_CASE("self_contact refuses bad parameters", "[self_contact]") {
  CHECK_THROWS_WITH(params_for("self_contact", "{distance: 0}"), Catch::Contains("'distance'"));
  CHECK_THROWS_WITH(params_for("self_contact", "{stiffness: -1}"), Catch::Contains("'stiffness'"));
  CHECK_THROWS_WITH(params_for("self_contact", "{min_separation: 1}"), Catch::Contains("'min_separation'"));
  CHECK_THROWS_WITH(params_for("self_contact", "{rest_exclusion: -1}"), Catch::Contains("'rest_exclusion'"));
  const auto ok = self_contact_on(*two_layers(4, 0.01, 0.5e-3));
  CHECK_THROWS_WITH(ok->value(Eigen::MatrixX3d::Zero(3, 3)), Catch::Contains("3 vertices given"));
}

TEST_CASE("self_contact leaves a tangled start out and guards the rest", "[self_contact]") {
  // Two sheets through each other at rest (a barrier cannot undo that), and
  // 1 m away two layers 0.5 mm apart.
  auto g = empty_garment();
  add_sheet(*g, 3, 0.01, 0.0, {0, 0, 0});
  add_sheet(*g, 3, 0.01, 0.0, {0, 0, 0});
  Eigen::MatrixX3d& v = g->mesh.vertices;
  for (Eigen::Index i = 9; i < 18; ++i) v(i, 2) = v(i, 1), v(i, 1) = 0.0005;  // stood up across the first
  REQUIRE_FALSE(geometry::self_intersections(v, g->mesh.faces, 1).empty());
  add_sheet(*g, 5, 0.01, 0.0, {1.0, 0, 0});
  add_sheet(*g, 4, 0.01, 0.3, {1.0013, 0.0007, 0.5e-3});
  std::vector<std::string> warnings;
  const WarningHandler previous = set_warning_handler([&](const std::string& w) { warnings.push_back(w); });
  const auto e = self_contact_on(*g);
  self_contact_on(*g);  // the same garment bound again (a dataset's next sample): said once
  set_warning_handler(previous);
  REQUIRE(warnings.size() == 1);  // the user is told which part goes unguarded
  CHECK_THAT(warnings[0], Catch::StartsWith("self_contact: the rest garment") && Catch::Contains("passes through itself"));
  const Eigen::MatrixX3d x = g->mesh.vertices;
  const double value = e->value(x);
  CHECK(std::isfinite(value));
  CHECK(value > 0);  // the layers
  // The standing sheet slides on through the other: not bounded.
  Eigen::MatrixX3d through = Eigen::MatrixX3d::Zero(x.rows(), 3);
  through.block(9, 2, 9, 1).setConstant(-0.004);
  CHECK(e->max_step(x, through) == 1.0);
  // The upper layer pressed into the lower one: bounded.
  Eigen::MatrixX3d down = Eigen::MatrixX3d::Zero(x.rows(), 3);
  down.bottomRows(16).col(2).setConstant(-0.002);
  CHECK(e->max_step(x, down) < 0.25);
}

TEST_CASE("self_contact costs nothing apart and grows as layers close", "[self_contact]") {
  auto far = two_layers(5, 0.01, 2e-3);
  const auto e = self_contact_on(*far);
  CHECK(e->value(far->mesh.vertices) == 0.0);
  Eigen::MatrixX3d x = far->mesh.vertices;
  double last = 0;
  for (const double gap : {0.9e-3, 0.5e-3, 0.2e-3, 0.05e-3}) {
    for (Eigen::Index i = 25; i < x.rows(); ++i) x(i, 2) = gap;
    const double value = e->value(x);
    INFO("gap " << gap);
    CHECK(value > last);
    last = value;
  }
  for (Eigen::Index i = 25; i < x.rows(); ++i) x(i, 2) = 0.0;  // touching
  CHECK(std::isinf(e->value(x)));
  Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(x.rows(), 3);
  CHECK_THROWS_WITH(e->add_gradient(x, g), Catch::Contains("not separated from itself"));
}

TEST_CASE("self_contact derivatives match finite differences", "[self_contact][gradcheck]") {
  // Two layers 0.5 mm apart, the upper one perturbed by 0.2 mm: vertex-face
  // pairs of every distance type and edge-edge pairs, all within d_hat.
  auto g = two_layers(5, 0.004, 0.5e-3);
  const auto e = self_contact_on(*g);
  const Eigen::MatrixX3d x = perturbed(g->mesh.vertices, 1e-4, 5);
  REQUIRE(e->value(x) > 0);
  const GradCheckReport r = check_energy_derivatives(*e, x, {1e-8, 200, 3});
  INFO(r.str());
  CHECK(r.ok(1e-4));
}

// The candidates are kept while the cloth moves less than a skin (a Verlet
// list): after small and large moves the kept search must give, bit for bit,
// what a contact that has seen nothing before gives.
TEST_CASE("self_contact kept candidates equal a fresh search", "[self_contact]") {
  auto g = two_layers(6, 0.004, 0.6e-3);
  const auto kept = self_contact_on(*g);
  Eigen::MatrixX3d x = perturbed(g->mesh.vertices, 1e-4, 11);
  // The upper layer moved by 0.1, 0.6 and 2.5 mm (within the skin of 1 mm,
  // and past it), up and back down, each vertex its own way.
  int seed = 20;
  for (const double m : {1e-4, 6e-4, 2.5e-3, -2.5e-3, -6e-4, -3e-4}) {
    Eigen::MatrixX3d step = perturbed(Eigen::MatrixX3d::Zero(x.rows(), 3), 0.2 * std::abs(m), seed++);
    step.topRows(36).setZero();
    step.bottomRows(x.rows() - 36).col(2).array() += m;
    x += step;
    const auto fresh = self_contact_on(*g);
    INFO("after a move of " << m << " m");
    const double value = fresh->value(x);
    CHECK(kept->value(x) == value);
    Eigen::MatrixX3d a = Eigen::MatrixX3d::Zero(x.rows(), 3), b = a;
    CHECK(kept->add_gradient(x, a) == fresh->add_gradient(x, b));
    CHECK(a == b);
    CHECK(dense_hessian(*kept, x, true) == dense_hessian(*fresh, x, true));
  }
  CHECK(self_contact_on(*g)->value(x) > 0);  // the last state has pairs within d_hat
}

// max_step takes its pairs from the kept candidates when the move stays
// within their reach (drift plus step at most d_hat / 2 + skin = 1.5 mm on
// every coordinate): bit for bit the bound of a contact that has seen nothing.
TEST_CASE("self_contact kept candidates bound a step as a fresh search does", "[self_contact]") {
  auto g = two_layers(6, 0.004, 0.6e-3);
  const auto kept = self_contact_on(*g);
  const Eigen::MatrixX3d x0 = perturbed(g->mesh.vertices, 1e-4, 11);
  REQUIRE(kept->value(x0) > 0);  // the candidates are found here
  int seed = 40, stopped = 0;
  for (const double drift : {0.0, 2e-4, 6e-4}) {
    Eigen::MatrixX3d x = x0 + perturbed(Eigen::MatrixX3d::Zero(x0.rows(), 3), 0.2 * drift, seed++);
    x.bottomRows(x0.rows() - 36).col(2).array() += drift;  // the upper layer up, clear of the lower
    for (const double step : {2e-4, 8e-4, 1.2e-3, 3e-3}) {
      for (const double sign : {-1.0, 1.0}) {
        Eigen::MatrixX3d dx = perturbed(Eigen::MatrixX3d::Zero(x0.rows(), 3), 0.2 * step, seed++);
        dx.bottomRows(x0.rows() - 36).col(2).array() += sign * step;
        INFO("drift " << drift << " m, step " << sign * step << " m");
        const double alpha = kept->max_step(x, dx);
        CHECK(alpha == self_contact_on(*g)->max_step(x, dx));
        stopped += alpha < 1.0;
      }
    }
  }
  CHECK(stopped >= 4);  // the upper layer stepping down through the lower was bounded
}

TEST_CASE("self_contact max_step stops before the layers cross", "[self_contact]") {
  auto g = two_layers(4, 0.01, 0.5e-3);
  const auto e = self_contact_on(*g);
  const Eigen::MatrixX3d& x = g->mesh.vertices;
  // The upper layer tilted through the lower one: down 2 mm at one side, up 1 mm at the other.
  Eigen::MatrixX3d down = Eigen::MatrixX3d::Zero(x.rows(), 3);
  for (Eigen::Index i = 16; i < x.rows(); ++i) down(i, 2) = -0.1 * (x(i, 0) + 0.005);
  REQUIRE_FALSE(geometry::self_intersections(x + down, g->mesh.faces, 1).empty());  // the full move crosses
  const double alpha = e->max_step(x, down);
  CHECK(alpha > 0);
  CHECK(alpha < 0.5e-3 / -down.col(2).minCoeff());  // before the first vertex reaches the lower layer
  CHECK(std::isfinite(e->value(x + alpha * down)));
  CHECK(geometry::self_intersections(x + alpha * down, g->mesh.faces, 1).empty());
  Eigen::MatrixX3d up = Eigen::MatrixX3d::Zero(x.rows(), 3);
  for (Eigen::Index i = 16; i < x.rows(); ++i) up(i, 2) = 0.01;
  CHECK(e->max_step(x, up) == 1.0);  // moving apart: no bound
  Eigen::MatrixX3d slide = Eigen::MatrixX3d::Zero(x.rows(), 3);
  for (Eigen::Index i = 16; i < x.rows(); ++i) slide(i, 0) = 0.02;
  CHECK(e->max_step(x, slide) == 1.0);  // sliding over at the same height
}

TEST_CASE("self_contact skips slivers at rest but not far fabric", "[self_contact]") {
  // The sliver strip's apex-to-edge pair is left out at rest by default and
  // counted with rest_exclusion 0.
  const Garment g = sliver_strip();
  const Eigen::MatrixX3d& v = g.mesh.vertices;
  CHECK(self_contact_on(g)->value(v) == 0.0);
  const auto strict = self_contact_on(g, "{rest_exclusion: 0}");
  const double value = strict->value(v);
  CHECK(value > 0);
  CHECK(std::isfinite(value));
  // The same closeness between separate sheets (no path of mesh edges) is always counted.
  auto layers = two_layers(4, 0.01, 0.5e-3);
  CHECK(self_contact_on(*layers, "{rest_exclusion: 100}")->value(layers->mesh.vertices) > 0);
}

TEST_CASE("self_contact leaves out the fabric neighbours close where the garment was cut, not where it was dressed",
          "[self_contact]") {
  // An outside check's garment placed through the body: dressing pushed
  // vertices 14 mm apart together onto the body, the pairs between them were
  // left out as "close at rest", and they passed through each other in the
  // morph (10 crossings in the armpit). As cut, the sliver's apex stands 5 mm
  // up: the pair is no rest neighbour, and is guarded where it is now.
  Garment g = sliver_strip();
  const Eigen::MatrixX3d dressed = g.mesh.vertices;
  CHECK(self_contact_on(g)->value(dressed) == 0.0);  // cut as it lies: left out
  g.cut_vertices = dressed;
  g.cut_vertices(2, 1) = 5e-3;
  CHECK(g.as_cut()(2, 1) == 5e-3);
  CHECK(self_contact_on(g)->value(dressed) > 0);
  // Cut positions of another vertex count are none: the mesh's own are used.
  g.cut_vertices.resize(2, 3);
  CHECK(self_contact_on(g)->value(dressed) == 0.0);
}

TEST_CASE("self_contact with thin_rest_neighbours keeps close fabric neighbours, each by half its rest distance",
          "[self_contact]") {
  // The sliver strip: the apex (vertex 2) 0.1 mm from the edge it stands on,
  // which bounds the opposite triangle (0, 3, 1). Left out by default; kept
  // thin, its own d_hat is 0.05 mm.
  const Garment g = sliver_strip();
  const Eigen::MatrixX3d& v = g.mesh.vertices;
  const auto excluded = self_contact_on(g);
  const auto thin = self_contact_on(g, "{thin_rest_neighbours: true}");
  CHECK(thin->value(v) == 0.0);  // nothing pushed at rest
  // The apex pressed to 0.03 mm above the plane of the opposite triangle's
  // edge (and lifted a little out of the strip's plane): within its 0.05 mm.
  Eigen::MatrixX3d pressed = v;
  pressed.row(2) << 0.005, 3e-5, 1e-5;
  CHECK(excluded->value(pressed) == 0.0);
  const double e = thin->value(pressed);
  CHECK(e > 0);
  CHECK(std::isfinite(e));
  const GradCheckReport r = check_energy_derivatives(*thin, pressed, {1e-10, 200, 3});
  INFO(r.str());
  CHECK(r.ok(1e-4));
  // Folded through the edge: the excluded pair lets it pass, the thin one stops it first.
  Eigen::MatrixX3d through = Eigen::MatrixX3d::Zero(5, 3);
  through(2, 1) = -2e-4;
  CHECK(excluded->max_step(v, through) == 1.0);
  const double alpha = thin->max_step(v, through);
  CHECK(alpha < 0.5);  // before the apex reaches the edge, at half the move
  CHECK(std::isfinite(thin->value(v + alpha * through)));
}

TEST_CASE("self_contact stays finite near a degenerate triangle", "[self_contact]") {
  // A needle triangle (height 1e-9 m) 0.5 mm over a layer: its plane is
  // undefined, so its pairs must take edge and corner distances.
  auto g = two_layers(4, 0.01, 2e-3);
  Mesh& m = g->mesh;
  const Eigen::Index base = m.vertices.rows();
  m.vertices.conservativeResize(base + 3, 3);
  m.vertices.row(base) << 0.001, 0.002, 0.5e-3;
  m.vertices.row(base + 1) << 0.006, 0.002, 0.5e-3;
  m.vertices.row(base + 2) << 0.0035, 0.002 + 1e-9, 0.5e-3;
  m.uv.conservativeResize(base + 3, 2);
  m.uv.bottomRows(3) = m.vertices.bottomRows(3).leftCols<2>();
  m.uv.bottomRows(3).col(0).array() += 100.0;
  m.faces.conservativeResize(m.faces.rows() + 1, 3);
  m.faces.bottomRows(1) << static_cast<int>(base), static_cast<int>(base + 1), static_cast<int>(base + 2);
  m.uv_faces = m.faces;
  const auto e = self_contact_on(*g);
  const Eigen::MatrixX3d& x = m.vertices;
  const double value = e->value(x);
  CHECK(value > 0);
  CHECK(std::isfinite(value));
  const Eigen::MatrixX3d grad = gradient_of(*e, x);
  CHECK(grad.allFinite());
  CHECK(dense_hessian(*e, x, true).allFinite());
  CHECK(dense_hessian(*e, x, false).allFinite());
}

namespace {

// Drops a 9 x 9 sheet from 1.5 cm onto a 13 x 13 sheet of the same garment
// lying on a table; returns the steps' self-intersection counts (faces
// meeting, geometry::self_intersections) and the final state.
std::vector<std::size_t> drop_layers(bool with_self_contact, Eigen::MatrixX3d& x) {
  const Mesh table = box(-0.2, 0.2, -0.2, 0.2, -0.1, 0);
  geometry::BodySurface body(table);
  auto g = empty_garment();
  add_sheet(*g, 13, 0.01, 0.0, {0.0, 0.0, 0.002});
  add_sheet(*g, 9, 0.01, 0.5, {0.0013, 0.0007, 0.015});
  std::vector<NamedEnergy> energies;
  EnergyContext ctx;
  ctx.garment = g.get();
  ctx.body = &body;
  ctx.gravity = Eigen::Vector3d(0, 0, -9.81);
  std::vector<std::string> names{"gravity", "stretching", "bending", "barrier"};
  if (with_self_contact) names.push_back("self_contact");
  for (const std::string& name : names) {
    auto e = plugins().create_energy(name, params_for(name, "{}"));
    e->bind(ctx);
    energies.push_back({name, std::move(e)});
  }
  SolverSettings settings;
  settings.max_newton_iterations = 20;
  ClothSolver solver(*g, energies, settings);
  x = g->mesh.vertices;
  Eigen::MatrixX3d v = Eigen::MatrixX3d::Zero(x.rows(), 3);
  std::vector<std::size_t> crossings;
  for (int step = 0; step < 12; ++step) {
    solver.step(x, v);
    REQUIRE(x.allFinite());
    crossings.push_back(geometry::self_intersections(x, g->mesh.faces, 1000).size());
  }
  return crossings;
}

}  // namespace

TEST_CASE("self_contact keeps a falling layer on top", "[self_contact][solver]") {
  Eigen::MatrixX3d free_x, held_x;
  const std::vector<std::size_t> free = drop_layers(false, free_x);
  const std::vector<std::size_t> held = drop_layers(true, held_x);
  // Without the energy the upper sheet falls into the lower one: crossings.
  CHECK(*std::max_element(free.begin(), free.end()) > 0);
  // With it, no step ever crosses, and the upper sheet rests on the lower.
  CHECK(*std::max_element(held.begin(), held.end()) == 0);
  const double lower_top = held_x.topRows(169).col(2).maxCoeff();
  const double upper_bottom = held_x.bottomRows(81).col(2).minCoeff();
  CHECK(upper_bottom > lower_top);
  CHECK(upper_bottom < lower_top + 0.003);  // landed, not hovering
}

TEST_CASE("self_contact max_step on hand-made trajectories: parallel edges and a grazing pass", "[self_contact]") {
  // Two 1 cm squares of one garment (one quad each), the upper one 2 mm above
  // and moved 4 mm down in one step: halfway down it is level with the lower.
  auto sheets = [](double x_offset) {
    auto g = empty_garment();
    add_sheet(*g, 2, 0.01, 0.0, {0, 0, 0});
    add_sheet(*g, 2, 0.01, 0.0, {x_offset, 0, 0.002});
    return g;
  };
  // The step max_step allows for that move, and whether the contact is
  // finite and the sheets uncrossed where it ends.
  struct Step {
    double alpha;
    bool finite, uncrossed;
  };
  auto step_down = [&](double x_offset) {
    const auto g = sheets(x_offset);
    const auto e = self_contact_on(*g);
    const Eigen::MatrixX3d& x = g->mesh.vertices;
    Eigen::MatrixX3d dx = Eigen::MatrixX3d::Zero(x.rows(), 3);
    dx.bottomRows(4).col(2).setConstant(-0.004);
    const double alpha = e->max_step(x, dx);
    const Eigen::MatrixX3d end = x + alpha * dx;
    return Step{alpha, std::isfinite(e->value(end)), geometry::self_intersections(end, g->mesh.faces, 1).empty()};
  };
  // Parallel edges: the upper square's left edge right above the lower's
  // right edge, so the two edges pass through each other edge on edge (no
  // vertex ever over the other square's inside). The step is cut before
  // they meet, where the contact is finite.
  const Step parallel = step_down(0.01);
  INFO("parallel: alpha " << parallel.alpha);
  CHECK(parallel.alpha > 0);
  CHECK(parallel.alpha < 0.5);  // before the edges are level
  CHECK(parallel.finite);
  // A grazing pass: the upper square 0.3 mm beside the lower in plan, moved
  // down past its edge. The edges come no nearer than 0.3 mm: the step may
  // be shortened (the barrier's reach is 1 mm), but not stopped, and where it
  // ends the contact is finite.
  const Step grazing = step_down(0.0103);
  INFO("grazing: alpha " << grazing.alpha);
  CHECK(grazing.alpha > 0.5);  // past level with the lower square
  CHECK(grazing.finite);
  CHECK(grazing.uncrossed);
}
