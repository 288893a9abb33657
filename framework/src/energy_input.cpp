// check_energy_input (energy_input.hpp).
#include <drape/energy_input.hpp>
#include <drape/error_context.hpp>
#include <drape/errors.hpp>

#include <cmath>
#include <cstdio>

namespace drape {

void check_energy_input(const Eigen::MatrixX3d& x, Eigen::Index expected_vertices) {
  if (x.rows() != expected_vertices)
    throw ConfigError(std::to_string(x.rows()) + " vertices given, the bound garment has " +
                      std::to_string(expected_vertices) + (expected_vertices == 0 ? " (bind() was not called)" : ""));
  if (x.allFinite()) return;  // the common case: one pass, no branch per coordinate
  for (Eigen::Index v = 0; v < x.rows(); ++v)
    for (int axis = 0; axis < 3; ++axis)
      if (!std::isfinite(x(v, axis))) {
        char value[32];
        std::snprintf(value, sizeof value, "%g", x(v, axis));
        throw ConfigError("garment vertex " + std::to_string(v) + " has a non-finite coordinate (" + "xyz"[axis] +
                          " = " + value + "); an energy is defined on finite positions only");
      }
}

void check_energy_input(const std::string& energy, const Eigen::MatrixX3d& x, Eigen::Index expected_vertices) {
  in_context(energy, [&] { check_energy_input(x, expected_vertices); });
}

}  // namespace drape
