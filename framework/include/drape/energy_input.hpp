#pragma once
// The one check every energy makes of the positions it is given, before any
// arithmetic on them: the count its bind() expects, and every coordinate
// finite. A NaN coordinate would otherwise reach table lookups (ArcSim's
// stiffness grid indexes by strain) and closest-point searches as an index
// or a comparison that is always false, and crash or loop; an energy refuses
// it with one line naming the vertex instead (drape::ConfigError: the CLI prints it,
// Python raises ValueError).
#include <Eigen/Core>

#include <string>

namespace drape {

// Throws drape::ConfigError (the caller's input) when x has not
// `expected_vertices` rows (0: bind() was not called) or holds a non-finite
// coordinate. The framework puts the energy's name in front (error_context.hpp).
void check_energy_input(const Eigen::MatrixX3d& x, Eigen::Index expected_vertices);
// The same, with the messages prefixed by `energy` (for code called outside
// the registry's plugin calls).
void check_energy_input(const std::string& energy, const Eigen::MatrixX3d& x, Eigen::Index expected_vertices);

}  // namespace drape
