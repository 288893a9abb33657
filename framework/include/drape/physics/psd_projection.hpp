#pragma once
// Projection of a symmetric element Hessian onto the positive semidefinite cone
// (the nearest PSD matrix in the Frobenius norm): eigen-decompose and clamp the
// negative eigenvalues to zero (Teran et al. 2005, "Robust quasistatic finite
// elements"). Projected Newton sums such blocks into a PSD global matrix.
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace drape {

// Returns false (and leaves h unchanged) when h was already PSD.
template <int N>
bool project_to_psd(Eigen::Matrix<double, N, N>& h) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eig(h);
  const auto& lambda = eig.eigenvalues();
  if (lambda.minCoeff() >= 0.0) return false;
  h = eig.eigenvectors() * lambda.cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose();
  return true;
}

}  // namespace drape
