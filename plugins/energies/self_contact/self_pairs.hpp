#pragma once
// Finding the self contact's pairs (self_contact.hpp): the garment's
// primitives and the pairs excluded at bind, the broad phase over box
// overlaps, and the narrow phase's exact distances and distance types.
#include "self_contact.hpp"

#include <drape/energy.hpp>

#include <Eigen/Core>

#include <vector>

namespace drape::self_contact {

// The garment's edges, material-space weights and neighbours, and the pairs
// of fabric neighbours closer than `exclusion` (m) in its rest mesh:
// excluded, or with `thin_limit` > 0 kept with half their rest distance (at
// most thin_limit, the usual d_hat) as their own d_hat.
SelfTopology make_topology(const Garment& garment, double exclusion, double thin_limit);

// Every vertex-face and edge-edge pair (not skipped) whose boxes overlap, the
// mesh moving from x to x_end (null: standing), each box grown by `inflate`;
// distances not yet set, a thin rest neighbour's own d_hat set (found here,
// once per candidate list, not at every evaluation). In (kind, a, b) order.
std::vector<SelfPair> candidate_pairs(const SelfTopology& t, const Eigen::MatrixX3d& x, const Eigen::MatrixX3d* x_end,
                                      double inflate);

// The candidates closer than sqrt(below2) at x (a thin rest neighbour: than
// its own d_hat), with their squared distances and distance types, in
// candidate order.
std::vector<SelfPair> close_pairs(const SelfTopology& t, const Eigen::MatrixX3d& x, std::vector<SelfPair> candidates,
                                  double below2);

}  // namespace drape::self_contact
