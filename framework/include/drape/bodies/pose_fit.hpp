#pragma once
// A body mesh given posed (a mesh another tool posed, a body of the model's
// topology in a stance), told apart into the pose angles and the body at rest
// that make it: what `drape predict --body` does with a posed mesh for a model
// of posed drapes, and what `drape body --unpose` writes.
//
// The angles are read against the body model itself, not against its mean
// body: at rest, a thin body's thighs turn 10 degrees and its spine 7.5
// against the mean body's (limb_turns.hpp), so a mean-body reading would take
// a build for a pose. The fit is a Levenberg-Marquardt least squares over
// every vertex: the model's body of a shape, posed by the angles and moved by
// a translation, against the given mesh; the shape, the angles (within their
// ranges of motion), the turn of the body as a whole and the translation are
// its unknowns. The rest body is
// then the given mesh itself unposed at those angles (the skinning inverted
// vertex by vertex, a few fixed-point steps), so that posing it again gives
// the given mesh back, whatever of the mesh the body model cannot make.
#include <drape/bodies/body.hpp>
#include <drape/geometry/body_heading.hpp>

#include <Eigen/Core>

namespace drape {

struct PoseFit {
  Pose pose;                 // every angle of the model's pose space, degrees
  // The given mesh unposed, in the model's frame: model.posed_vertices(rest,
  // pose, 1) is moved.placed(given), to reposed_error.
  Eigen::MatrixX3d rest;
  Eigen::VectorXd shape;     // the body model's shape fitted beside the angles
  // The given mesh into the model's frame: the body as a whole turned (the
  // pose space has no root rotation) and moved; back() takes a drape made
  // on the posed body where the mesh stands.
  BodyMove moved;
  double fit_rms = 0;        // m: rms distance of the model's body so posed to the given mesh, vertex to vertex
  double fit_max = 0;        // m: the largest such distance
  double reposed_error = 0;  // m: the largest distance of `rest` posed again to the given mesh
  int iterations = 0;        // Levenberg-Marquardt steps taken, in all rounds
};

// The fit for `given` (the model's vertex count, facing and standing upright
// roughly as the model's bodies do: turn_to_face first; what it leaves, the fit
// takes up). ConfigError for a model
// without a skeleton or a mesh of another vertex count.
PoseFit fit_pose(const BodyModel& model, const Eigen::MatrixX3d& given);

}  // namespace drape
