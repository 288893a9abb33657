#pragma once
// What the barrier contact's tests share: a closed box for a body, and the
// barrier bound to a garment on it.
#include <drape/energy.hpp>
#include <drape/geometry/closest_point.hpp>

#include "../energies/energy_test_util.hpp"

#include <memory>
#include <string>

namespace drape::test {

// A closed box [x0, x1] x [y0, y1] x [z0, z1], counter-clockwise seen from outside.
inline Mesh box(double x0, double x1, double y0, double y1, double z0, double z1) {
  Mesh m;
  m.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i) m.vertices.row(i) << (i & 1 ? x1 : x0), (i & 2 ? y1 : y0), (i & 4 ? z1 : z0);
  m.faces.resize(12, 3);
  m.faces << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5;
  return m;
}

inline std::unique_ptr<Energy> barrier_on(const Garment& g, const geometry::BodySurface& body, const std::string& yaml = "{}") {
  auto e = plugins().create_energy("barrier", params_for("barrier", yaml));
  EnergyContext ctx;
  ctx.garment = &g;
  ctx.body = &body;
  e->bind(ctx);
  return e;
}

}  // namespace drape::test
