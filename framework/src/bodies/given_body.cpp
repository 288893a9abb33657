// GivenBodyFrame and place_given_body (bodies/given_body.hpp).
#include <drape/bodies/given_body.hpp>
#include <drape/training/model_domain.hpp>

#include <mutex>
#include <optional>

namespace drape {

struct GivenBodyFrame::State {
  std::once_flag once;
  BodyAnchor anchor;
  std::optional<LimbFit> limbs;
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

BodyMove place_given_body(Eigen::MatrixX3d& body, const Eigen::MatrixX3d& mean, const BodyAnchor* anchor,
                          const Eigen::Vector3d& reference, const Eigen::Vector3d& spread, bool posed,
                          const std::string& who, std::string* turned) {
  BodyMove move = turn_to_face(body, mean, who, turned, posed);
  if (const std::optional<Eigen::Vector3d> offset = move_to_placement(reference, spread, anchor, body))
    move.offset = offset->transpose();
  return move;
}

}  // namespace drape
