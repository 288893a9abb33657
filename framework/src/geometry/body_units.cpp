// body_units_problem / check_body_units (body_units.hpp).
#include <drape/geometry/body_units.hpp>
#include <drape/errors.hpp>

#include <cmath>
#include <cstdio>
#include <vector>

namespace drape {

namespace {
// Farther than this from the origin a vertex is no part of a body placed in
// the model's frame (the checks below would only print huge numbers).
constexpr double kFarthest = 1e9;  // m: a body in micrometres (1,750 km tall) still gets the units hint
// A typical adult height: the suggested power of ten brings the body nearest it.
constexpr double kTypicalHeight = 1.7;  // m
}  // namespace

std::string body_units_problem(const Eigen::MatrixX3d& body, const std::string& what) {
  if (body.rows() == 0) return what + " has no vertices";
  std::vector<char> line(what.size() + 512);
  for (Eigen::Index v = 0; v < body.rows(); ++v)
    for (int axis = 0; axis < 3; ++axis) {
      const double c = body(v, axis);
      if (!std::isfinite(c) || std::abs(c) > kFarthest) {
        std::snprintf(line.data(), line.size(), "%s: body vertex %ld has %c = %.4g, %s", what.c_str(), static_cast<long>(v),
                      "xyz"[axis], c,
                      std::isfinite(c) ? "over 1e9 m from the origin, far beyond any body: drape reads metres, in the body model's frame"
                                       : "not a number: every coordinate of a body must be finite");
        return line.data();
      }
    }
  const Eigen::RowVector3d extent = body.colwise().maxCoeff() - body.colwise().minCoeff();
  Eigen::Index longest = 0;
  const double size = extent.maxCoeff(&longest);
  if (size > HeightRange::max || size < HeightRange::min) {
    const double scale = std::pow(10.0, std::round(std::log10(kTypicalHeight / size)));
    const char* unit = scale == 0.1 ? "decimetres" : scale == 0.01 ? "centimetres" : scale == 0.001 ? "millimetres"
                     : scale == 1e-6 ? "micrometres" : "other units";
    std::snprintf(line.data(), line.size(),
                  "%s is %.4g m tall (its longest extent): drape reads metres and takes bodies of %.1f-%.1f m, so the "
                  "body is likely in %s (scaled by %g it would be %.3g m)",
                  what.c_str(), size, HeightRange::min, HeightRange::max, unit, scale, scale * size);
    return line.data();
  }
  if (longest != 1 && extent[longest] > 1.3 * extent[1]) {
    std::snprintf(line.data(), line.size(),
                  "%s is longer along %c than along y (%.3g m against %.3g m): drape's bodies stand along y (Y up, "
                  "A-pose), as the body model makes them; export it Y up",
                  what.c_str(), "xyz"[longest], extent[longest], extent[1]);
    return line.data();
  }
  return {};
}

void check_body_units(const Eigen::MatrixX3d& body, const std::string& what) {
  const std::string problem = body_units_problem(body, what);
  if (!problem.empty()) throw ConfigError(problem);
}

}  // namespace drape
