#pragma once
// Whether a draped garment rode up: a garment far smaller round than its
// body settles as a band round the chest, p = 0 and settled, and nothing in
// a drape's summary said so (an outside check's tee, 36 % smaller round than
// a BMI 55 body, 0.23 m tall where it was modelled 0.70 m). The frictionless
// datasets' crop tops of the regular shirt come down to 0.37 of its height,
// which is physics, so this is a note of what happened, never a refusal.
#include <Eigen/Core>

#include <string>

namespace drape {

// Below this share of its modelled height (along y, up) a draped garment has ridden up.
inline constexpr double kRodeUpShare = 0.5;

// "the garment rode up: ..." when `draped` spans less than kRodeUpShare of
// `modelled`'s height (the garment as the scene modelled it, dressed); ""
// otherwise, or for an empty garment.
std::string garment_rode_up(const Eigen::MatrixX3d& modelled, const Eigen::MatrixX3d& draped);

}  // namespace drape
