// fit_pose (bodies/pose_fit.hpp).
#include <drape/bodies/pose_fit.hpp>
#include <drape/bodies/skinning.hpp>
#include <drape/errors.hpp>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <future>
#include <thread>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace drape {
namespace {

constexpr double kAngleStep = 1e-3;   // degrees: the finite difference of a column of the angles
constexpr double kShapeStep = 1e-3;   // of a shape parameter's range (or absolute when unbounded)
constexpr double kLinearShapeTolerance = 1e-3;  // m: the linear shape model trusted this far from the true body
constexpr int kMaxSteps = 60;
constexpr int kMaxRounds = 4;

using Weighted = std::vector<std::pair<int, double>>;

// The finite-difference step of an angle at `degrees`: kAngleStep, taken
// backwards at the top of its range (a pose past it is refused).
double angle_step(double degrees, const PoseAngle& range) { return degrees + kAngleStep > range.max ? -kAngleStep : kAngleStep; }

// The unknowns: the pose angles (degrees), the body's turn as a whole (a
// rotation vector, radians: the pose space has no root rotation, and a body
// turned to face by its whole mesh is still turned a little when its trunk
// twists), the translation (m), the shape.
struct Unknowns {
  Eigen::VectorXd angles;
  Eigen::Vector3d turn = Eigen::Vector3d::Zero();
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  Eigen::VectorXd shape;
};
constexpr int kRigid = 6;  // the turn's and the translation's columns

class Fit {
 public:
  Fit(const BodyModel& model, const Eigen::MatrixX3d& given)
      : model_(model), given_(given), space_(model.pose_angles()), ranges_(model.shape_ranges()) {
    weights_ = model.skinning_weights();
    const Eigen::MatrixXd& weights = weights_;
    bones_.resize(static_cast<std::size_t>(weights.cols()));
    for (Eigen::Index v = 0; v < weights.rows(); ++v)
      for (Eigen::Index b = 0; b < weights.cols(); ++b)
        if (weights(v, b) != 0) bones_[static_cast<std::size_t>(b)].emplace_back(static_cast<int>(v), weights(v, b));
  }

  // The shape's body, from the linear model about the last linearisation.
  Eigen::MatrixX3d rest(const Eigen::VectorXd& shape) const {
    Eigen::MatrixX3d v = base_;
    for (Eigen::Index k = 0; k < shape.size(); ++k)
      if (shape[k] != base_shape_[k]) v += (shape[k] - base_shape_[k]) * shape_columns_[static_cast<std::size_t>(k)];
    return v;
  }

  Pose pose_of(const Eigen::VectorXd& angles) const {
    Pose p;
    for (std::size_t a = 0; a < space_.size(); ++a) p.angles[space_[a].name] = angles[static_cast<Eigen::Index>(a)];
    return p;
  }

  // The model's posed body turned about `centre` and moved: where x puts it.
  Eigen::MatrixX3d placed(const Eigen::MatrixX3d& model_posed, const Unknowns& x) const {
    const Eigen::Matrix3d r = skinning::rodrigues(x.turn);
    return (((model_posed.rowwise() - centre_) * r.transpose()).rowwise() + centre_).rowwise() + x.offset.transpose();
  }
  Eigen::MatrixX3d residual(const Unknowns& x, bool with_shape) const {
    const Eigen::MatrixX3d body = with_shape ? rest(x.shape) : base_;
    return placed(model_.posed_vertices(body, pose_of(x.angles), 1.0), x) - given_;
  }
  // The given mesh in the model's frame: the turn and the translation undone.
  Eigen::MatrixX3d in_model_frame(const Unknowns& x) const {
    const Eigen::Matrix3d r = skinning::rodrigues(x.turn);
    return (((given_.rowwise() - centre_).rowwise() - x.offset.transpose()) * r).rowwise() + centre_;
  }
  void set_centre(const Eigen::RowVector3d& centre) { centre_ = centre; }
  const Eigen::RowVector3d& centre() const { return centre_; }

