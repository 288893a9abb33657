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
  double neck_height = 1.52;  // y of the top seam at the neck points (2 cm above the base of the neck: clear of the trapezius)
  double arm_angle_deg = 47;  // upper arms below horizontal (their axis, from cross-sections)
  // A point on the left upper arm's axis; its cross-sections are about 5 cm in
  // radius. The sleeve tube is coaxial with it, so the arm lies inside the
  // sleeve from the start (a tube hung from the shoulder seam instead sat 6 cm
  // low, and the top of the arm came out through the sleeve's top).
  double arm_axis_x = 0.292, arm_axis_y = 1.324, arm_axis_z = -0.016;
  double margin = 0.015;      // clearance added around half_width/half_depth
  // Half the depth of the shoulders (6.3 cm at the arm root, measured) plus
  // the margin: how far the panels stand off the arm's centre above the armpits.
  double shoulder_half_depth = 0.078;
  // The neck's section above its base (measured at y = 1.50-1.54).
  double neck_half_width = 0.056, neck_half_depth = 0.057, neck_centre_z = -0.013;
  double neck_base_height = 1.46;
  // How a panel's point on the other panel's side of the neck's centre is
  // cleared of the neck (placement.cpp, clear_neck): false, flipped to its own
  // side (the regular size, kept as it was: the shipped model's template);
  // true, moved out sideways (every other size: fit_torso).
  bool neck_sideways = false;
  // The collar's clearance around the neck. A size cut larger keeps more
  // (fit_torso): its neckline's points lie farther apart around a thicker
  // neck, and the chords between them cut in deeper.
  double neck_margin = 0.015;
};

// The canonical torso of a size's fit body (drape/bodies/fit_body.hpp: the
// parametric body of the mean height and sex whose girth is `grade` times the
// mean body's, on which a scene dresses that size): `mean` moved by what
// differs between that body and the mean body, measured on both (chest width,
// depth and centre, neck section, the arm's axis and angle, the shoulders'
// depth; the neck points stay at their height). Between the measured grades
// linear; beyond them the nearest (the fit bodies stop there too: BMI 10 and
// 65). `mean` itself at grade 1.
TorsoFrame fit_torso(const TorsoFrame& mean, double grade);

// 3D position of pattern point `p` (front frame) on the front (side = +1) or back (-1) panel.
Eigen::Vector3d place(const PatternSpec& spec, const TorsoFrame& torso, const Eigen::Vector2d& p, double side);

}  // namespace drape::tshirt
