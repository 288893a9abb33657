#include <drape/geometry/garment_clearance.hpp>

#include <drape/errors.hpp>

#include <string>

namespace drape::geometry {

GarmentClearance::GarmentClearance(const Eigen::MatrixX3i& faces, int num_vertices, const GarmentClearanceOptions& options)
    : options_(options), faces_(faces), edges_(edge_list(faces)), adjacency_(vertex_adjacency(edges_, num_vertices)) {
  if (!(options.margin >= 0) || !(options.self_gap >= 0) || options.untangle_rounds < 1)
    throw Error("garment clearance: the margin and the gap must be >= 0 and the untangle rounds >= 1");
  if (options.untangle) untangler_.emplace(faces_, num_vertices);
}

PushOutOptions GarmentClearance::push_out_options(std::vector<int>* closest_faces,
                                                  const std::vector<std::array<int, 2>>* edges) const {
  PushOutOptions options;
  options.margin = options_.margin;
  options.closest_faces = closest_faces;
  if (options_.lift_edges) options.edges = edges;
  return options;
}

PushOutReport GarmentClearance::push_out(const BodySurface& body, Eigen::MatrixX3d& vertices) {
  PushOutOptions options = push_out_options(&closest_faces_, &edges_);
  if (options_.lift_edges) options.faces = &faces_;
  return geometry::push_out(body, vertices, options);
}

void GarmentClearance::push_out_moved(const BodySurface& body, Eigen::MatrixX3d& vertices, std::vector<char>& moved) {
  const auto n = static_cast<int>(vertices.rows());
  if (moved.size() != static_cast<std::size_t>(n) || closest_faces_.size() != static_cast<std::size_t>(n))
    throw Error("garment clearance: " + std::to_string(moved.size()) + " moved flags and " +
                std::to_string(closest_faces_.size()) + " closest faces for " + std::to_string(n) +
                " vertices (push_out first, on the same garment)");
  std::vector<int> local(static_cast<std::size_t>(n), -1), chosen;
  const auto take = [&](int v) {
    if (local[static_cast<std::size_t>(v)] < 0) local[static_cast<std::size_t>(v)] = static_cast<int>(chosen.size()), chosen.push_back(v);
  };
  for (int v = 0; v < n; ++v)
    if (moved[static_cast<std::size_t>(v)]) {
      take(v);
      for (int k = adjacency_.start[static_cast<std::size_t>(v)]; k < adjacency_.start[static_cast<std::size_t>(v) + 1]; ++k)
        take(adjacency_.neighbours[static_cast<std::size_t>(k)]);
    }
  Eigen::MatrixX3d part(static_cast<Eigen::Index>(chosen.size()), 3);
  std::vector<int> hints(chosen.size());
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    part.row(static_cast<Eigen::Index>(i)) = vertices.row(chosen[i]);
    hints[i] = closest_faces_[static_cast<std::size_t>(chosen[i])];  // (the whole push-out just set every vertex's)
  }
  std::vector<std::array<int, 2>> part_edges;
  if (options_.lift_edges)
    for (const auto& [a, b] : edges_)
      if (local[static_cast<std::size_t>(a)] >= 0 && local[static_cast<std::size_t>(b)] >= 0)
        part_edges.push_back({local[static_cast<std::size_t>(a)], local[static_cast<std::size_t>(b)]});
  geometry::push_out(body, part, push_out_options(&hints, &part_edges));
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    if (part.row(row) == vertices.row(chosen[i])) continue;
    vertices.row(chosen[i]) = part.row(row);
    moved[static_cast<std::size_t>(chosen[i])] = 1;
  }
}

UntangleReport GarmentClearance::untangle(const BodySurface& body, Eigen::MatrixX3d& vertices, const Eigen::MatrixX3d* rest) {
  if (!untangler_) return {};
  UntangleOptions untangling;
  untangling.gap = options_.self_gap;
  untangling.max_rounds = options_.untangle_rounds;
  untangling.rest = rest;
  // After each round, the patches it moved kept off the body.
  untangling.after_round = [&](Eigen::MatrixX3d& now, std::vector<char>& moved) { push_out_moved(body, now, moved); };
  return untangler_->run(vertices, untangling);
}

GarmentClearance::Report GarmentClearance::run(const BodySurface& body, Eigen::MatrixX3d& vertices, const Eigen::MatrixX3d* rest) {
  Report report;
  report.pushed = push_out(body, vertices);
  report.untangled = untangle(body, vertices, rest);
  return report;
}

}  // namespace drape::geometry
