// Point-triangle closest points against an exhaustive long-double reference,
// on ordinary, degenerate and near-degenerate triangles.
#include "reference.hpp"

#include <drape/geometry/closest_point.hpp>

#include <catch2/catch.hpp>

#include <random>

using drape::geometry::closest_point_on_triangle;
using drape::geometry::TriangleFeature;
using drape::geometry::TrianglePoint;

namespace {

Eigen::Vector3d random_point(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return {u(rng), u(rng), u(rng)};
}

// The answer must be a point of the triangle (its barycentric combination) at
// the reference distance.
void check(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const TrianglePoint q = closest_point_on_triangle(p, a, b, c);
  INFO("p " << p.transpose() << " a " << a.transpose() << " b " << b.transpose() << " c " << c.transpose());
  REQUIRE(q.point.allFinite());
  REQUIRE(q.barycentric.allFinite());
  CHECK(q.barycentric.minCoeff() >= 0);
  CHECK(q.barycentric.maxCoeff() <= 1);
  CHECK(q.barycentric.sum() == Approx(1).margin(1e-12));
  // Rounding is relative to the coordinates, not only to the triangle's size.
  const double scale = std::max({(a - p).norm(), (b - p).norm(), (c - p).norm(), p.norm(), a.norm()});
  const Eigen::Vector3d from_weights = q.barycentric[0] * a + q.barycentric[1] * b + q.barycentric[2] * c;
  CHECK((from_weights - q.point).norm() <= 1e-12 * scale);
  const double reference = static_cast<double>(std::sqrt(drape::test::triangle_distance2(p, a, b, c)));
  CHECK(std::abs((q.point - p).norm() - reference) <= 1e-12 * scale);
}

}  // namespace

TEST_CASE("closest point on random triangles matches the exhaustive reference") {
  std::mt19937 rng(7);
  for (int i = 0; i < 20000; ++i) check(random_point(rng, 2), random_point(rng, 1), random_point(rng, 1), random_point(rng, 1));
}

TEST_CASE("closest point on degenerate and near-degenerate triangles stays finite and exact") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int i = 0; i < 5000; ++i) {
    const Eigen::Vector3d a = random_point(rng, 1), b = random_point(rng, 1), p = random_point(rng, 2);
    const Eigen::Vector3d d = random_point(rng, 1);
    // Collinear, with c between, beyond or before a and b.
    check(p, a, b, a + (3 * unit(rng) - 1) * (b - a));
    // Two or three coincident corners.
    check(p, a, a, b);
    check(p, a, b, b);
    check(p, b, a, a);
    check(p, a, a, a);
    // Slivers: c off the line ab by 1e-9 .. 1e-15 of the size.
    const double off = std::pow(10.0, -9 - 6 * unit(rng));
    check(p, a, b, 0.5 * (a + b) + off * d);
    // Tiny triangles, far and near.
    const double tiny = std::pow(10.0, -6 - 8 * unit(rng));
    check(p, a, a + tiny * b, a + tiny * d);
    check(a + 2 * tiny * p, a, a + tiny * b, a + tiny * d);
  }
}

TEST_CASE("closest point reports the feature it lies on") {
  const Eigen::Vector3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  CHECK(closest_point_on_triangle({-1, -1, 0.3}, a, b, c).feature == TriangleFeature::vertex_a);
  CHECK(closest_point_on_triangle({2, -0.1, 0}, a, b, c).feature == TriangleFeature::vertex_b);
  CHECK(closest_point_on_triangle({-0.1, 3, 1}, a, b, c).feature == TriangleFeature::vertex_c);
  CHECK(closest_point_on_triangle({0.5, -1, 0}, a, b, c).feature == TriangleFeature::edge_ab);
  CHECK(closest_point_on_triangle({1, 1, -2}, a, b, c).feature == TriangleFeature::edge_bc);
  CHECK(closest_point_on_triangle({-1, 0.5, 0}, a, b, c).feature == TriangleFeature::edge_ca);
  const TrianglePoint in = closest_point_on_triangle({0.2, 0.3, 5}, a, b, c);
  CHECK(in.feature == TriangleFeature::interior);
  CHECK((in.point - Eigen::Vector3d(0.2, 0.3, 0)).norm() < 1e-15);
  CHECK((in.barycentric - Eigen::Vector3d(0.5, 0.2, 0.3)).norm() < 1e-15);
}
