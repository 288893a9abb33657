// body_units_problem / check_body_units (body_units.hpp).
#include <drape/geometry/body_units.hpp>
#include <drape/errors.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace drape {

namespace {
// Farther than this from the origin a vertex is no part of a body placed in
// the model's frame (the checks below would only print huge numbers).
constexpr double kFarthest = 1e9;  // m: a body in micrometres (1,750 km tall) still gets the units hint
// A typical adult height: the suggested unit brings the body nearest it.
constexpr double kTypicalHeight = 1.7;  // m

// ": N vertices lie ... (vertex i at ...)" when all but the farthest half
// percent of the vertices on each side of each axis span a body's height and
// the rest stick out beyond it; "" otherwise.
std::string stray_vertices(const Eigen::MatrixX3d& body, double size) {
  const auto n = static_cast<std::size_t>(body.rows());
  const std::size_t cut = n / 200;
  if (cut == 0) return {};
  double core = 0;
  Eigen::Vector3d lo, hi;
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> c(body.col(axis).data(), body.col(axis).data() + n);
    std::nth_element(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(cut), c.end());
    lo[axis] = c[cut];
    std::nth_element(c.begin(), c.end() - 1 - static_cast<std::ptrdiff_t>(cut), c.end());
    hi[axis] = c[n - 1 - cut];
    core = std::max(core, hi[axis] - lo[axis]);
  }
  if (core < HeightRange::min || core > HeightRange::max || size < 1.5 * core) return {};
  // Beyond the core's box by more than a tenth of its size: stray.
  int count = 0;
  Eigen::Index farthest = 0;
  double worst = 0;
  for (Eigen::Index v = 0; v < body.rows(); ++v) {
    const Eigen::Vector3d p = body.row(v).transpose();
    const double out = (p - p.cwiseMax(lo).cwiseMin(hi)).norm();
    if (out > 0.1 * core) ++count;
    if (out > worst) worst = out, farthest = v;
  }
  char line[320];
  std::snprintf(line, sizeof line,
                ": %d vertices lie far outside the rest of the body, which is %.3g m tall (vertex %ld at (%.3g, %.3g, "
                "%.3g), %.3g m beyond it): a spike or stray points, not a body in other units",
                count, core, static_cast<long>(farthest), body(farthest, 0), body(farthest, 1), body(farthest, 2), worst);
  return line;
}
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
  if (!(size > 0)) {
    std::snprintf(line.data(), line.size(), "%s has every vertex at one point (0 m tall): it is no body", what.c_str());
    return line.data();
  }
  if (size > HeightRange::max || size < HeightRange::min) {
    // A few stray vertices (a spike) make a body of the right size look too
    // tall: the extent of all but the farthest half percent on each side says so.
    if (const std::string stray = stray_vertices(body, size); !stray.empty()) return what + stray;
    // The unit that brings the body nearest a typical height (inches and
    // feet too: a body in inches read as centimetres would be 0.69 m tall).
    struct Unit {
      const char* name;
      double metres;
    };
    constexpr Unit kUnits[] = {{"decimetres", 0.1},  {"centimetres", 0.01}, {"millimetres", 0.001},
                               {"micrometres", 1e-6}, {"inches", 0.0254},   {"feet", 0.3048}};
    const Unit* best = nullptr;
    for (const Unit& u : kUnits) {
      const double scaled = u.metres * size;
      if (scaled < HeightRange::min || scaled > HeightRange::max) continue;
      if (!best || std::abs(std::log(scaled / kTypicalHeight)) < std::abs(std::log(best->metres * size / kTypicalHeight))) best = &u;
    }
    if (best)
      std::snprintf(line.data(), line.size(),
                    "%s is %.4g m tall (its longest extent): drape reads metres and takes bodies of %.1f-%.1f m, so the "
                    "body is likely in %s (scaled by %g it would be %.3g m)",
                    what.c_str(), size, HeightRange::min, HeightRange::max, best->name, best->metres, best->metres * size);
    else
      std::snprintf(line.data(), line.size(),
                    "%s is %.4g m tall (its longest extent): drape reads metres and takes bodies of %.1f-%.1f m; no "
                    "common unit brings it there (scaled by %.3g it would be %.3g m)",
                    what.c_str(), size, HeightRange::min, HeightRange::max, kTypicalHeight / size, kTypicalHeight);
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

double float_rounding(double x) { return x == 0.0 ? 0.0 : std::ldexp(1.0, std::ilogb(std::abs(x)) - 24); }

}  // namespace drape
