#pragma once
// Closest points on the body's faces that face another way: the far side of a
// crease (crease_penalty.hpp). The body's faces are sorted into groups by the
// direction of their normal (the nearest of the 26 directions from a cube's
// centre to its faces, edges and corners, so two faces whose normals differ by
// more than about 45 degrees are never in one group); the far side of a vertex
// whose nearest point lies on a face of group G is its nearest point on the
// faces of all other groups. Where the groups meet on smooth skin the far point
// is the same skin seen again beside the near one, and the crease weight
// (kCreaseFrom) leaves it out; across a fold, such as the armpit of a heavy
// body, it is the other side of the fold.
//
// The groups are fixed when the energy is bound (from the body's normals then:
// the mean shape at the start of a morph), so within a solve the energy is one
// continuous function of the garment; the groups' search trees are refitted
// whenever the body moves.
#include <drape/geometry/closest_point.hpp>

#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace drape::collision {

class CreaseSearch {
 public:
  explicit CreaseSearch(const geometry::BodySurface& body);

  // Refits to the body's current vertices if it moved since the last call.
  void follow(const geometry::BodySurface& body);
  // The group of a body face.
  int group_of(int face) const { return face_group_[static_cast<std::size_t>(face)]; }

  struct Hit {
    geometry::SurfacePoint point;             // face = -1: nothing within the distance asked
    const geometry::BodySurface* surface = nullptr;  // the group's surface, whose faces point.face indexes
  };
  // The closest point of p on the faces of groups other than `group`, within max_distance.
  Hit locate_elsewhere(const Eigen::Vector3d& p, int group, double max_distance) const;

 private:
  std::vector<int> face_group_;
  std::vector<int> group_index_;  // per direction, its index in groups_, or -1 when no face points that way
  std::vector<geometry::BodySurface> groups_;
  std::uint64_t revision_ = 0;
};

}  // namespace drape::collision
