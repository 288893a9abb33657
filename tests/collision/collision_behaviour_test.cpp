// The collision energy at work: Newton steps on it alone push a patch that
// starts deep inside a sphere out through the near side; a moving body is seen
// at the next call; any BodyQuery works, not only a BodySurface.
#include "collision_test_util.hpp"

#include <drape/energy.hpp>
#include <drape/geometry/penetration.hpp>

#include <Eigen/SparseCholesky>

#include <functional>

#include <catch2/catch.hpp>

using namespace drape;
using namespace drape::test;

namespace {

// Damped Newton on one energy: (H + lambda I) dx = -g with the projected
// Hessian, then backtracking until the energy falls. H alone is rank one per
// vertex (no tangential stiffness) and zero on max_depth's linear tail; lambda
// (N/m) stands in for the rest of a scene's stiffness. Returns the energy after every step.
std::vector<double> newton_steps(const Energy& e, Eigen::MatrixX3d& x, double lambda, int max_steps,
                                 const std::function<bool(const Eigen::MatrixX3d&)>& done) {
  const Eigen::Index n = 3 * x.rows();
  std::vector<double> energies{e.value(x)};
  for (int step = 0; step < max_steps && !done(x); ++step) {
    Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(x.rows(), 3);
    e.add_gradient(x, g);
    Triplets t;
    e.add_hessian(x, t, true);
    for (Eigen::Index i = 0; i < n; ++i) t.emplace_back(static_cast<int>(i), static_cast<int>(i), lambda);
    Eigen::SparseMatrix<double> h(n, n);
    h.setFromTriplets(t.begin(), t.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(h);
    REQUIRE(solver.info() == Eigen::Success);
    Eigen::VectorXd rhs(n);
    for (Eigen::Index i = 0; i < n; ++i) rhs[i] = -g(i / 3, i % 3);
    const Eigen::VectorXd dx = solver.solve(rhs);
    Eigen::MatrixX3d direction(x.rows(), 3);
    for (Eigen::Index i = 0; i < n; ++i) direction(i / 3, i % 3) = dx[i];
    double alpha = 1, next = e.value(x + direction);
    while (next >= energies.back() && alpha > 1e-6) next = e.value(x + (alpha *= 0.5) * direction);
    REQUIRE(next < energies.back());
    x += alpha * direction;
    energies.push_back(next);
  }
  return energies;
}

// A 5 x 5 patch, 1 cm apart, facing +Y, centred at `center`.
Eigen::MatrixX3d patch_at(const Eigen::Vector3d& center) {
  Eigen::MatrixX3d x(25, 3);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) x.row(5 * i + j) = center + Eigen::Vector3d(0.01 * (j - 2), 0.0, 0.01 * (i - 2));
  return x;
}

}  // namespace

TEST_CASE("Newton on collision alone pushes a patch from 60% of a sphere's radius out through the near side",
          "[collision]") {
  const double radius = 0.2;
  const geometry::BodySurface body = sphere_body(4, radius);
  const auto garment = grid_garment(5, 0.01);
  Eigen::MatrixX3d x = patch_at({0.0, 0.6 * radius, 0.0});
  const Eigen::MatrixX3d start = x;
  REQUIRE(geometry::penetration_ratio(body, x) == 1.0);
  REQUIRE(body.signed_distances(x).maxCoeff() < -0.07);

  const auto outside = [&](const Eigen::MatrixX3d& y) { return body.signed_distances(y).minCoeff() > 0; };
  struct Case {
    std::string yaml;
    double lambda;     // N/m
    int max_steps;
    double overshoot;  // m: how far beyond the sphere a step may end
  };
  // The pure cubic, on nearly pure Newton: each step halves the depth into the
  // margin (phi' / phi'' = delta / 2), so 8 cm take five steps and the last
  // ends inside the margin. With max_depth the push is constant down there and
  // the step length is set by lambda: more, shorter steps that may overshoot.
  for (const Case& c : {Case{"{}", 1e-2, 8, 0.003}, Case{"{max_depth: 0.01}", 10.0, 100, 0.02}}) {
    INFO(c.yaml);
    x = start;
    const auto e = collision_energy(c.yaml, *garment, &body);
    const std::vector<double> energies = newton_steps(*e, x, c.lambda, c.max_steps, outside);
    INFO("steps: " << energies.size() - 1 << ", last energy " << energies.back());
    CHECK(outside(x));
    CHECK(geometry::penetration_ratio(body, x) == 0.0);
    for (std::size_t i = 1; i < energies.size(); ++i) CHECK(energies[i] < energies[i - 1]);
    // Out through the near side, radially: not pulled through the body.
    for (int v = 0; v < 25; ++v) {
      CHECK(x.row(v).normalized().dot(start.row(v).normalized()) > 0.999);
      CHECK(x.row(v).norm() < radius + c.overshoot);
    }
  }
}

