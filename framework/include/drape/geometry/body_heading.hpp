#pragma once
// Which way a body mesh a user brings faces, and whether it stands upright.
// A body in the body model's vertex order is compared with the model's mean
// body (least-squares rotation of one onto the other, the Kabsch method): a
// scan or a scene's character may face any way about the vertical, which
// changes nothing in how cloth hangs on it, yet the network reads absolute
// coordinates and the simulation morphs from the mean body facing +z. Such a
// body is turned to face the way the model's bodies face, draped there and
// the drape turned back (BodyMove). A body that leans is another matter:
// gravity then acts across it, which no model or scene here was made for.
#include <Eigen/Core>

#include <string>

namespace drape {

struct BodyHeading {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // the body about its centroid ~ rotation * the mean body
  double turn_degrees = 0;  // about the vertical (+y), counter-clockwise seen from above; in (-180, 180]
  double lean_degrees = 0;  // how far its up axis (rotation * +y) is from +y
};

// The rotation that best carries `mean` onto `body` (same vertex order), both
// about their centroids. A body of the model's own shape space, of any
// build, comes out within about 0.3 degrees of lean and 0.01 of turn
// (symmetric left to right; its belly and buttocks tip the fit a little).
BodyHeading body_heading(const Eigen::MatrixX3d& body, const Eigen::MatrixX3d& mean);

// Below these a body is taken as it is: within what the model's own bodies
// measure, and no rotation is applied (their drapes stay bit for bit).
inline constexpr double kTurnToleranceDegrees = 1.0;
inline constexpr double kLeanToleranceDegrees = 2.0;
// Above this a body is refused: a leaning body's drape is not its upright
// drape turned (gravity acts across it). Between the two it is straightened
// with a note: within a few degrees the drape barely differs.
inline constexpr double kLeanLimitDegrees = 10.0;

// A rigid move of a body to where (and the way) a model's bodies stand, and
// back: placed = (given - pivot) * rotation + pivot - offset, so that a drape
// made on the placed body, back(), lies on the given body.
struct BodyMove {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // given ~ rotation * placed, about pivot
  Eigen::RowVector3d pivot = Eigen::RowVector3d::Zero();
  Eigen::RowVector3d offset = Eigen::RowVector3d::Zero();

  bool turned() const { return !rotation.isIdentity(0.0); }
  bool is_identity() const { return !turned() && offset.isZero(0.0); }
  Eigen::MatrixX3d placed(const Eigen::MatrixX3d& given) const;
  Eigen::MatrixX3d back(const Eigen::MatrixX3d& placed) const;
  // This move, then `next` (on what this one placed): one move, placed() and
  // back() of both in turn.
  BodyMove then(const BodyMove& next) const;
};

// Turns `body` (in place) to face as `mean` does when it is turned or leans
// beyond the tolerances, returning the move (pivot: its centroid) and, in
// *note, one sentence saying so; nothing for a body within them. A ConfigError
// starting with `what` ("the body", "body FILE") for a lean beyond
// kLeanLimitDegrees, naming the lean and the turn that would stand it up.
// `posed`: the body's limbs are turned (limb_turns.hpp), so the fit tilts
// with them (both hips flexed 20 degrees "leaned" 10.8; a pelvis alone
// leans 4-8 degrees with the build): only a turn is undone, the lean left.
// "faces 150.0 degrees from the way the body model's bodies face (turned
// about the vertical, counter-clockwise seen from above)": how a note says
// which way a body faces (turn_to_face, unpose_given_body, drape body --unpose).
std::string facing_text(double turn_degrees);

BodyMove turn_to_face(Eigen::MatrixX3d& body, const Eigen::MatrixX3d& mean, const std::string& what,
                      std::string* note = nullptr, bool posed = false);

// The refusal of a body leaning `lean_degrees` (beyond kLeanLimitDegrees),
// its up axis `up` in its own coordinates: "<what> leans 90.0 degrees from
// upright (...): ... stand it upright (turn it 90.0 degrees about ...)".
std::string lean_refusal(const std::string& what, double lean_degrees, const Eigen::Vector3d& up);

}  // namespace drape
