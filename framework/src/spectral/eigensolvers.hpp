#pragma once
// The two eigensolver back-ends of compute_eigenbasis. Each returns the k
// smallest eigenpairs, unsorted and unnormalised in sign. Private.
#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace drape::spectral_detail {

// Spectra shift-invert Lanczos around sigma (must be below the smallest eigenvalue).
void shift_invert_eigs(const Eigen::SparseMatrix<double>& a, int k, double sigma, Eigen::VectorXd& values,
                       Eigen::MatrixXd& vectors);

// Every eigenpair of the dense matrix, then the first k.
void dense_eigs(const Eigen::SparseMatrix<double>& a, int k, Eigen::VectorXd& values, Eigen::MatrixXd& vectors);

bool lapack_available();

}  // namespace drape::spectral_detail
