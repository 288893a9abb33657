#pragma once
// A body mesh given for a body model (a scan, a mesh another tool left):
// turned to face as the model's bodies face, placed where it makes them, and
// told when posed, and unposed when its model can pose. The one mechanism behind `drape predict`/`optimize`/
// `render` (services/model_body.hpp) and `drape simulate` (services/
// scene_body.hpp), in C++ and Python.
#include <drape/bodies/body_anchor.hpp>
#include <drape/bodies/limb_turns.hpp>
#include <drape/bodies/pose_fit.hpp>
#include <drape/geometry/body_heading.hpp>

#include <Eigen/Core>
#include <memory>
#include <string>

namespace drape {

// What depends only on the body model: its anchor (body_anchor.hpp, 0.1-0.2
// s: two bodies solved) and its limbs (limb_turns.hpp), found on first use,
// once (thread-safe; copies share them).
class GivenBodyFrame {
 public:
  explicit GivenBodyFrame(const BodyModel& model);
  const BodyAnchor& anchor() const;
  const LimbFit& limbs() const;
  const Eigen::MatrixX3d& mean() const;  // the model's mean body, what a given body is turned to face as

 private:
  struct State;
  const BodyModel* model_;
  std::shared_ptr<State> state_;
};

// Turns `body` (in place) to face as `mean` does (turn_to_face: the note of
// the turn into *turned, a lean past the limit refused naming `who`), then
// places it by `anchor` where its model makes bodies, on the axes the
// anchor holds and where `reference` +- `spread` agrees, else by that record
// (move_to_placement; NaN: no record). Returns the move a drape made there
// takes back (its offset: where the body stood, for the caller's note).
// `posed`: the body's limbs are turned (LimbFit::posed), its lean not read.
BodyMove place_given_body(Eigen::MatrixX3d& body, const Eigen::MatrixX3d& mean, const BodyAnchor* anchor,
                          const Eigen::Vector3d& reference, const Eigen::Vector3d& spread, bool posed,
                          const std::string& who, std::string* turned);

// A body mesh given posed (LimbFit::posed) for a poseable body model: turned
// and placed roughly by the whole mesh (place_given_body, no lean read), its
// pose, turn and place read off it (fit_pose), then the mesh unposed and
// placed as a body given at rest. `body` becomes that body at rest; posed by
// `fit.pose` it is the given mesh moved by `moved`.
struct GivenPosedBody {
  BodyMove moved;  // the given mesh -> the placed body's frame; back() takes a drape there onto the mesh
  PoseFit fit;     // its rest: the mesh unposed before the last placement
  // For the user, one sentence each, without a prefix:
  double turn_degrees = 0;  // the mesh's turn about the vertical in all (counter-clockwise seen from above)
  std::string turned;     // saying so for a drape ("" within kTurnToleranceDegrees)
  std::string pose_note;  // "the body mesh is posed: its pose read off it is left_elbow_flexion=40,... "
  bool at_rest = false;   // its pose read lies within kPosedAngleDegrees of the rest pose at every joint
  std::string warning;    // "" unless the mesh unposed misses itself posed again by over a millimetre
  // How far the mesh stood from upright as a whole (the fitted turn's tilt of
  // its up axis: lying, upside down), and, beyond kLeanLimitDegrees, the
  // refusal a drape gives (lean_refusal): predict and simulate throw it (a
  // drape made upright and turned back would hang across gravity); drape
  // body --unpose, which drapes nothing, says so and writes the body as it stood.
  double lean_degrees = 0;
  std::string leaning;
  // The mesh is a body the model cannot make: the fit holds a shape
  // parameter at the edge of its range and still lies over
  // kOutsideFitRms from the mesh (a body of 1.2 m against the human rig's
  // 1.4-2.1 m was read as leaning 15 degrees, its pose wrong at every
  // joint). Then the pose read off it is wrong too, and the lean: the
  // refusal, naming the parameter and its range; every caller throws it,
  // before the lean's (a mesh that size at rest is draped with a warning).
  std::string outside;
};
// m rms: the fit of a body the model makes lies within a millimetre of it;
// 1.3 and 1.2 m bodies (the human rig's heights start at 1.4) lie 24 and 47.
inline constexpr double kOutsideFitRms = 0.01;
GivenPosedBody unpose_given_body(Eigen::MatrixX3d& body, const BodyModel& model, const Eigen::MatrixX3d& mean,
                                 const BodyAnchor* anchor, const Eigen::Vector3d& reference,
                                 const Eigen::Vector3d& spread, const std::string& who);
// The same placed by the frame's anchor alone (no training placement on
// record): drape body --unpose, BodyModel.unpose, drape bench unpose.
GivenPosedBody unpose_given_body(Eigen::MatrixX3d& body, const BodyModel& model, const GivenBodyFrame& frame,
                                 const std::string& who);

// Whether a body mesh is posed, in words for a warning ("" at rest): the
// limbs turned past kPosedLimbDegrees against the mean body (LimbFit::posed:
// "against the mean body at rest, left_forearm 40 degrees, ... (a body at
// rest turns none by more than 15)"); or, where the largest turn lies
// between kMildLimbDegrees and that (a pose too mild for the turns to tell
// from a build: a thin body's thighs turn 10 degrees at rest, a spine bent 10
// degrees as much), its pose read off it (unpose_given_body on a copy, about
// a second) when it lies more than kPosedAngleDegrees from the rest pose at
// some joint ("its pose read off it is spine_flexion=10,..."). A body model
// without a skeleton, or read_mild false: by the turns alone (Python's
// predict with check=False: an outside check's heavy bodies, whose arms turn
// past kMildLimbDegrees at rest, cost 0.5-0.9 s a call in the fit).
inline constexpr double kMildLimbDegrees = 4.0;
inline constexpr double kPosedAngleDegrees = 3.0;
std::string posed_in_words(const Eigen::MatrixX3d& mesh, const BodyModel& model, const GivenBodyFrame& frame,
                           bool read_mild = true);

// A posed mesh's place is read to the fit's precision; nearer is not said.
inline constexpr double kPosedPlacementTolerance = 5e-4;  // m

}  // namespace drape