  // The model's body at `shape` and its derivative along each shape parameter
  // (finite differences inward from the range's bounds): the linear shape model.
  void linearise(const Eigen::VectorXd& shape) {
    rebase(shape);
    shape_columns_.assign(static_cast<std::size_t>(shape.size()), Eigen::MatrixX3d());
    auto column = [&](Eigen::Index k) {
      const auto [lo, hi] = ranges_[static_cast<std::size_t>(k)];
      double h = kShapeStep * (std::isfinite(hi - lo) ? hi - lo : 1.0);
      if (shape[k] + h > hi) h = -h;
      Eigen::VectorXd moved = shape;
      moved[k] += h;
      shape_columns_[static_cast<std::size_t>(k)] = (model_.vertices(moved) - base_) / h;
    };
    if (shape.size() == 0) return;  // a model without shape parameters
    // A parametric body costs tens of milliseconds: the columns on every core.
    const Eigen::Index threads = std::clamp<Eigen::Index>(std::thread::hardware_concurrency(), 1, shape.size());
    std::vector<std::future<void>> work;
    for (Eigen::Index t = 1; t < threads; ++t)
      work.push_back(std::async(std::launch::async, [&, t] {
        for (Eigen::Index k = t; k < shape.size(); k += threads) column(k);
      }));
    for (Eigen::Index k = 0; k < shape.size(); k += threads) column(k);
    for (auto& w : work) w.get();
  }
  // The true body at `shape`, the derivatives kept: what a round ends on,
  // before deciding whether another round needs them renewed.
  void rebase(const Eigen::VectorXd& shape) {
    base_shape_ = shape;
    base_ = model_.vertices(shape);
  }
  const Eigen::MatrixX3d& base() const { return base_; }

  // d residual / d unknowns, one column per angle, then the translation, then
  // (with_shape) the shape: the angles' by finite differences of the joints'
  // transforms, blended over the vertices of the bones a step moves; the
  // shape's through each vertex's blended rotation.
  Eigen::MatrixXd jacobian(const Unknowns& x, bool with_shape) const {
    const Eigen::MatrixX3d body = with_shape ? rest(x.shape) : base_;
    const Eigen::Index n = body.rows(), na = x.angles.size(), ns = with_shape ? x.shape.size() : 0;
    Eigen::MatrixXd jac = Eigen::MatrixXd::Zero(3 * n, na + kRigid + ns);
    const Pose pose = pose_of(x.angles);
    const Eigen::Matrix3d r = skinning::rodrigues(x.turn);
    const std::vector<skinning::Rigid> at = model_.joint_transforms(body, pose);
    for (Eigen::Index a = 0; a < na; ++a) {
      const PoseAngle& range = space_[static_cast<std::size_t>(a)];
      const double h = angle_step(x.angles[a], range);
      Pose stepped = pose;
      stepped.angles[range.name] += h;
      const std::vector<skinning::Rigid> moved = model_.joint_transforms(body, stepped);
      for (std::size_t b = 0; b < at.size(); ++b) {
        const Eigen::Matrix3d dr = (moved[b].r - at[b].r) / h;
        const Eigen::Vector3d dt = (moved[b].t - at[b].t) / h;
        if (dr.isZero(0.0) && dt.isZero(0.0)) continue;
        const Eigen::Matrix3d rdr = r * dr;
        const Eigen::Vector3d rdt = r * dt;
        for (const auto& [v, w] : bones_[b]) {
          const Eigen::Vector3d d = w * (rdr * body.row(v).transpose() + rdt);
          for (int c = 0; c < 3; ++c) jac(3 * v + c, a) += d[c];
        }
      }
    }
    const Eigen::MatrixX3d model_posed = skinning::blend(body, weights_, at).rowwise() - centre_;
    for (int k = 0; k < 3; ++k) {
      constexpr double h = 1e-6;  // radians
      const Eigen::Matrix3d dr = (skinning::rodrigues(x.turn + h * Eigen::Vector3d::Unit(k)) - r) / h;
      for (Eigen::Index v = 0; v < n; ++v) {
        const Eigen::Vector3d d = dr * model_posed.row(v).transpose();
        for (int c = 0; c < 3; ++c) jac(3 * v + c, na + k) = d[c];
      }
    }
    for (Eigen::Index v = 0; v < n; ++v)
      for (int c = 0; c < 3; ++c) jac(3 * v + c, na + 3 + c) = 1.0;
    if (ns == 0) return jac;
    const std::vector<Eigen::Matrix3d> turn = blended_rotations(at, n);
    for (Eigen::Index k = 0; k < ns; ++k) {
      const Eigen::MatrixX3d& column = shape_columns_[static_cast<std::size_t>(k)];
      for (Eigen::Index v = 0; v < n; ++v) {
        const Eigen::Vector3d d = r * turn[static_cast<std::size_t>(v)] * column.row(v).transpose();
        for (int c = 0; c < 3; ++c) jac(3 * v + c, na + kRigid + k) = d[c];
      }
    }
    return jac;
  }

