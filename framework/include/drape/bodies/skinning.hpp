#pragma once
// Linear blend skinning, the part every poseable body model shares (the
// parametric body's skeleton, SMPL's kinematic tree): per-joint rotations in
// the rest frame composed down a kinematic tree about the rest joint centres,
// then each vertex moved by its joints' transforms blended by its weights.
// What a model's angles mean (anatomical angles, SMPL's axis-angle θ) stays
// in its plugin; plugins never depend on each other, so this lives here.
#include <Eigen/Core>

#include <vector>

namespace drape::skinning {

// x -> r x + t.
struct Rigid {
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  bool identity() const { return r == Eigen::Matrix3d::Identity() && t == Eigen::Vector3d::Zero(); }
};

// Each joint's transform of the rest body: its rotation `local[b]` (in the
// rest frame) about its rest centre `joints.row(b)`, after its parent's,
// G_b = G_parent(b) T(J_b) R_b T(-J_b). `parents[b]` is -1 for a root and
// comes before b. This is SMPL's G_k(θ, J) with the rest transform
// G_k(0, J) removed (Loper et al. 2015, eqs. 3-4) written without it.
std::vector<Rigid> joint_transforms(const std::vector<int>& parents, const std::vector<Eigen::Matrix3d>& local,
                                    const Eigen::MatrixX3d& joints);

// v' = v + sum_b w(v, b) ((R_b - I) v + t_b), `weights` one row per vertex
// and one column per joint: sum_b w (R_b v + t_b) when the row sums to 1,
// and a joint at rest adds exactly nothing, so the rest pose gives
// `vertices` back bit for bit.
Eigen::MatrixX3d blend(const Eigen::MatrixX3d& vertices, const Eigen::MatrixXd& weights,
                       const std::vector<Rigid>& transforms);

// The rotation of an axis-angle vector (radians; its direction the axis, its
// norm the angle), by Rodrigues' formula; the zero vector gives the identity
// exactly.
Eigen::Matrix3d rodrigues(const Eigen::Vector3d& axis_angle);

}  // namespace drape::skinning
