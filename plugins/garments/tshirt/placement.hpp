#pragma once
// Where the pattern goes in 3D around a canonical torso: the body part of each
// panel wraps half an ellipse (front at +z, back at -z, side seams at +-x) and
// folds over the shoulders to the top seam; the sleeve part becomes a tube around
// the A-pose arm; the two maps blend across the armhole. Both panels give the
// same point on every seam, so sewing is exact. dress() (drape/garment_dressing.hpp)
// then fits this to an actual body.
#include "pattern.hpp"

#include <Eigen/Core>

namespace drape::tshirt {

// The canonical torso, in the body's frame (meters, Y up, facing +Z). Defaults
// are measurements of the mean `parametric` body.
struct TorsoFrame {
  double half_width = 0.155;  // x extent of the chest from the centre line (y = 1.24-1.28)
  double half_depth = 0.112;  // z extent of the chest from centre_z
  double centre_z = 0.008;
  double neck_height = 1.50;  // y of the top seam at the neck points (base of the neck)
  double arm_angle_deg = 53;  // arms below horizontal (principal axis of the upper arms)
  double margin = 0.015;      // clearance added around half_width/half_depth
};

// 3D position of pattern point `p` (front frame) on the front (side = +1) or back (-1) panel.
Eigen::Vector3d place(const PatternSpec& spec, const TorsoFrame& torso, const Eigen::Vector2d& p, double side);

}  // namespace drape::tshirt
