// Every energy the registry finds, whatever its name, passes the same checks:
// its gradient and exact Hessian match finite differences, its projected
// Hessian is PSD, its lower-triangle Hessian is the full one's lower triangle
// (check_energy_derivatives), and value, gradient and both Hessians are
// bit-identical with 1 and 2 threads. A new energy plugin is checked here
// without being named; its own test file adds what is particular to it.
#include <drape/energy.hpp>
#include <drape/element_assembly.hpp>
#include <drape/gradcheck.hpp>
#include <drape/physics/dissipation.hpp>
#include <drape/materials/materials.hpp>

#include <catch2/catch.hpp>

#include <limits>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "../collision/collision_test_util.hpp"
#include "energy_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

// (ArcSim's knit, arcsim_knit(), and a linear print below: both stiffness
// models in one garment.)

// A box whose top face, z = top, spans [x0, x1] x [y0, y1]; counter-clockwise from outside.
Mesh box(double x0, double x1, double y0, double y1, double top) {
  Mesh m;
  m.vertices.resize(8, 3);
  const double z0 = top - 2.0;
  for (int i = 0; i < 8; ++i) m.vertices.row(i) << (i & 1 ? x1 : x0), (i & 2 ? y1 : y0), (i & 4 ? top : z0);
  m.faces.resize(12, 3);
  m.faces << 0, 2, 1, 1, 2, 3,  // bottom (z0), facing -z
      4, 5, 6, 5, 7, 6,         // top, facing +z
      0, 1, 4, 1, 5, 4,         // y0, facing -y
      2, 6, 3, 3, 6, 7,         // y1, facing +y
      0, 4, 2, 2, 4, 6,         // x0, facing -x
      1, 3, 5, 3, 7, 5;         // x1, facing +x
  return m;
}

// A grid garment of both stiffness models lying on a body: the body's top is
// 2 mm above the garment's plane, so every vertex is in contact (inside by up
// to 2 mm) and every energy has work to do. The contact is with one flat face
// pair, away from the body's edges: a kinked energy (has_kinks: its gradient
// jumps where the closest body feature changes) is smooth there, so its
// derivatives can be compared with differences.
struct Scene {
  std::shared_ptr<Garment> garment;
  geometry::BodySurface body;
  Eigen::MatrixX3d x;
};

Scene scene(int n, double spacing, double perturbation) {
  const double size = (n - 1) * spacing;
  Scene s{two_material_grid(n, spacing), geometry::BodySurface(box(-1.0, 1.0 + size, 0.0, 2.0 + size, 0.002)), {}};
  s.garment->materials[0] = arcsim_knit();
  Eigen::MatrixX3d x = s.garment->mesh.vertices;
  x.col(0) *= 1.05;  // in tension along u: the strain-dependent stiffness is away from its rest values
  s.x = perturbed(x, perturbation, 23);
  return s;
}

std::vector<std::string> energy_names() {
  std::vector<std::string> names;
  for (const auto& name : plugins().names())
    if (plugins().get(name).kind == "energy") names.push_back(name);
  return names;
}

std::unique_ptr<Energy> bound(const std::string& name, const Scene& s) {
  auto e = plugins().create_energy(name, params_for(name, "{}"));
  EnergyContext ctx;
  ctx.garment = s.garment.get();
  if (e->needs_body()) ctx.body = &s.body;
  e->bind(ctx);
  return e;
}

struct Evaluation {
  double value, gradient_value;
  Eigen::MatrixX3d gradient;
  Triplets hessian, projected, lower;
};

Evaluation evaluate(const Energy& e, const Eigen::MatrixX3d& x) {
  Evaluation r;
  r.value = e.value(x);
  r.gradient = Eigen::MatrixX3d::Zero(x.rows(), 3);
  r.gradient_value = e.add_gradient(x, r.gradient);
  e.add_hessian(x, r.hessian, false);
  e.add_hessian(x, r.projected, true);
  e.add_hessian_lower(x, r.lower, true);
  return r;
}

bool identical(const Triplets& a, const Triplets& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].row() != b[i].row() || a[i].col() != b[i].col() || a[i].value() != b[i].value()) return false;
  return true;
}

}  // namespace

TEST_CASE("the registry has the shipped energies", "[conformance]") {
  const auto names = energy_names();
  for (const char* shipped : {"gravity", "stretching", "bending", "collision", "barrier", "self_contact"})
    CHECK(std::find(names.begin(), names.end(), shipped) != names.end());
}

TEST_CASE("every registered energy's derivatives match finite differences and its Newton Hessian is PSD", "[conformance][gradcheck]") {
  const Scene s = scene(6, 0.04, 0.002);
  for (const std::string& name : energy_names()) {
    const auto e = bound(name, s);
    // Central differences with a step of 1e-7 m: ArcSim's stiffness varies
    // fast with strain (grid cells of 1/30), so the truncation error of a
    // 1e-6 step reaches 2e-5 on this grid; it falls as the step squared.
    // A barrier's curvature grows like 1/d^2 as a pair closes in (here some
    // vertices are micrometres from the box face): its step is 1e-9 m.
    const double step = e->bounds_steps() ? 1e-9 : 1e-7;
    const GradCheckReport r = check_energy_derivatives(*e, s.x, {step, 64, 7});
    INFO(name << "\n" << r.str());
    CHECK(std::isfinite(e->value(s.x)));
    CHECK(r.ok(1e-5));
  }
}

