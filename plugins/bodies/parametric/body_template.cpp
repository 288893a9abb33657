#include "body_template.hpp"

#include "body_plan.hpp"
#include "surface_nets.hpp"
#include "vertex_order.hpp"

#include <drape/errors.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/topology.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <map>
#include <numeric>

namespace drape::parametric {
namespace {

// Width of the part weights: parts whose surface is this much (m) further away
// than the nearest one get e^-1 of its weight.
constexpr double kBindWidth = 0.012;

// Where a rejected sampling joined sheets: each edge used by more than two
// faces, for whoever reshapes a rig (DRAPE_BODY_DEBUG=1).
void print_shared_edges(const RawMesh& raw, int attempt) {
  std::map<std::pair<int, int>, int> uses;
  for (Eigen::Index f = 0; f < raw.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int u = raw.faces(f, c), w = raw.faces(f, (c + 1) % 3);
      ++uses[{std::min(u, w), std::max(u, w)}];
    }
  for (const auto& [edge, count] : uses)
    if (count > 2)
      std::fprintf(stderr, "attempt %d: edge at (%.3f, %.3f, %.3f) m in %d faces\n", attempt, raw.vertices(edge.first, 0),
                   raw.vertices(edge.first, 1), raw.vertices(edge.first, 2), count);
}

void bind_to_parts(BodyTemplate& t) {
  const auto nv = static_cast<std::size_t>(t.vertices.rows());
  t.bind_part.assign(nv, {});
  t.bind_weight.assign(nv, {});
  std::vector<std::pair<double, int>> dist(t.mean.parts.size());
  for (std::size_t v = 0; v < nv; ++v) {
    const Eigen::Vector3d p = t.vertices.row(static_cast<Eigen::Index>(v));
    for (std::size_t i = 0; i < dist.size(); ++i)
      dist[i] = {t.mean.parts[i].carries ? t.mean.parts[i].eval(p, nullptr) : INFINITY, static_cast<int>(i)};
    std::partial_sort(dist.begin(), dist.begin() + BodyTemplate::kBind, dist.end());
    double total = 0;
    for (int k = 0; k < BodyTemplate::kBind; ++k) {
      const double w = std::exp(-(dist[static_cast<std::size_t>(k)].first - dist[0].first) / kBindWidth);
      t.bind_part[v][static_cast<std::size_t>(k)] = dist[static_cast<std::size_t>(k)].second;
      t.bind_weight[v][static_cast<std::size_t>(k)] = w;
      total += w;
    }
    for (double& w : t.bind_weight[v]) w /= total;
  }
}

}  // namespace

void relax_on_surface(const ImplicitBody& body, const std::vector<std::vector<int>>& neighbours,
                      Eigen::MatrixX3d& vertices, int iterations, double step) {
  Eigen::MatrixX3d next(vertices.rows(), 3), warped;
  Eigen::Vector3d g;
  for (int it = 0; it < iterations; ++it) {
    // Each vertex warped once per iteration, not once per neighbour.
    if (!body.magnifiers.empty()) {
      warped.resize(vertices.rows(), 3);
      for (Eigen::Index v = 0; v < vertices.rows(); ++v) warped.row(v) = warp(body.magnifiers, vertices.row(v).transpose()).transpose();
    }
    for (Eigen::Index v = 0; v < vertices.rows(); ++v) {
      const auto& nb = neighbours[static_cast<std::size_t>(v)];
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (int u : nb) mean += vertices.row(u).transpose();
      mean /= static_cast<double>(nb.size());
      const Eigen::Vector3d p = vertices.row(v);
      body.eval(p, &g);
      const Eigen::Vector3d n = g.normalized();
      Eigen::Vector3d d = mean - p;
      if (!body.magnifiers.empty()) {
        // The neighbours' mean in the warped space, where the mesh is uniform:
        // relaxing keeps the finer triangles where the template put them.
        Eigen::Vector3d warped_mean = Eigen::Vector3d::Zero();
        for (int u : nb) warped_mean += warped.row(u).transpose();
        warped_mean /= static_cast<double>(nb.size());
        const Eigen::Vector3d wp = warped.row(v).transpose();
        d = (unwarp(body.magnifiers, wp + step * (warped_mean - wp)) - p) / step;
      }
      d -= d.dot(n) * n;
      next.row(v) = body.project(p + step * d, 4);
    }
    vertices.swap(next);
  }
}

BodyTemplate build_template(int target_vertices, Rig rig) {
  BodyTemplate t;
  t.rig = rig;
  t.mean = plan_body(mean_shape_vector(), rig);
  mesh_template(t, target_vertices);
  finish_template(t);
  return t;
}

void mesh_template(BodyTemplate& t, int target_vertices) {
  const Rig rig = t.rig;
  // Surface nets give about area / cell^2 vertices: one correction of the cell
  // size lands close to the target.
  // The cell is set without the magnifiers, so that the target is the count of
  // a uniform mesh and the magnified places come on top of it.
  ImplicitBody uniform = t.mean;
  uniform.magnifiers.clear();
  double cell = 0.019;
  RawMesh raw = surface_nets(uniform, cell);
  cell *= std::sqrt(static_cast<double>(raw.vertices.rows()) / target_vertices);
  // Where a limb runs diagonally through the grid, surface nets can join two
  // sheets in one cell (an edge with four faces). Such samplings are rejected:
  // the grid is shifted by a fixed sequence of offsets until the mesh is a
  // closed manifold sphere (deterministic; usually within a few tries).
  // The first attempt caches the search's answer for each rig; a changed rig
  // still finds its own (just more slowly at load time).
  constexpr int kAttempts = 120;
  const int known_good_attempt = rig == Rig::Human ? 25 : 19;
  for (int tries = 0;; ++tries) {
    const int attempt = (known_good_attempt + tries) % kAttempts;
    const Eigen::Vector2d offset(std::fmod(0.37 * attempt, 1.0), std::fmod(0.61 * attempt, 1.0));
    raw = surface_nets(t.mean, cell, offset);
    const auto topo = geometry::check_topology(raw.faces, static_cast<int>(raw.vertices.rows()));
    if (topo.closed_manifold() && topo.euler_characteristic == 2) {
      if (std::getenv("DRAPE_BODY_DEBUG")) std::fprintf(stderr, "template: attempt %d, cell %g\n", attempt, cell);
      break;
    }
    if (std::getenv("DRAPE_BODY_DEBUG")) print_shared_edges(raw, attempt);
    if (tries + 1 == kAttempts) throw Error("body parametric: cannot mesh the mean body into a closed manifold: " + topo.str());
  }

  const int nv = static_cast<int>(raw.vertices.rows());
  auto nbrs = geometry::vertex_neighbours(raw.faces, nv);
  for (int v = 0; v < nv; ++v) raw.vertices.row(v) = t.mean.project(raw.vertices.row(v).transpose()).transpose();
  relax_on_surface(t.mean, nbrs, raw.vertices, 8, 0.5);

  const std::vector<int> order = locality_order(nbrs, raw.vertices);
  std::vector<int> new_index(static_cast<std::size_t>(nv));
  for (int i = 0; i < nv; ++i) new_index[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])] = i;
  t.vertices.resize(nv, 3);
  for (int i = 0; i < nv; ++i) t.vertices.row(i) = raw.vertices.row(order[static_cast<std::size_t>(i)]);
  t.faces = raw.faces;
  for (Eigen::Index f = 0; f < t.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) t.faces(f, c) = new_index[static_cast<std::size_t>(t.faces(f, c))];
}

void finish_template(BodyTemplate& t) {
  t.neighbours = geometry::vertex_neighbours(t.faces, static_cast<int>(t.vertices.rows()));
  bind_to_parts(t);
}

}  // namespace drape::parametric
