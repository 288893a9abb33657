// GivenBodyFrame and place_given_body (bodies/given_body.hpp).
#include <drape/bodies/given_body.hpp>
#include <drape/training/model_domain.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <numbers>
#include <optional>

namespace drape {

struct GivenBodyFrame::State {
  std::once_flag once;
  BodyAnchor anchor;
  std::optional<LimbFit> limbs;
  std::once_flag mean_once;
  Eigen::MatrixX3d mean;
};

GivenBodyFrame::GivenBodyFrame(const BodyModel& model) : model_(&model), state_(std::make_shared<State>()) {}

const BodyAnchor& GivenBodyFrame::anchor() const {
  std::call_once(state_->once, [this] {
    state_->anchor = find_body_anchor(*model_);
    state_->limbs.emplace(*model_);
  });
  return state_->anchor;
}

const LimbFit& GivenBodyFrame::limbs() const {
  anchor();
  return *state_->limbs;
}

const Eigen::MatrixX3d& GivenBodyFrame::mean() const {
  std::call_once(state_->mean_once, [this] { state_->mean = model_->vertices(model_->mean_shape()); });
  return state_->mean;
}

BodyMove place_given_body(Eigen::MatrixX3d& body, const Eigen::MatrixX3d& mean, const BodyAnchor* anchor,
                          const Eigen::Vector3d& reference, const Eigen::Vector3d& spread, bool posed,
                          const std::string& who, std::string* turned) {
  BodyMove move = turn_to_face(body, mean, who, turned, posed);
  if (const std::optional<Eigen::Vector3d> offset = move_to_placement(reference, spread, anchor, body))
    move.offset = offset->transpose();
  return move;
}

namespace {

// A mesh unposed that poses back this far from itself is told.
constexpr double kUnposeTolerance = 1e-3;  // m

// The angles of `pose` at least half a degree from the rest pose `rest`,
// rounded to a degree: "left_elbow_flexion=40,..."; "" when there are none.
std::string posed_angles(const Pose& pose, const Pose& rest) {
  std::string out;
  for (const auto& [name, value] : pose.angles) {
    if (!(std::abs(value - rest.get(name, 0.0)) >= 0.5)) continue;
    char part[96];
    std::snprintf(part, sizeof part, "%s%s=%.0f", out.empty() ? "" : ",", name.c_str(), value);
    out += part;
  }
  return out;
}

}  // namespace

GivenPosedBody unpose_given_body(Eigen::MatrixX3d& body, const BodyModel& model, const Eigen::MatrixX3d& mean,
                                 const BodyAnchor* anchor, const Eigen::Vector3d& reference,
                                 const Eigen::Vector3d& spread, const std::string& who) {
  // Faced and placed roughly by the whole mesh, the fit taking up what is
  // left (a trunk twisted 10 degrees turns the whole mesh's fit by 8). The
  // notes of the three steps would contradict each other: one says where
  // the mesh stood in all.
  GivenPosedBody out;
  std::string said;
  const BodyMove as_posed = place_given_body(body, mean, anchor, reference, spread, true, who, &said);
  out.fit = fit_pose(model, body);
  body = out.fit.rest;
  const BodyMove at_rest = place_given_body(body, mean, anchor, reference, spread, false, who, &said);
  out.moved = as_posed.then(out.fit.moved).then(at_rest);

  if (out.fit.fit_rms > kOutsideFitRms) {
    const std::vector<std::string> names = model.shape_names();
    const std::vector<std::pair<double, double>> ranges = model.shape_ranges();
    std::string held;
    for (std::size_t i = 0; i < names.size() && i < ranges.size() && static_cast<Eigen::Index>(i) < out.fit.shape.size(); ++i) {
      const auto [lo, hi] = ranges[i];
      const double v = out.fit.shape[static_cast<Eigen::Index>(i)], slack = 1e-3 * std::max(1.0, hi - lo);
      if (!(std::isfinite(lo) && std::isfinite(hi)) || (v > lo + slack && v < hi - slack)) continue;
      char part[160];
      std::snprintf(part, sizeof part, "%s%s at %g (its range %g to %g)", held.empty() ? "" : ", ", names[i].c_str(), v, lo, hi);
      held += part;
    }
    if (!held.empty()) {
      char line[900];
      std::snprintf(line, sizeof line,
                    "%s is not a body the body model can make: the closest it makes, posed, holds %s and still lies "
                    "%.1f mm rms from the mesh, so the pose read off it would be wrong (a body of another height or "
                    "build than the model's range? If it stands at rest, a model of A-pose drapes drapes it with a warning: "
                    "--model models/tshirt-coarse-human.h5)",
                    who.c_str(), held.c_str(), 1e3 * out.fit.fit_rms);
      out.outside = line;
    }
  }
  // The model's up (y in the placed frame) in the mesh's own coordinates.
  const Eigen::Vector3d up = out.moved.rotation.col(1);
  out.lean_degrees = std::acos(std::clamp(up.y(), -1.0, 1.0)) * 180.0 / std::numbers::pi;
  if (out.lean_degrees > kLeanLimitDegrees) out.leaning = lean_refusal(who, out.lean_degrees, up);
  char line[600];
  const Eigen::Vector3d facing = out.moved.rotation.col(2);
  const double turn = out.turn_degrees = std::atan2(facing.x(), facing.z()) * 180.0 / std::numbers::pi;
  if (std::abs(turn) > kTurnToleranceDegrees)
    out.turned = facing_text(turn) + "; it is draped turned to face as they do and the drape turned back with it";
  const Pose rest = model.rest_pose(out.fit.shape);
  const std::string angles = posed_angles(out.fit.pose, rest);
  out.at_rest = true;
  for (const auto& [name, value] : out.fit.pose.angles)
    out.at_rest = out.at_rest && !(std::abs(value - rest.get(name, 0.0)) > kPosedAngleDegrees);
  if (angles.empty())
    std::snprintf(line, sizeof line,
                  "the body mesh is at rest: its pose read off it is within half a degree of the rest pose at every "
                  "joint (the body model so posed lies %.1f mm rms, %.1f mm at most, from the mesh)",
                  1e3 * out.fit.fit_rms, 1e3 * out.fit.fit_max);
  else
    std::snprintf(line, sizeof line,
                  "the body mesh is posed: its pose read off it is %s (the body model so posed lies %.1f mm rms, %.1f mm "
                  "at most, from the mesh); draped in that pose on the mesh unposed (docs/poses.md, \"A body given "
                  "posed\")",
                  angles.c_str(), 1e3 * out.fit.fit_rms, 1e3 * out.fit.fit_max);
  out.pose_note = line;
  if (out.fit.reposed_error > kUnposeTolerance) {
    std::snprintf(line, sizeof line,
                  "the mesh unposed does not pose back onto itself: %.1f mm off at worst (a mesh the skinning cannot "
                  "make, such as limbs passing through each other); the drape is for a body that far from it",
                  1e3 * out.fit.reposed_error);
    out.warning = line;
  }
  return out;
}

GivenPosedBody unpose_given_body(Eigen::MatrixX3d& body, const BodyModel& model, const GivenBodyFrame& frame,
                                 const std::string& who) {
  const Eigen::Vector3d none = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  return unpose_given_body(body, model, frame.mean(), &frame.anchor(), none, none, who);
}

std::string posed_in_words(const Eigen::MatrixX3d& mesh, const BodyModel& model, const GivenBodyFrame& frame,
                           bool read_mild) {
  double most = 0;
  std::string turned;
  for (const LimbTurn& t : frame.limbs().turns(frame.mean(), mesh)) {
    most = std::max(most, t.degrees);
    if (!(t.degrees > kPosedLimbDegrees)) continue;
    char part[96];
    std::snprintf(part, sizeof part, "%s%s %.0f degrees", turned.empty() ? "" : ", ", t.bone.c_str(), t.degrees);
    turned += part;
  }
  if (!turned.empty())
    return "against the mean body at rest, " + turned + " (a body at rest turns none by more than " +
           std::to_string(static_cast<int>(kPosedLimbDegrees)) + ")";
  if (!(most > kMildLimbDegrees) || !model.poseable() || !read_mild) return "";
  Eigen::MatrixX3d copy = mesh;
  const GivenPosedBody read = unpose_given_body(copy, model, frame, "the body");
  if (read.at_rest) return "";
  const Pose rest = model.rest_pose(read.fit.shape);
  char more[40];
  std::snprintf(more, sizeof more, "%.0f", kPosedAngleDegrees);
  return "its pose read off it is " + posed_angles(read.fit.pose, rest) + " (more than " + more +
         " degrees from the rest pose)";
}

}  // namespace drape
