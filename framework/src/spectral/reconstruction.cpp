#include <drape/errors.hpp>
#include <drape/spectral/spectral.hpp>

#include <algorithm>
#include <numeric>

namespace drape {

std::vector<ReconstructionError> reconstruction_error(const Eigen::MatrixXd& V, const Eigen::MatrixX3d& X,
                                                      const std::vector<int>& ks) {
  if (V.rows() != X.rows())
    throw ConfigError("reconstruction_error: the basis has " + std::to_string(V.rows()) + " rows but the shape has " +
                      std::to_string(X.rows()) + " vertices");
  for (int k : ks)
    if (k < 0 || k > V.cols())
      throw ConfigError("reconstruction_error: k = " + std::to_string(k) + " is outside [0, " +
                        std::to_string(V.cols()) + "]");
  // Add the columns' contributions in increasing k, so every k costs only its new columns.
  std::vector<int> order(ks.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return ks[a] < ks[b]; });
  const Eigen::MatrixX3d coefficients = V.transpose() * X;
  Eigen::MatrixX3d reconstruction = Eigen::MatrixX3d::Zero(X.rows(), 3);
  int done = 0;
  std::vector<ReconstructionError> out(ks.size());
  for (int idx : order) {
    const int k = ks[idx];
    if (k > done) {
      reconstruction += V.middleCols(done, k - done) * coefficients.middleRows(done, k - done);
      done = k;
    }
    const Eigen::VectorXd err = (X - reconstruction).rowwise().norm();
    out[idx] = {k, X.rows() ? err.mean() : 0.0, X.rows() ? err.maxCoeff() : 0.0};
  }
  return out;
}

}  // namespace drape
