#include "crease_search.hpp"

#include <Eigen/Geometry>

#include <array>
#include <cmath>

namespace drape::collision {
namespace {

// The 26 unit directions (i, j, k) / |(i, j, k)|, i, j, k in {-1, 0, 1}, not all 0.
const std::vector<Eigen::Vector3d>& directions() {
  static const std::vector<Eigen::Vector3d> all = [] {
    std::vector<Eigen::Vector3d> d;
    for (int i = -1; i <= 1; ++i)
      for (int j = -1; j <= 1; ++j)
        for (int k = -1; k <= 1; ++k)
          if (i || j || k) d.push_back(Eigen::Vector3d(i, j, k).normalized());
    return d;
  }();
  return all;
}

int nearest_direction(const Eigen::Vector3d& normal) {
  int best = 0;
  double best_dot = -INFINITY;
  for (std::size_t i = 0; i < directions().size(); ++i)
    if (const double d = normal.dot(directions()[i]); d > best_dot) best_dot = d, best = static_cast<int>(i);
  return best;
}

}  // namespace

CreaseSearch::CreaseSearch(const geometry::BodySurface& body) : revision_(body.revision()) {
  const Eigen::MatrixX3i& faces = body.faces();
  const Eigen::MatrixX3d& x = body.vertices();
  face_group_.resize(static_cast<std::size_t>(faces.rows()));
  std::vector<std::vector<int>> members(directions().size());
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = x.row(faces(f, 0)), b = x.row(faces(f, 1)), c = x.row(faces(f, 2));
    const int direction = nearest_direction((b - a).cross(c - a));  // a degenerate face joins group 0
    face_group_[static_cast<std::size_t>(f)] = direction;
    members[static_cast<std::size_t>(direction)].push_back(static_cast<int>(f));
  }
  group_index_.assign(directions().size(), -1);
  for (std::size_t d = 0; d < members.size(); ++d) {
    if (members[d].empty()) continue;
    Eigen::MatrixX3i sub(static_cast<Eigen::Index>(members[d].size()), 3);
    for (std::size_t i = 0; i < members[d].size(); ++i) sub.row(static_cast<Eigen::Index>(i)) = faces.row(members[d][i]);
    group_index_[d] = static_cast<int>(groups_.size());
    groups_.emplace_back(x, sub);
  }
}

void CreaseSearch::follow(const geometry::BodySurface& body) {
  if (body.revision() == revision_) return;
  for (geometry::BodySurface& g : groups_) g.update(body.vertices());
  revision_ = body.revision();
}

CreaseSearch::Hit CreaseSearch::locate_elsewhere(const Eigen::Vector3d& p, int group, double max_distance) const {
  Hit best;
  const int own = group_index_[static_cast<std::size_t>(group)];
  for (std::size_t i = 0; i < groups_.size(); ++i) {
    if (static_cast<int>(i) == own) continue;
    // Each later group only has to beat the nearest point found so far.
    const geometry::SurfacePoint s = groups_[i].locate(p, max_distance);
    if (s.face < 0) continue;
    max_distance = std::abs(s.signed_distance);
    best = {s, &groups_[i]};
  }
  return best;
}

}  // namespace drape::collision