  // sum_b w(v, b) R_b per vertex: what the skinning does to a small change of the rest body there.
  std::vector<Eigen::Matrix3d> blended_rotations(const std::vector<skinning::Rigid>& at, Eigen::Index n) const {
    std::vector<Eigen::Matrix3d> turn(static_cast<std::size_t>(n), Eigen::Matrix3d::Zero());
    for (std::size_t b = 0; b < at.size(); ++b)
      for (const auto& [v, w] : bones_[b]) turn[static_cast<std::size_t>(v)] += w * at[b].r;
    return turn;
  }

  // Levenberg-Marquardt with Marquardt's scaling, each step kept within the
  // angles' ranges of motion and the shape's ranges. Returns the cost.
  double minimise(Unknowns& x, bool with_shape, int& steps, double enough) const {
    auto flat = [](const Eigen::MatrixX3d& r) {
      return Eigen::Map<const Eigen::VectorXd>(Eigen::MatrixXd(r.transpose()).data(), 3 * r.rows()).eval();
    };
    Eigen::VectorXd r = flat(residual(x, with_shape));
    double cost = r.squaredNorm(), lambda = 1e-3;
    for (int it = 0; it < kMaxSteps; ++it) {
      const Eigen::MatrixXd jac = jacobian(x, with_shape);
      Eigen::MatrixXd jtj = Eigen::MatrixXd::Zero(jac.cols(), jac.cols());
      jtj.selfadjointView<Eigen::Lower>().rankUpdate(jac.transpose());
      jtj = jtj.selfadjointView<Eigen::Lower>();
      const Eigen::VectorXd jtr = jac.transpose() * r;
      bool improved = false;
      for (int tries = 0; tries < 12 && !improved; ++tries) {
        Eigen::MatrixXd a = jtj;
        a.diagonal() += lambda * jtj.diagonal().cwiseMax(1e-12);
        const Eigen::VectorXd step = a.ldlt().solve(-jtr);
        Unknowns next = take(x, step, with_shape);
        const Eigen::VectorXd rn = flat(residual(next, with_shape));
        const double c = rn.squaredNorm();
        if (c < cost) {
          const double gain = cost - c;
          x = std::move(next), r = rn, lambda = std::max(lambda / 3.0, 1e-9), improved = true;
          cost = c;
          ++steps;
          if (gain < enough * cost || cost < floor_cost()) return cost;
        } else {
          lambda *= 4.0;
        }
      }
      if (!improved) break;
    }
    return cost;
  }

  Unknowns take(const Unknowns& x, const Eigen::VectorXd& step, bool with_shape) const {
    Unknowns next = x;
    const Eigen::Index na = x.angles.size();
    for (Eigen::Index a = 0; a < na; ++a) {
      const PoseAngle& range = space_[static_cast<std::size_t>(a)];
      next.angles[a] = std::clamp(x.angles[a] + step[a], range.min, range.max);
    }
    next.turn += step.segment<3>(na);
    next.offset += step.segment<3>(na + 3);
    if (with_shape)
      for (Eigen::Index k = 0; k < x.shape.size(); ++k) {
        const auto [lo, hi] = ranges_[static_cast<std::size_t>(k)];
        next.shape[k] = std::clamp(x.shape[k] + step[na + kRigid + k], lo, hi);
      }
    return next;
  }