TEST_CASE("every registered energy gives bit-identical results with 1 and 2 threads", "[conformance]") {
#ifndef _OPENMP
  WARN("built without OpenMP: nothing to compare");
#else
  // 8464 vertices, 16562 faces, 24655 hinges: past the sizes from which sums run in parallel.
  const Scene s = scene(92, 0.005, 0.0015);
  static_assert(2 * 91 * 91 >= kParallelSumMinimum);
  for (const std::string& name : energy_names()) {
    const auto e = bound(name, s);
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    const Evaluation one = evaluate(*e, s.x);
    omp_set_num_threads(2);
    const Evaluation two = evaluate(*e, s.x);
    omp_set_num_threads(threads);
    INFO(name);
    CHECK(std::isfinite(one.value));
    CHECK(one.value == two.value);
    CHECK(one.gradient_value == Approx(one.value).epsilon(1e-12));
    CHECK(two.gradient_value == one.gradient_value);
    CHECK(one.gradient == two.gradient);
    CHECK(identical(one.hessian, two.hessian));
    CHECK(identical(one.projected, two.projected));
    CHECK(identical(one.lower, two.lower));
  }
#endif
}

TEST_CASE("every registered energy refuses a non-finite position with one line naming the vertex", "[conformance]") {
  // A NaN coordinate once reached ArcSim's stiffness lookup as a grid index
  // and crashed the process (issue 58). Every entry point that takes
  // positions refuses them first, whatever the energy.
  const Scene s = scene(6, 0.04, 0.002);
  const Eigen::Index bad_vertex = 17;
  for (const std::string& name : energy_names()) {
    const auto e = bound(name, s);
    for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                             -std::numeric_limits<double>::infinity()}) {
      for (int axis = 0; axis < 3; ++axis) {
        Eigen::MatrixX3d x = s.x;
        x(bad_vertex, axis) = bad;
        INFO(name << ", coordinate " << axis << " = " << bad);
        Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(x.rows(), 3);
        Triplets h;
        const Eigen::MatrixX3d no_move = Eigen::MatrixX3d::Zero(x.rows(), 3);
        const std::string expected = name + ": garment vertex 17 has a non-finite coordinate";
        CHECK_THROWS_WITH(e->value(x), Catch::Contains(expected));
        CHECK_THROWS_WITH(e->add_gradient(x, g), Catch::Contains(expected));
        CHECK_THROWS_WITH(e->add_hessian(x, h, true), Catch::Contains(expected));
        CHECK_THROWS_WITH(e->add_hessian(x, h, false), Catch::Contains(expected));
        CHECK_THROWS_WITH(e->add_hessian_lower(x, h, true), Catch::Contains(expected));
        CHECK_THROWS_AS(e->value(x), ConfigError);  // the caller's input: exit 2, Python's ValueError
        if (e->bounds_steps()) {
          CHECK_THROWS_WITH(e->max_step(x, no_move), Catch::Contains(expected));
          // ... and a non-finite move from a finite state.
          Eigen::MatrixX3d move = no_move;
          move(bad_vertex, axis) = bad;
          CHECK_THROWS_WITH(e->max_step(s.x, move), Catch::Contains("non-finite"));
        }
        if (!e->has_kinks()) continue;
        std::vector<Eigen::Vector3d> samples;
        CHECK_THROWS_WITH(e->vertex_gradient_samples(x, static_cast<int>(bad_vertex), 1e-3, samples),
                          Catch::Contains("not finite"));
      }
    }
    // Friction's lagged terms take positions too.
    auto with_friction = plugins().create_energy(name, params_for(name, name == "barrier" ? "{friction: 0.3}" : "{}"));
    EnergyContext ctx;
    ctx.garment = s.garment.get();
    if (with_friction->needs_body()) ctx.body = &s.body;
    with_friction->bind(ctx);
    Dissipation* friction = with_friction->dissipation();
    CHECK((friction != nullptr) == (name == "barrier"));  // only the barrier carries friction
    Eigen::MatrixX3d x = s.x;
    x(bad_vertex, 1) = std::numeric_limits<double>::quiet_NaN();
    INFO(name << " with friction");
    if (friction) {
      friction->begin_step(s.x, 0.1);
      CHECK_THROWS_WITH(friction->begin_step(x, 0.1), Catch::Contains("non-finite"));
      Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(x.rows(), 3);
      Triplets h;
      CHECK_THROWS_WITH(friction->value(x), Catch::Contains("non-finite"));
      CHECK_THROWS_WITH(friction->add_gradient(x, g), Catch::Contains("non-finite"));
      CHECK_THROWS_WITH(friction->add_hessian_lower(x, h), Catch::Contains("non-finite"));
      CHECK_THROWS_WITH(friction->slip_ratio(x), Catch::Contains("non-finite"));
    }
  }
}

TEST_CASE("every registered energy stays finite or refuses at a coordinate of 1e308, without crashing", "[conformance]") {
  // Finite but absurd: an energy may overflow to inf (a barrier pair would
  // then be far apart), but must not crash or hang on it.
  const Scene s = scene(6, 0.04, 0.002);
  for (const std::string& name : energy_names()) {
    const auto e = bound(name, s);
    Eigen::MatrixX3d x = s.x;
    x(17, 0) = 1e308;
    INFO(name);
    Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(x.rows(), 3);
    Triplets h;
    try {
      (void)e->value(x);
      e->add_gradient(x, g);
      e->add_hessian_lower(x, h, true);
      SUCCEED("evaluated");
    } catch (const Error& error) {
      SUCCEED(std::string("refused: ") + error.what());
    }
  }
}