TEST_CASE("collision sees a body moved by BodySurface::update at the next call", "[collision]") {
  const auto garment = grid_garment(4, 0.03);
  geometry::BodySurface body = sphere_body(3, 0.2);
  const Eigen::MatrixX3d x = points_at_distances(body, Eigen::Vector3d::Zero(), 16, 0.004, 0.03, 4);
  const auto e = collision_energy("{}", *garment, &body);
  REQUIRE(e->value(x) == 0.0);

  const Mesh sphere = geometry::icosphere(3, 0.2);
  const Eigen::RowVector3d shift(0.02, 0.01, 0.0);
  const Eigen::MatrixX3d moved = sphere.vertices.rowwise() + shift;
  body.update(moved);
  const geometry::BodySurface fresh(moved, sphere.faces);
  const auto reference = collision_energy("{}", *garment, &fresh);
  const double after = e->value(x);
  CHECK(after > 0.0);
  CHECK(after == Approx(reference->value(x)).epsilon(1e-12));
  Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(16, 3), g_ref = Eigen::MatrixX3d::Zero(16, 3);
  e->add_gradient(x, g);
  reference->add_gradient(x, g_ref);
  CHECK((g - g_ref).norm() <= 1e-12 * g_ref.norm());
  // And back: the energy follows the body, nothing is cached from the first position.
  body.update(sphere.vertices);
  CHECK(e->value(x) == 0.0);
}

TEST_CASE("vertices skipped as surely beyond the margin change nothing: value, gradient and Hessian as a fresh energy's",
          "[collision]") {
  // One energy follows a trajectory (and so keeps its record of where each
  // vertex was and how far out); at every point it must answer bit for bit as
  // an energy that has never seen the garment. The trajectory wanders in and
  // out of the margin and the body, in small steps and large ones, and the
  // body moves half way.
  const auto garment = grid_garment(6, 0.03);
  geometry::BodySurface body = sphere_body(3, 0.2);
  const auto followed = collision_energy("{margin: 0.01}", *garment, &body);
  Eigen::MatrixX3d x = points_at_distances(body, Eigen::Vector3d::Zero(), 36, -0.02, 0.06, 9);
  std::mt19937_64 rng(17);
  std::normal_distribution<double> step;
  int inside_margin = 0, beyond = 0;
  for (int it = 0; it < 40; ++it) {
    if (it == 20) body.update(geometry::icosphere(3, 0.2).vertices.rowwise() + Eigen::RowVector3d(0.01, 0.0, -0.005));
    const auto fresh = collision_energy("{margin: 0.01}", *garment, &body);
    Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(x.rows(), 3), g_fresh = g;
    const double value = followed->add_gradient(x, g);
    CHECK(value == fresh->add_gradient(x, g_fresh));
    CHECK(followed->value(x) == fresh->value(x));
    CHECK(g == g_fresh);
    Triplets h, h_fresh;
    followed->add_hessian(x, h, true);
    fresh->add_hessian(x, h_fresh, true);
    REQUIRE(h.size() == h_fresh.size());
    for (std::size_t k = 0; k < h.size(); ++k) CHECK(h[k].value() == h_fresh[k].value());
    const Eigen::VectorXd d = body.signed_distances(x);
    inside_margin += static_cast<int>((d.array() < 0.01).count());
    beyond += static_cast<int>((d.array() >= 0.01).count());
    const double scale = it % 5 == 4 ? 0.02 : 0.002;
    for (Eigen::Index v = 0; v < x.rows(); ++v) x.row(v) += scale * Eigen::RowVector3d(step(rng), step(rng), step(rng));
  }
  // Both kinds were met, so both paths were compared.
  CHECK(inside_margin > 100);
  CHECK(beyond > 100);
}

namespace {

// A body known only through BodyQuery::closest (not a BodySurface).
class ForwardingBody final : public BodyQuery {
 public:
  explicit ForwardingBody(const geometry::BodySurface& surface) : surface_(surface) {}
  Hit closest(const Eigen::Vector3d& p) const override { return surface_.closest(p); }

 private:
  const geometry::BodySurface& surface_;
};

}  // namespace

TEST_CASE("collision works with any BodyQuery, without the curvature a BodySurface can give", "[collision]") {
  const geometry::BodySurface surface = sphere_body(1, 0.2);
  const ForwardingBody query(surface);
  const auto garment = grid_garment(5, 0.02);
  const Eigen::MatrixX3d x = points_at_distances(surface, Eigen::Vector3d::Zero(), 25, -0.01, 0.006, 8);
  const auto direct = collision_energy("{}", *garment, &surface);
  const auto generic = collision_energy("{}", *garment, &query);
  CHECK(generic->value(x) == direct->value(x));
  Eigen::MatrixX3d g = Eigen::MatrixX3d::Zero(25, 3), g_direct = Eigen::MatrixX3d::Zero(25, 3);
  CHECK(generic->add_gradient(x, g) == direct->add_gradient(x, g_direct));
  CHECK(g == g_direct);
  // The generic Hessian is the tangent-plane one, 2 k a (margin - d) n n^T per vertex.
  Triplets h;
  generic->add_hessian(x, h, false);
  REQUIRE(h.size() == 9 * 25);
  const Eigen::VectorXd d = surface.signed_distances(x);
  for (int v = 0; v < 25; ++v) {
    Eigen::Matrix3d block;
    for (int k = 0; k < 9; ++k) block(k / 3, k % 3) = h[9 * v + k].value();
    const double delta = 0.003 - d[v];
    const double tangential = (block - block * surface.closest(x.row(v).transpose()).normal *
                                           surface.closest(x.row(v).transpose()).normal.transpose()).norm();
    CHECK(tangential <= 1e-9 * (1 + block.norm()));
    if (delta <= 0) CHECK(block.isZero(0.0));
  }
  // Its gradient is still exact.
  const GradCheckReport r = check_energy_derivatives(*generic, x);
  INFO(r.str());
  CHECK(r.entries[0].max_error < 1e-6);
}