  // The given mesh unposed at `pose`: each vertex moved by the inverse of its
  // blended transform until posing it again gives the mesh back. The step
  // leaves out how a vertex moves the joints regressed from it, so near a
  // joint it can creep away again: the best iterate is kept.
  Eigen::MatrixX3d unpose(Eigen::MatrixX3d rest, const Eigen::MatrixX3d& target, const Pose& pose, double& error) const {
    Eigen::MatrixX3d best = rest;
    error = std::numeric_limits<double>::infinity();
    for (int it = 0; it < 12; ++it) {
      const Eigen::MatrixX3d miss = target - model_.posed_vertices(rest, pose, 1.0);
      const double e = miss.rowwise().norm().maxCoeff();
      if (!(e < error)) break;
      error = e, best = rest;
      if (e < 1e-9) break;
      const std::vector<Eigen::Matrix3d> turn = blended_rotations(model_.joint_transforms(rest, pose), rest.rows());
      for (Eigen::Index v = 0; v < rest.rows(); ++v)
        rest.row(v) += (turn[static_cast<std::size_t>(v)].inverse() * miss.row(v).transpose()).transpose();
    }
    return best;
  }

  const std::vector<PoseAngle>& space() const { return space_; }
  // The mean body's rest angles, where the fit starts.
  void set_rest_angles(const Eigen::VectorXd& angles) { rest_angles_ = angles; }
  const Eigen::VectorXd& rest_angles() const { return rest_angles_; }
  // 1e-6 m rms: past any use of the fit.
  double floor_cost() const { return 1e-12 * static_cast<double>(given_.rows()); }

