#pragma once
// Forward and back substitution with a single-precision copy of a supernodal
// Cholesky factor that CHOLMOD computed in double precision.
//
// Why: the cloth solver preconditions conjugate gradients with the last
// factor and applies it ~40 times per factorisation (docs/scenes.md), and
// those triangular solves were a third of a drape. A preconditioner need not
// be exact: the float copy (the factor rounded to float, so L L' stays
// symmetric positive definite) halves the bytes each solve streams and doubles
// the values per vector instruction. The Newton direction itself is still
// accepted only when PCG, in double, has reduced the true residual, and a
// fresh factor's direct solve stays in double.
#include <Eigen/Core>

#include <vector>

namespace drape::physics {

// A supernodal LL' factor in CHOLMOD's layout (int indices), values in float.
class FloatSupernodalFactor {
 public:
  // The factor's pattern, fixed by the symbolic analysis: copied once per
  // analysis, not per factorisation.
  void set_pattern(int n, int supernodes, const int* perm, const int* super, const int* row_start,
                   const int* value_start, const int* rows);
  // The numeric values (`count` doubles, each supernode column-major, rows x
  // columns), rounded to float.
  void set_values(const double* values, std::size_t count);
  // x = A^-1 b for A = P' L L' P, to float precision.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;

 private:
  int n_ = 0, supernodes_ = 0, widest_ = 0;
  std::vector<int> perm_, super_, row_start_, value_start_, rows_;
  std::vector<float> values_;
  mutable Eigen::VectorXf y_, gathered_;  // work space: solve is not thread-safe
};

}  // namespace drape::physics
