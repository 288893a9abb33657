// The only translation unit that includes Spectra (its templates are slow to compile).
#include "eigensolvers.hpp"

#include <drape/errors.hpp>

#include <Eigen/SparseCholesky>
#include <Spectra/SymEigsShiftSolver.h>

#include <algorithm>
#include <string>

namespace drape::spectral_detail {
namespace {

// y = (A - sigma I)^-1 x through a sparse LDLT: A - sigma I is symmetric
// positive definite for sigma below the spectrum, so LDLT suffices and is
// cheaper than the LU that Spectra's own SparseSymShiftSolve uses.
class LdltShiftInvert {
 public:
  using Scalar = double;
  explicit LdltShiftInvert(const Eigen::SparseMatrix<double>& a) : a_(a) {}
  Eigen::Index rows() const { return a_.rows(); }
  Eigen::Index cols() const { return a_.cols(); }
  void set_shift(const double& sigma) {
    Eigen::SparseMatrix<double> identity(a_.rows(), a_.cols());
    identity.setIdentity();
    ldlt_.compute(a_ - sigma * identity);
    if (ldlt_.info() != Eigen::Success)
      throw Error("compute_eigenbasis: the LDLT factorisation of (L - sigma I) failed for sigma = " + std::to_string(sigma));
  }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, a_.rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, a_.rows());
    y = ldlt_.solve(x);
  }

 private:
  const Eigen::SparseMatrix<double>& a_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt_;
};

}  // namespace

void shift_invert_eigs(const Eigen::SparseMatrix<double>& a, int k, double sigma, Eigen::VectorXd& values,
                       Eigen::MatrixXd& vectors) {
  const int n = static_cast<int>(a.rows());
  LdltShiftInvert op(a);
  // A Krylov space of about twice the wanted size converges in few restarts.
  const int ncv = std::min(n, std::max(2 * k + 1, k + 20));
  Spectra::SymEigsShiftSolver<LdltShiftInvert> eigs(op, k, ncv, sigma);
  eigs.init();
  const Eigen::Index converged = eigs.compute(Spectra::SortRule::LargestMagn, 1000, 1e-10);
  if (eigs.info() != Spectra::CompInfo::Successful)
    throw Error("compute_eigenbasis: shift-invert Lanczos converged for " + std::to_string(converged) + " of " +
                std::to_string(k) + " eigenpairs; try the dense solver");
  values = eigs.eigenvalues();
  vectors = eigs.eigenvectors();
}

}  // namespace drape::spectral_detail
