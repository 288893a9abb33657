#pragma once
// Helpers for the collision tests: the energy built through the registry and
// bound to a body, sphere bodies, and garments whose vertices sit at chosen
// signed distances from a body.
#include "../plugins/plugin_test_util.hpp"

#include <drape/energy.hpp>
#include <drape/geometry/closed_shapes.hpp>
#include <drape/geometry/closest_point.hpp>

#include <Eigen/Geometry>

#include <memory>
#include <random>
#include <string>

namespace drape::test {

inline std::unique_ptr<Energy> collision_energy(const std::string& yaml, const Garment& garment, const BodyQuery* body) {
  auto e = plugins().create_energy("collision", params_for("collision", yaml));
  EnergyContext ctx;
  ctx.garment = &garment;
  ctx.body = body;
  e->bind(ctx);
  return e;
}

inline geometry::BodySurface sphere_body(int level, double radius) {
  return geometry::BodySurface(geometry::icosphere(level, radius));
}

// A point at signed distance `distance` from the body along the normal of face
// f at barycentric weights w: its closest point is that face point as long as
// |distance| is small against the face and its neighbours.
inline Eigen::Vector3d off_face(const geometry::BodySurface& body, int f, const Eigen::Vector3d& w, double distance) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Vector3d corner[3];
  for (int k = 0; k < 3; ++k) {
    corner[k] = body.vertices().row(body.faces()(f, k));
    p += w[k] * corner[k];
  }
  const Eigen::Vector3d n = (corner[1] - corner[0]).cross(corner[2] - corner[0]).normalized();
  return p + distance * n;
}

// n x n garment points at random directions about `center`, each at a signed
// distance drawn from [lo, hi] from the body (a sphere or any star-shaped body
// about center); positions found by bisection along the ray.
inline Eigen::MatrixX3d points_at_distances(const geometry::BodySurface& body, const Eigen::Vector3d& center, int count,
                                            double lo, double hi, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(lo, hi);
  Eigen::MatrixX3d x(count, 3);
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d dir = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    const double target = u(rng);
    double a = 0, b = 10;  // signed distance increases along the ray out of a star-shaped body
    for (int it = 0; it < 80; ++it) {
      const double m = 0.5 * (a + b);
      (body.locate(center + m * dir).signed_distance < target ? a : b) = m;
    }
    x.row(i) = center + 0.5 * (a + b) * dir;
  }
  return x;
}

}  // namespace drape::test
