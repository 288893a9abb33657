#pragma once
// The garment carried along by a moving body: the first guess of a morph
// step under a barrier contact.
//
// A barrier contact must never enter a state where the surfaces touch, so a
// body that grows into the cloth cannot simply be moved and the cloth pushed
// out afterwards (what the penalty contact does). Instead, each garment vertex
// near the body moves with its closest body point (the barycentric blend of
// that face's corner displacements), fully within `inner` of the skin and
// fading linearly to not at all at `outer`. Cloth lying on the skin then keeps
// its distance while the body moves under it, and the continuous collision
// check of the joint move (garment and body) rarely has to cut it short.
#include <drape/geometry/closest_point.hpp>

#include <Eigen/Core>

namespace drape::scene_detail {

// x moved with the body from `body` (its current vertices) to `body_next`.
Eigen::MatrixX3d carried_with_body(const Eigen::MatrixX3d& x, const geometry::BodySurface& body,
                                   const Eigen::MatrixX3d& body_next, double inner, double outer);

}  // namespace drape::scene_detail
