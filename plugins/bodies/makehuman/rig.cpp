// MakeHuman's rig as drape's skeleton (rig.hpp).
#include "rig.hpp"
#include "model.hpp"

#include <drape/errors.hpp>

#include <Eigen/Cholesky>

#include <algorithm>
#include <map>

namespace drape::makehuman {
namespace {

// Every target's offsets densely, one row per base vertex, 3 columns per target.
Eigen::MatrixXd dense_offsets(const std::vector<Target>& targets, Eigen::Index num_vertices) {
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(num_vertices, 3 * static_cast<Eigen::Index>(targets.size()));
  for (std::size_t t = 0; t < targets.size(); ++t)
    for (std::size_t k = 0; k < targets[t].index.size(); ++k)
      for (int a = 0; a < 3; ++a)
        d(targets[t].index[k], 3 * static_cast<Eigen::Index>(t) + a) = targets[t].offset(static_cast<Eigen::Index>(k), a);
  return d;
}

// Column c of a basis for points `rows` of the mesh: 0.1 (mean over each
// point's vertices of target c's offsets), then unit translations.
Eigen::MatrixXd basis(const std::vector<std::vector<int>>& points, const Eigen::MatrixXd& offsets, std::size_t targets,
                      Eigen::VectorXd& base_out, const Eigen::MatrixX3d& base) {
  const auto n = static_cast<Eigen::Index>(points.size());
  const auto t = static_cast<Eigen::Index>(targets);
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(3 * n, t + 3);
  base_out = Eigen::VectorXd::Zero(3 * n);
  for (Eigen::Index p = 0; p < n; ++p) {
    const auto& ids = points[static_cast<std::size_t>(p)];
    const double share = 1.0 / static_cast<double>(ids.size());
    for (int v : ids)
      for (int a = 0; a < 3; ++a) {
        base_out[3 * p + a] += kMetersPerUnit * share * base(v, a);
        for (Eigen::Index c = 0; c < t; ++c) m(3 * p + a, c) += kMetersPerUnit * share * offsets(v, 3 * c + a);
      }
    for (int a = 0; a < 3; ++a) m(3 * p + a, t + a) = 1;
  }
  return m;
}

}  // namespace

int Rig::index(const std::string& bone) const {
  for (std::size_t b = 0; b < joints.size(); ++b)
    if (joints[b].name == bone) return static_cast<int>(b);
  throw Error("MakeHuman rig: no bone \"" + bone + "\"");
}

Rig build_rig(const RigFiles& files, const Eigen::MatrixX3d& base, int skin_vertices, const std::vector<Target>& targets,
              const std::function<std::vector<std::string>(const std::string& bone)>& angles_of) {
  Rig rig;
  std::map<std::string, int> index;
  for (const RigFiles::Bone& b : files.bones) {
    index[b.name] = static_cast<int>(rig.joints.size());
    rig.joints.push_back({b.name, b.parent.empty() ? -1 : index.at(b.parent), angles_of(b.name)});
  }

  for (const RigFiles::Bone& b : files.bones) rig.head_vertices.push_back(files.joints.at(b.head));
  const Eigen::MatrixXd offsets = dense_offsets(targets, base.rows());
  std::vector<std::vector<int>> skin(static_cast<std::size_t>(skin_vertices));
  for (int v = 0; v < skin_vertices; ++v) skin[static_cast<std::size_t>(v)] = {v};
  rig.skin_basis = basis(skin, offsets, targets.size(), rig.skin_base, base);
  rig.head_basis = basis(rig.head_vertices, offsets, targets.size(), rig.head_base, base);
  // Targets that move the skin alike (or a header-only one) leave the normal
  // matrix singular: a ridge of 1e-9 of its mean diagonal picks the
  // smallest weights among the equal fits.
  Eigen::MatrixXd normal = rig.skin_basis.transpose() * rig.skin_basis;
  normal.diagonal().array() += 1e-9 * normal.diagonal().mean();
  rig.skin_normal.compute(normal);

  // Weights as MakeHuman normalises them (each vertex's weights divided by
  // their sum, a vertex listed twice for a bone summed), on the skin only:
  // entries on helper vertices are dropped, and a skin vertex no bone
  // weights goes to the root with weight 1.
  rig.weights = Eigen::MatrixXd::Zero(skin_vertices, static_cast<Eigen::Index>(rig.joints.size()));
  for (const auto& [bone, list] : files.weights)
    for (const auto& [v, w] : list) {
      if (v >= skin_vertices) {
        ++rig.dropped_weights;
        continue;
      }
      rig.weights(v, index.at(bone)) += w;
    }
  for (Eigen::Index v = 0; v < rig.weights.rows(); ++v) {
    const double sum = rig.weights.row(v).sum();
    if (sum > 0)
      rig.weights.row(v) /= sum;
    else
      rig.weights(v, 0) = 1;
  }
  return rig;
}

Eigen::MatrixX3d regress_joints(const Rig& rig, const Eigen::MatrixX3d& skin) {
  Eigen::VectorXd flat(3 * skin.rows());
  for (Eigen::Index v = 0; v < skin.rows(); ++v) flat.segment<3>(3 * v) = skin.row(v).transpose();
  const Eigen::VectorXd w = rig.skin_normal.solve(rig.skin_basis.transpose() * (flat - rig.skin_base));
  const Eigen::VectorXd heads = rig.head_base + rig.head_basis * w;
  Eigen::MatrixX3d j(static_cast<Eigen::Index>(rig.head_vertices.size()), 3);
  for (Eigen::Index b = 0; b < j.rows(); ++b) j.row(b) = heads.segment<3>(3 * b).transpose();
  return j;
}

Eigen::MatrixX3d group_joints(const Rig& rig, const Eigen::MatrixX3d& all) {
  Eigen::MatrixX3d j(static_cast<Eigen::Index>(rig.head_vertices.size()), 3);
  for (std::size_t b = 0; b < rig.head_vertices.size(); ++b) {
    Eigen::RowVector3d s = Eigen::RowVector3d::Zero();
    for (int v : rig.head_vertices[b]) s += all.row(v);
    j.row(static_cast<Eigen::Index>(b)) = s / static_cast<double>(rig.head_vertices[b].size());
  }
  return j;
}

}  // namespace drape::makehuman
