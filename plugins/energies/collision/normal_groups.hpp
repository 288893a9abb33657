#pragma once
// Which body faces can be the far side of a crease (crease_penalty.hpp): the
// faces are sorted into groups by the direction of their normal (the nearest of
// the 26 directions from a cube's centre to its faces, edges and corners, so
// two faces whose normals differ by more than about 45 degrees are never in one
// group). The far side of a vertex whose nearest point lies on a face of group
// G is its nearest point on the faces of all other groups
// (BodySurface::locate_excluding). Where the groups meet on smooth skin that
// point is the same skin seen again beside the near one, and the crease weight
// (kFarWallRamp) leaves it out; across a fold, such as the armpit of a heavy
// body, it is the other side of the fold. A milder fold between two faces of
// one group is found across the near face's edges instead (face_neighbours).
//
// The collision energy labels the faces once, when it is bound (from the
// body's normals then: the mean shape at the start of a morph), so within a
// solve the energy is one continuous function of the garment.
#include <drape/geometry/closest_point.hpp>

#include <vector>

namespace drape::collision {

// Per face of the body, its group; a degenerate face joins group 0.
std::vector<int> normal_groups(const geometry::BodySurface& body);

}  // namespace drape::collision
