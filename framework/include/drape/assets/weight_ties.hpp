#pragma once
// What a network's weights are tied to in its assets, compared between two
// assets: a model trained on one and started again on the other (drape train
// --init) keeps weights that mean a garment vertex's body point (the
// correspondences), a cluster of the hierarchy (the decoder's per-edge
// weights) and an eigenvector (the spectral branch's coefficients). Shapes
// can all fit while the meanings differ: the human rig's first encoder-body
// assets took their eigenbasis from the garment dressed on the human rig,
// whose eigenvectors past the first few dozen are others or flipped, and the
// models started from the mannequin's weights kept a spike at the underarm
// seam (docs/bodies.md, "One encoder for both rigs").
#include <drape/assets/assets.hpp>

#include <string>
#include <vector>

namespace drape {

// An eigenvector is taken as the same when |cos| between the two is at least this.
inline constexpr double kSameEigenvector = 0.9;

// One sentence per tie that differs between `from` (the weights' assets) and
// `to`; empty when every tie is the same.
std::vector<std::string> weight_ties_differ(const Assets& from, const Assets& to);

}  // namespace drape
