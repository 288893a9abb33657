// garment_skinning.hpp: a garment's skinning weights from the body surface,
// posing and unposing.
#include <drape/bodies/garment_skinning.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/body_correspondence.hpp>

#include <Eigen/LU>

#include <string>

namespace drape {

Eigen::MatrixXd garment_skinning_weights(const Mesh& body, const Eigen::MatrixXd& body_weights, const Mesh& garment,
                                         int smoothing) {
  if (body_weights.rows() != body.num_vertices())
    throw Error("garment skinning: " + std::to_string(body_weights.rows()) + " rows of body weights for " +
                std::to_string(body.num_vertices()) + " body vertices");
  const geometry::SurfaceAttachment at = geometry::attach_to_surface(body, garment.vertices);
  const Eigen::Index n = garment.vertices.rows(), joints = body_weights.cols();
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(n, joints);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) w.row(i) += at.barycentric(i, c) * body_weights.row(body.faces(at.face[i], c));
  // Neighbours by the garment's edges (each edge of each face; an interior
  // edge twice, which weighs no neighbour more than another in the mean).
  std::vector<std::vector<int>> neighbours(static_cast<std::size_t>(n));
  for (Eigen::Index f = 0; f < garment.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = garment.faces(f, c), b = garment.faces(f, (c + 1) % 3);
      neighbours[static_cast<std::size_t>(a)].push_back(b);
      neighbours[static_cast<std::size_t>(b)].push_back(a);
    }
  for (auto& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  for (int pass = 0; pass < smoothing; ++pass) {
    Eigen::MatrixXd next = w;
    for (Eigen::Index i = 0; i < n; ++i) {
      for (int j : neighbours[static_cast<std::size_t>(i)]) next.row(i) += w.row(j);
      next.row(i) /= static_cast<double>(1 + neighbours[static_cast<std::size_t>(i)].size());
    }
    w.swap(next);
  }
  for (Eigen::Index i = 0; i < n; ++i) w.row(i) /= w.row(i).sum();  // the means keep the sum; rounding aside
  return w;
}

Eigen::MatrixX3d pose_garment(const Eigen::MatrixX3d& canonical, const Eigen::MatrixXd& weights,
                              const std::vector<skinning::Rigid>& transforms) {
  return skinning::blend(canonical, weights, transforms);
}

Eigen::MatrixX3d unpose_garment(const Eigen::MatrixX3d& posed, const Eigen::MatrixXd& weights,
                                const std::vector<skinning::Rigid>& transforms) {
  if (weights.rows() != posed.rows() || weights.cols() != static_cast<Eigen::Index>(transforms.size()))
    throw Error("unpose_garment: weights [" + std::to_string(weights.rows()) + ", " + std::to_string(weights.cols()) +
                "] for " + std::to_string(posed.rows()) + " vertices and " + std::to_string(transforms.size()) + " joints");
  Eigen::MatrixX3d out(posed.rows(), 3);
  for (Eigen::Index i = 0; i < posed.rows(); ++i) {
    Eigen::Matrix3d r = Eigen::Matrix3d::Zero();
    Eigen::Vector3d t = Eigen::Vector3d::Zero();
    for (std::size_t b = 0; b < transforms.size(); ++b) {
      const double w = weights(i, static_cast<Eigen::Index>(b));
      if (w == 0) continue;
      r += w * transforms[b].r;
      t += w * transforms[b].t;
    }
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(r);
    if (!lu.isInvertible())
      throw Error("unpose_garment: vertex " + std::to_string(i) + "'s blended transform is singular");
    out.row(i) = lu.solve(posed.row(i).transpose() - t).transpose();
  }
  return out;
}

MatrixRM transforms_rows(const std::vector<skinning::Rigid>& transforms) {
  MatrixRM out(static_cast<Eigen::Index>(transforms.size()), 12);
  for (std::size_t b = 0; b < transforms.size(); ++b) {
    const auto row = static_cast<Eigen::Index>(b);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) out(row, 3 * r + c) = static_cast<float>(transforms[b].r(r, c));
    for (int c = 0; c < 3; ++c) out(row, 9 + c) = static_cast<float>(transforms[b].t[c]);
  }
  return out;
}

std::vector<skinning::Rigid> transforms_of_rows(const Tensor& rows, int sample) {
  if (rows.cols() != 12) throw Error("transforms_of_rows: rows of " + std::to_string(rows.cols()) + " values, expected 12");
  std::vector<skinning::Rigid> out(static_cast<std::size_t>(rows.rows()));
  for (std::size_t b = 0; b < out.size(); ++b) {
    const int row = static_cast<int>(b);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) out[b].r(r, c) = rows(sample, row, 3 * r + c);
    for (int c = 0; c < 3; ++c) out[b].t[c] = rows(sample, row, 9 + c);
  }
  return out;
}

NodeSkinning::NodeSkinning(const Eigen::MatrixXf& garment_skinning, const Shape& transforms, const std::string& node)
    : weights(garment_skinning) {
  if (weights.size() == 0)
    throw ConfigError(node + " needs the garment's skinning weights, and the bound template has none (its body model "
                             "has no skeleton, or no template assets are bound)");
  if (transforms.cols != 12 || transforms.rows != weights.cols())
    throw ConfigError("input 'transforms' must be [" + std::to_string(weights.cols()) +
                      ", 12] (one rigid transform per joint: R row by row, then t), got " + transforms.str());
  joints.resize(static_cast<std::size_t>(weights.rows()));
  for (Eigen::Index i = 0; i < weights.rows(); ++i)
    for (Eigen::Index b = 0; b < weights.cols(); ++b)
      if (weights(i, b) != 0.0f) joints[static_cast<std::size_t>(i)].push_back(static_cast<int>(b));
}

}  // namespace drape
