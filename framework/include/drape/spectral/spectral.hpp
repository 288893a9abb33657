#pragma once
// The spectral basis of a garment (seed Sec. 6.3.3, eq. 6.5 and 6.13): V, the
// eigenvectors of the mesh Laplacian for its k smallest eigenvalues. The network
// uses c = V^T x and dx = V dc, so V must be plainly orthonormal (V^T V = I):
// the operator is symmetric and no mass matrix enters the eigenproblem.
//
// Default operator: the cotangent stiffness K of the rest garment (geometry
// aware, constants in its kernel, so the first eigenvector is constant). With
// the identity as mass, V V^T is the orthogonal projection for the plain sum
// over vertices, the same weighting as the mean vertex error the seed reports.
// The combinatorial graph Laplacian D - A is available for comparison.
#include <drape/mesh.hpp>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <string>
#include <vector>

namespace drape {

enum class SpectralOperator { cotangent, combinatorial };

enum class EigenSolver {
  automatic,     // measured choice: shift-invert Lanczos for small k, dense otherwise
  shift_invert,  // Spectra's SymEigsShiftSolver over a sparse LDLT of (L - sigma I)
  dense,         // all pairs with LAPACK dsyevd (Eigen's solver if LAPACK is absent)
};

struct EigenbasisOptions {
  SpectralOperator op = SpectralOperator::cotangent;
  EigenSolver solver = EigenSolver::automatic;
  // Shift of the shift-invert solve, relative to the mean diagonal of the
  // operator. Slightly negative so that L - sigma I stays positive definite
  // although L is singular (constants, one per connected component).
  double relative_shift = -1e-3;
};

struct Eigenbasis {
  Eigen::VectorXd values;   // [k] ascending, non-negative (roundoff clamped to 0)
  Eigen::MatrixXd vectors;  // [n, k] orthonormal columns; sign: positive sum (or first large entry)
  EigenSolver solver = EigenSolver::automatic;  // the one that ran
  double seconds = 0;                           // wall time of the eigensolve
};

// The symmetric operator the basis is computed from.
Eigen::SparseMatrix<double> spectral_operator(const Mesh& mesh, SpectralOperator op);

// k smallest eigenpairs of the mesh's operator; 1 <= k <= n, else ConfigError.
Eigenbasis compute_eigenbasis(const Mesh& mesh, int k, const EigenbasisOptions& options = {});

// The same for any symmetric positive semi-definite matrix.
Eigenbasis compute_eigenbasis(const Eigen::SparseMatrix<double>& symmetric_psd, int k,
                              const EigenbasisOptions& options = {});

// The solver `automatic` picks for n vertices and k vectors.
EigenSolver automatic_solver(int n, int k);
bool have_lapack();
std::string to_string(EigenSolver solver);

struct ReconstructionError {
  int k = 0;
  double mean = 0;  // mean over vertices of |x_i - (V_k V_k^T x)_i|, in the mesh's units
  double max = 0;
};

// Error of projecting the shape X [n, 3] onto the first k columns of V, for
// each k in `ks` (each in [0, V.cols()]), like the seed's Fig. 6.4.
std::vector<ReconstructionError> reconstruction_error(const Eigen::MatrixXd& V, const Eigen::MatrixX3d& X,
                                                      const std::vector<int>& ks);

}  // namespace drape
