#pragma once
// Where a body model stands its bodies, read off vertices that do not move
// with the shape. A body model builds every body in one frame (the soles at
// y = 0, the midline at x = 0, and a few vertices whose depth z is the same
// for every build), while the centroid, the measure a placement had before,
// moves with the shape: the parametric body's lies 1.3-5.9 mm behind z = 0
// depending on the belly. A network reads absolute coordinates, so a body
// re-centred by another tool (centroid at z = 0) drapes differently: 3.5 mm
// moved the shipped model's garment by 8 mm on average. The anchor puts a
// body given as a mesh back exactly where its model made it.
#include <drape/bodies/body.hpp>

#include <Eigen/Core>
#include <array>
#include <optional>
#include <vector>

namespace drape {

struct BodyAnchor {
  // Per axis (x, y, z), the measure of where a body stands that differs least
  // between the model's bodies: the centroid (x, on a body symmetric left to
  // right), the lowest point (y: the soles), or the mean of a few vertices
  // (z, for the parametric body's human rig: four at the hips, within 0.06
  // mm over its whole space); `none` when even the best differs by more than
  // kAnchorTolerance (that axis is then placed another way).
  enum class Measure { none, centroid, lowest, vertices };
  std::array<Measure, 3> measure = {Measure::none, Measure::none, Measure::none};
  std::array<std::vector<int>, 3> vertices;  // for Measure::vertices
  Eigen::Vector3d reference = Eigen::Vector3d::Zero();  // their mean coordinate on the model's bodies
  Eigen::Vector3d spread = Eigen::Vector3d::Zero();     // m: how far it differs between the bodies compared
  // The range over the bodies compared of where a placement by the centroid
  // put them (model_domain.hpp's body_placement: mean x, lowest y, mean z).
  Eigen::Vector3d placed_lo = Eigen::Vector3d::Zero(), placed_hi = Eigen::Vector3d::Zero();

  bool anchors(int axis) const { return measure[static_cast<std::size_t>(axis)] != Measure::none; }
  // The measure on one axis of a body (NaN for an axis it does not anchor).
  double at(const Eigen::MatrixX3d& body, int axis) const;
  // How far `body` stands from where its model makes bodies, on the anchored
  // axes (0 on the others).
  Eigen::Vector3d offset(const Eigen::MatrixX3d& body) const;
  // Whether bodies recorded standing at `placement` +- `spread` on an axis
  // (body_placement's measure: a model's training bodies) stood where this
  // model makes them: false for bodies placed otherwise (grown about their
  // centroid, moved by the tool that made them), which are then matched by
  // that record instead.
  bool agrees(int axis, double placement, double spread) const;
};

// A measure anchors an axis when it differs by at most this between the
// bodies compared (the human rig's: 0 in x and y, 0.06 mm in z over 23 bodies
// of its whole space). The mannequin rig has no vertex that steady in z (its
// best differ by 0.2 mm between the three bodies, 1 mm over its space): its
// z is placed by the centroid within the training bodies' spread, as before.
inline constexpr double kAnchorTolerance = 1e-4;
inline constexpr int kAnchorVertices = 4;  // per axis
// m: a body off its anchor by no more than the anchor's spread and this is
// left where it is (a mesh writer's rounding is a micrometre).
inline constexpr double kAnchorSlack = 1e-4;

// Compares the model's mean body with two far from it (the lightest woman and
// the heaviest man it makes, 1.55 and 1.95 m): about 0.2 s, the two bodies'
// solves, so callers keep it (BodyPreparation makes it once per model).
BodyAnchor find_body_anchor(const BodyModel& model);

}  // namespace drape
