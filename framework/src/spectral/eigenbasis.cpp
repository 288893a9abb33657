// compute_eigenbasis: operator, solver choice, sorting and sign convention.
#include <drape/errors.hpp>
#include <drape/geometry/laplacian.hpp>
#include <drape/spectral/spectral.hpp>

#include "eigensolvers.hpp"

#include <algorithm>
#include <chrono>
#include <numeric>

namespace drape {

Eigen::SparseMatrix<double> spectral_operator(const Mesh& mesh, SpectralOperator op) {
  if (op == SpectralOperator::combinatorial)
    return geometry::graph_laplacian(mesh.faces, mesh.num_vertices(), geometry::GraphLaplacian::combinatorial);
  return geometry::cotangent_stiffness(mesh.vertices, mesh.faces);
}

bool have_lapack() { return spectral_detail::lapack_available(); }

std::string to_string(EigenSolver solver) {
  switch (solver) {
    case EigenSolver::automatic: return "automatic";
    case EigenSolver::shift_invert: return "shift-invert";
    case EigenSolver::dense: return "dense";
  }
  return "?";
}

// Measured (NOTES-deps.md and docs in the report): shift-invert Lanczos costs
// about n k^2, dense dsyevd about n^3; they cross near k = n / 7 (n = 3708:
// k = 256 takes 2.1 s vs 12.7 s dense, k = 1000 takes 70 s). Below ~1500
// vertices the dense solve takes well under a second and is the most robust.
EigenSolver automatic_solver(int n, int k) {
  if (n <= 1500 || 7 * k >= n) return EigenSolver::dense;
  return EigenSolver::shift_invert;
}

Eigenbasis compute_eigenbasis(const Eigen::SparseMatrix<double>& a, int k, const EigenbasisOptions& options) {
  const int n = static_cast<int>(a.rows());
  if (a.rows() != a.cols()) throw ConfigError("compute_eigenbasis: the operator is not square");
  if (k < 1 || k > n)
    throw ConfigError("compute_eigenbasis: k = " + std::to_string(k) + " is outside [1, " + std::to_string(n) + "]");
  Eigenbasis out;
  out.solver = options.solver == EigenSolver::automatic ? automatic_solver(n, k) : options.solver;
  // Lanczos needs a Krylov space larger than k.
  if (out.solver == EigenSolver::shift_invert && k + 1 >= n) out.solver = EigenSolver::dense;

  const auto start = std::chrono::steady_clock::now();
  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;
  if (out.solver == EigenSolver::dense) {
    spectral_detail::dense_eigs(a, k, values, vectors);
  } else {
    const double mean_diagonal = std::max(a.diagonal().cwiseAbs().mean(), 1e-300);
    spectral_detail::shift_invert_eigs(a, k, options.relative_shift * mean_diagonal, values, vectors);
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::vector<int> order(values.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int i, int j) { return values[i] < values[j]; });
  out.values.resize(k);
  out.vectors.resize(n, k);
  for (int c = 0; c < k; ++c) {
    // The operator is PSD: a tiny negative value is roundoff of a zero eigenvalue.
    out.values[c] = std::max(0.0, values[order[c]]);
    Eigen::VectorXd v = vectors.col(order[c]);
    // Deterministic sign: positive sum, or (for sum ~ 0) first large entry positive.
    const double sum = v.sum();
    double s = sum;
    if (std::abs(sum) < 1e-8 * std::sqrt(static_cast<double>(n))) {
      const double big = 1e-3 * v.cwiseAbs().maxCoeff();
      for (int i = 0; i < n; ++i)
        if (std::abs(v[i]) > big) {
          s = v[i];
          break;
        }
    }
    out.vectors.col(c) = s < 0 ? -v : v;
  }
  return out;
}

Eigenbasis compute_eigenbasis(const Mesh& mesh, int k, const EigenbasisOptions& options) {
  if (mesh.num_faces() == 0) throw ConfigError("compute_eigenbasis: the mesh has no faces");
  return compute_eigenbasis(spectral_operator(mesh, options.op), k, options);
}

}  // namespace drape
