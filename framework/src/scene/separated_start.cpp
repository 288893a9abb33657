// The start-state check of a barrier contact run (separated_start.hpp).
#include "separated_start.hpp"

#include <drape/errors.hpp>
#include <drape/geometry/surface_crossings.hpp>
#include <drape/simulation.hpp>

#include <algorithm>
#include <cstdio>
#include <numeric>

namespace drape::scene_detail {

namespace {
// How far (m) a start body may be shrunk along its normals, tried in turn.
constexpr double kShrinkDepths[] = {0.0, 0.005, 0.01, 0.02, 0.03, 0.04, 0.06};
}  // namespace

std::string describe_region(const Eigen::MatrixX3d& x, const std::vector<int>& vertices) {
  if (vertices.empty()) return "no garment vertices";
  Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
  double low = x(vertices.front(), 1), high = low;
  for (int v : vertices) {
    centre += x.row(v);
    low = std::min(low, x(v, 1));
    high = std::max(high, x(v, 1));
  }
  centre /= static_cast<double>(vertices.size());
  char text[160];
  std::snprintf(text, sizeof text, "%zu garment vertices around (%.3f, %.3f, %.3f) m, heights %.3f-%.3f m (vertex %d",
                vertices.size(), centre[0], centre[1], centre[2], low, high, vertices.front());
  std::string out = text;
  for (std::size_t i = 1; i < std::min<std::size_t>(vertices.size(), 5); ++i) out += ", " + std::to_string(vertices[i]);
  return out + (vertices.size() > 5 ? ", ...)" : ")");
}

void check_separated_start(const Eigen::MatrixX3d& x, const geometry::BodySurface& body, const Eigen::MatrixX3i& garment_faces) {
  const Eigen::VectorXd d = body.signed_distances(x);
  std::vector<int> inside;
  for (Eigen::Index v = 0; v < d.size(); ++v)
    if (!(d[v] > 0)) inside.push_back(static_cast<int>(v));
  if (!inside.empty())
    throw ConfigError("simulate: the garment starts inside the body (" + describe_region(x, inside) +
                      ", deepest " + std::to_string(-d.minCoeff() * 100) +
                      " cm); the barrier contact keeps surfaces apart but cannot pull them apart: start from a "
                      "garment outside the body, or use the penalty contact (effect `collision`) for this start");
  const geometry::SurfaceCrossings crossings = geometry::surface_crossings(x, garment_faces, body.vertices(), body.faces());
  if (crossings.total() > 0)
    throw ConfigError("simulate: the garment starts crossing the body surface (" +
                      std::to_string(crossings.garment_edges_through_body) + " garment edges through body faces, " +
                      std::to_string(crossings.body_edges_through_garment) + " body edges through garment faces; " +
                      describe_region(x, crossings.garment_vertices) +
                      "); the barrier contact cannot untangle them (nor, when the scene "
                      "morphs, does a start body shrunk by up to 6 cm free the garment): start from a separated garment, or use the penalty contact (effect "
                      "`collision`) for this start");
}

Eigen::MatrixX3d separated_start_body(const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& body,
                                      const Eigen::MatrixX3i& body_faces, const Eigen::MatrixX3i& garment_faces,
                                      double* shrink) {
  const geometry::BodySurface original(body, body_faces);
  for (double depth : kShrinkDepths) {
    Eigen::MatrixX3d shrunk = body - depth * original.vertex_normals();
    const geometry::BodySurface surface(shrunk, body_faces);
    try {
      check_separated_start(x, surface, garment_faces);
    } catch (const ConfigError&) {
      continue;
    }
    if (shrink) *shrink = depth;
    return shrunk;
  }
  check_separated_start(x, original, garment_faces);  // throws, naming the region
  return body;
}

std::string why_unsettled(const SimulationResult& result, const Eigen::MatrixX3d& x, double tolerance, int settle_steps) {
  char head[200];
  std::snprintf(head, sizeof head, "not settled after %d settling steps: stationarity %.2e of the weight, tolerance %.2e",
                settle_steps, result.stationarity, tolerance);
  std::string out = head;
  // The vertices carrying the largest unbalanced forces (the top 2 %, at least 3).
  const Eigen::VectorXd& f = result.vertex_force;
  std::vector<int> order(static_cast<std::size_t>(f.size()));
  std::iota(order.begin(), order.end(), 0);
  const std::size_t shown = std::min(order.size(), std::max<std::size_t>(3, order.size() / 50));
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(shown), order.end(),
                    [&](int a, int b) { return f[a] > f[b]; });
  order.resize(shown);
  std::sort(order.begin(), order.end());
  out += "; the largest unbalanced forces (up to " + std::to_string(f.maxCoeff()) + " N) are on " + describe_region(x, order);
  if (result.line_search_failures > 0)
    out += "; " + std::to_string(result.line_search_failures) +
           " Newton iterations found no decrease (the garment may be pinched between parts of the body, or not fit it)";
  return out;
}

}  // namespace drape::scene_detail
