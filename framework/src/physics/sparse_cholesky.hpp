#pragma once
// Sparse Cholesky factorisation of the Newton matrix with the symbolic
// analysis (fill-reducing ordering, elimination tree) done once per sparsity
// pattern: the pattern is fixed by the garment's topology, so every later
// factorisation is numeric only. Two back ends: Eigen's SimplicialLLT (always
// available) and CHOLMOD's supernodal LLT (when SuiteSparse was found at build
// time); `drape bench simulate` measures both.
#include <Eigen/SparseCore>

#include <memory>
#include <string>

namespace drape::physics {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

class SparseCholesky {
 public:
  virtual ~SparseCholesky() = default;
  // Factorises A (symmetric; the lower triangle is read). Re-analyses the
  // pattern when it changed. Returns false when A is not positive definite.
  virtual bool factorize(const SparseMatrix& a) = 0;
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& b) const = 0;
  // An approximate solve for preconditioning (conjugate gradients): the
  // CHOLMOD back end uses a single-precision copy of its factor; by default
  // the exact solve.
  virtual Eigen::VectorXd precondition(const Eigen::VectorXd& r) const { return solve(r); }
  virtual std::string name() const = 0;
};

// "eigen", "cholmod", or "auto" (CHOLMOD when built with it: faster, see the benchmark).
// ConfigError for an unknown name or cholmod when it is not available.
// float_preconditioner: CHOLMOD's precondition() solves with a float copy of
// the factor (Eigen's back end always solves exactly).
std::unique_ptr<SparseCholesky> make_sparse_cholesky(const std::string& name, bool float_preconditioner = true);
bool cholmod_available();

}  // namespace drape::physics