 private:
  const BodyModel& model_;
  const Eigen::MatrixX3d& given_;
  std::vector<PoseAngle> space_;
  std::vector<std::pair<double, double>> ranges_;
  Eigen::MatrixXd weights_;
  std::vector<Weighted> bones_;  // per bone: the vertices it moves, with their weights
  Eigen::RowVector3d centre_ = Eigen::RowVector3d::Zero();  // the turn's pivot: the mean body's centroid
  Eigen::VectorXd base_shape_;
  Eigen::MatrixX3d base_;
  std::vector<Eigen::MatrixX3d> shape_columns_;
  Eigen::VectorXd rest_angles_;
};

// A fit that misses the mesh by more than this somewhere is tried again,
// joint by joint, from other starts.
constexpr double kRetryMiss = 2e-3;  // m

// The indices in `space` of a joint's angles that poses are drawn over
// (a sampling range): what the retries below start again and compare.
std::vector<Eigen::Index> drawn_angles(const std::vector<PoseAngle>& space, const BodyModel::Joint& joint) {
  std::vector<Eigen::Index> own;
  for (const std::string& name : joint.angles)
    for (std::size_t a = 0; a < space.size(); ++a)
      if (space[a].name == name && space[a].sample_hi > space[a].sample_lo) own.push_back(static_cast<Eigen::Index>(a));
  return own;
}

// How far a joint's angles lie outside the ranges poses are drawn from
// (squared degrees): of two sets that fit the mesh as well, the one nearer
// what people and the training poses do is kept.
double outside_sampling(const std::vector<PoseAngle>& space, const Eigen::VectorXd& angles,
                        const std::vector<Eigen::Index>& own) {
  double outside = 0;
  for (const Eigen::Index a : own) {
    const PoseAngle& p = space[static_cast<std::size_t>(a)];
    const double d = std::max({0.0, p.sample_lo - angles[a], angles[a] - p.sample_hi});
    outside += d * d;
  }
  return outside;
}

// A joint of several angles (a shoulder: abduction, flexion, rotation) can
// lead the fit, started at rest, into a minimum that misses the mesh, or to
// another set of angles that makes the same limb: an arm near the
// horizontal is turned alike by its flexion and its rotation. Held-out
// bodies: an arm read with its rotation at the end of its range, 2.3 mm rms
// and 11 mm at most from the mesh; another (87.6, 52.2, 11.6 degrees) read
// as 92.4, -11.7, -52.5, the same mesh to 0.02 mm but other angles for the
// network. Each such joint (the fit missing the mesh, or the joint's angles
// outside the sampling ranges) is fitted again with its angles started at
// the middle of their sampling ranges; the set kept is the one that fits
// better, or, fitting as well, lies nearer the sampling ranges.
double retry_joints(const Fit& fit, const BodyModel& model, Unknowns& x, double cost, bool missed, int& steps) {
  const std::vector<PoseAngle>& space = fit.space();
  for (const BodyModel::Joint& joint : model.joints()) {
    const std::vector<Eigen::Index> own = drawn_angles(space, joint);
    if (own.size() < 2) continue;
    const double outside = outside_sampling(space, x.angles, own);
    if (!missed && !(outside > 1.0)) continue;
    Unknowns again = x;
    for (const Eigen::Index a : own)
      again.angles[a] = 0.5 * (space[static_cast<std::size_t>(a)].sample_lo + space[static_cast<std::size_t>(a)].sample_hi);
    const double other = fit.minimise(again, false, steps, 1e-8);
    const double tie = 1e-2 * cost + fit.floor_cost();
    if (other < cost - tie || (other < cost + tie && outside_sampling(space, again.angles, own) < outside))
      x = std::move(again), cost = other;
  }
  return cost;
}

// The same turn of a joint's bone by another set of its angles. Three angles
// about three axes make most turns two ways (as Euler angles do), both within
// the ranges of motion when an arm is near the horizontal: a held-out body's
// right arm at 87.6, 52.2, 11.6 degrees is posed to 0.05 mm by 92.4, -11.7,
// -52.5 as well, and a fit of the mesh can end on either. Where the set found
// lies outside the ranges poses are drawn from, the joint's angles are
// searched for others that turn its bone the same (on the bone's transform
// alone, from a grid of starts over the ranges of motion: no mesh is posed),
// and the set nearest the sampling ranges, then rest, is kept.
void choose_equivalent_angles(const Fit& fit, const BodyModel& model, Unknowns& x) {
  const std::vector<PoseAngle>& space = fit.space();
  const Eigen::MatrixX3d& body = fit.base();
  const std::vector<BodyModel::Joint> joints = model.joints();
  for (std::size_t j = 0; j < joints.size(); ++j) {
    const std::vector<Eigen::Index> own = drawn_angles(space, joints[j]);
    if (own.size() < 2 || !(outside_sampling(space, x.angles, own) > 1.0)) continue;
    const Eigen::Matrix3d target = model.joint_transforms(body, fit.pose_of(x.angles))[j].r;
    auto turn_of = [&](const Eigen::VectorXd& angles) { return model.joint_transforms(body, fit.pose_of(angles))[j].r; };
    auto miss = [&](const Eigen::VectorXd& angles) { return (turn_of(angles) - target).squaredNorm(); };
    Eigen::VectorXd best = x.angles;
    double best_outside = outside_sampling(space, best, own), best_rest = (best - fit.rest_angles()).squaredNorm();
    const int n = static_cast<int>(own.size());
    int starts = 1;
    for (int k = 0; k < n; ++k) starts *= 3;
    for (int start = 0; start < starts; ++start) {
      Eigen::VectorXd angles = x.angles;
      for (int k = 0, code = start; k < n; ++k, code /= 3) {
        const PoseAngle& p = space[static_cast<std::size_t>(own[static_cast<std::size_t>(k)])];
        angles[own[static_cast<std::size_t>(k)]] = p.min + (p.max - p.min) * (1.0 + 2.0 * (code % 3)) / 6.0;
      }
      // Gauss-Newton on the bone's rotation, the joint's angles alone.
      for (int it = 0; it < 30; ++it) {
        const Eigen::Matrix3d now = turn_of(angles);
        const Eigen::Matrix3d off = now - target;
        const Eigen::Map<const Eigen::Matrix<double, 9, 1>> r(off.data());
        if (r.squaredNorm() < 1e-24) break;
        Eigen::MatrixXd jac(9, n);
        for (int k = 0; k < n; ++k) {
          const Eigen::Index a = own[static_cast<std::size_t>(k)];
          const double h = angle_step(angles[a], space[static_cast<std::size_t>(a)]);
          Eigen::VectorXd stepped = angles;
          stepped[a] += h;
          const Eigen::Matrix3d d = (turn_of(stepped) - now) / h;
          jac.col(k) = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(d.data());
        }
        const Eigen::VectorXd step = (jac.transpose() * jac + 1e-12 * Eigen::MatrixXd::Identity(n, n)).ldlt().solve(-jac.transpose() * r);
        for (int k = 0; k < n; ++k) {
          const Eigen::Index a = own[static_cast<std::size_t>(k)];
          angles[a] = std::clamp(angles[a] + step[k], space[static_cast<std::size_t>(a)].min, space[static_cast<std::size_t>(a)].max);
        }
      }
      if (!(miss(angles) < 1e-14)) continue;  // another turn (or a start that found none)
      const double outside = outside_sampling(space, angles, own), rest = (angles - fit.rest_angles()).squaredNorm();
      if (outside < best_outside - 1e-9 || (outside < best_outside + 1e-9 && rest < best_rest - 1e-9))
        best = angles, best_outside = outside, best_rest = rest;
    }
    x.angles = best;
  }
}

}  // namespace

PoseFit fit_pose(const BodyModel& model, const Eigen::MatrixX3d& given) {
  if (!model.poseable()) throw ConfigError("fit_pose: the body model has no skeleton, so a pose cannot be read off a mesh");
  if (given.rows() != model.num_vertices())
    throw ConfigError("fit_pose: the mesh has " + std::to_string(given.rows()) + " vertices, the body model " +
                      std::to_string(model.num_vertices()));
  if (!given.allFinite()) throw ConfigError("fit_pose: the mesh has a coordinate that is not a finite number");
  Fit fit(model, given);
  Unknowns x;
  x.shape = model.mean_shape();
  fit.linearise(x.shape);
  const Pose rest = model.rest_pose(x.shape);
  x.angles.resize(static_cast<Eigen::Index>(fit.space().size()));
  for (std::size_t a = 0; a < fit.space().size(); ++a) x.angles[static_cast<Eigen::Index>(a)] = rest.get(fit.space()[a].name, 0.0);
  fit.set_rest_angles(x.angles);
  fit.set_centre(fit.base().colwise().mean());
  x.offset = (given.colwise().mean() - fit.centre()).transpose();

  PoseFit out;
  // First the angles on the mean body (cheap: no shape columns), then the
  // shape with them, the linear shape model renewed where it drifted.
  fit.minimise(x, false, out.iterations, 1e-3);
  for (int round = 0; round < kMaxRounds; ++round) {
    fit.minimise(x, true, out.iterations, 1e-6);

    const Eigen::MatrixX3d linear = fit.rest(x.shape);
    fit.rebase(x.shape);  // the true body first: its derivatives only when another round needs them
    if ((fit.base() - linear).rowwise().norm().maxCoeff() < kLinearShapeTolerance) break;
    fit.linearise(x.shape);
  }
  double cost = fit.minimise(x, false, out.iterations, 1e-8);  // the angles once more on the shape's true body
  const bool missed = std::sqrt(fit.residual(x, false).rowwise().squaredNorm().maxCoeff()) > kRetryMiss;
  if (retry_joints(fit, model, x, cost, missed, out.iterations) < cost) {
    // The shape, fitted beside the angles that missed, once more beside those that do not.
    fit.minimise(x, true, out.iterations, 1e-6);
    fit.rebase(x.shape);
    fit.minimise(x, false, out.iterations, 1e-8);
  }
  choose_equivalent_angles(fit, model, x);

  out.pose = fit.pose_of(x.angles);
  out.shape = x.shape;
  out.moved.rotation = skinning::rodrigues(x.turn);
  out.moved.pivot = fit.centre() + x.offset.transpose();
  out.moved.offset = x.offset.transpose();
  const Eigen::MatrixX3d miss = fit.residual(x, false);
  out.fit_rms = std::sqrt(miss.rowwise().squaredNorm().mean());
  out.fit_max = miss.rowwise().norm().maxCoeff();
  out.rest = fit.unpose(fit.base(), fit.in_model_frame(x), out.pose, out.reposed_error);
  return out;
}

}  // namespace drape
