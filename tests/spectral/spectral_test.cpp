// Spectral basis: orthonormal, sorted, non-negative, constant first vector,
// both solvers agree, reconstruction error falls to zero at k = n.
#include "../hierarchy/sewn_tube.hpp"

#include <drape/errors.hpp>
#include <drape/geometry/laplacian.hpp>
#include <drape/spectral/spectral.hpp>

#include <catch2/catch.hpp>

using namespace drape;

namespace {

double orthonormality_error(const Eigen::MatrixXd& V) {
  return (V.transpose() * V - Eigen::MatrixXd::Identity(V.cols(), V.cols())).cwiseAbs().maxCoeff();
}

void check_basis(const Eigenbasis& b, const Eigen::SparseMatrix<double>& op, int n, int k) {
  REQUIRE(b.values.size() == k);
  REQUIRE(b.vectors.rows() == n);
  REQUIRE(b.vectors.cols() == k);
  CHECK(orthonormality_error(b.vectors) < 1e-6);
  CHECK(b.values.minCoeff() >= 0);
  for (int i = 1; i < k; ++i) CHECK(b.values[i] >= b.values[i - 1]);
  // Eigenpairs: residual small against the operator's scale.
  const double scale = Eigen::VectorXd(op.diagonal()).maxCoeff();
  const Eigen::MatrixXd residual = op * b.vectors - b.vectors * b.values.asDiagonal();
  CHECK(residual.cwiseAbs().maxCoeff() < 1e-8 * scale);
  // Connected mesh: one zero eigenvalue, the constant vector (positive sign).
  CHECK(b.values[0] < 1e-10 * scale);
  CHECK(b.values[1] > 1e-6 * scale);
  CHECK((b.vectors.col(0).array() - 1.0 / std::sqrt(double(n))).abs().maxCoeff() < 1e-8);
}

}  // namespace

TEST_CASE("dense and shift-invert bases are orthonormal eigenpairs, sorted, starting with the constant") {
  const Mesh m = test::sewn_tube(20, 50);  // 2000 vertices
  const int n = m.num_vertices();
  for (SpectralOperator op : {SpectralOperator::cotangent, SpectralOperator::combinatorial}) {
    const Eigen::SparseMatrix<double> L = spectral_operator(m, op);
    INFO((op == SpectralOperator::cotangent ? "cotangent" : "combinatorial"));
    const Eigenbasis lanczos = compute_eigenbasis(m, 40, {.op = op, .solver = EigenSolver::shift_invert});
    CHECK(lanczos.solver == EigenSolver::shift_invert);
    check_basis(lanczos, L, n, 40);
    const Eigenbasis dense = compute_eigenbasis(m, 40, {.op = op, .solver = EigenSolver::dense});
    CHECK(dense.solver == EigenSolver::dense);
    check_basis(dense, L, n, 40);
    CHECK((lanczos.values - dense.values).cwiseAbs().maxCoeff() < 1e-8 * dense.values[39]);
  }
}

TEST_CASE("the automatic solver uses shift-invert for few vectors and dense for many") {
  CHECK(automatic_solver(3500, 64) == EigenSolver::shift_invert);
  CHECK(automatic_solver(3500, 1000) == EigenSolver::dense);
  CHECK(automatic_solver(500, 10) == EigenSolver::dense);
}

TEST_CASE("reconstruction error falls with k and vanishes with the full basis") {
  const Mesh m = test::sewn_tube(10, 20);  // 400 vertices: the full dense basis is instant
  const int n = m.num_vertices();
  const Eigenbasis b = compute_eigenbasis(m, n);
  CHECK(orthonormality_error(b.vectors) < 1e-6);
  const std::vector<int> ks = {n, 1, 4, 16, 64, 256};
  const auto errors = reconstruction_error(b.vectors, m.vertices, ks);
  REQUIRE(errors.size() == ks.size());
  for (std::size_t i = 0; i < ks.size(); ++i) CHECK(errors[i].k == ks[i]);
  CHECK(errors[0].mean < 1e-12);
  CHECK(errors[0].max < 1e-12);
  for (std::size_t i = 2; i < ks.size(); ++i) CHECK(errors[i].mean < errors[i - 1].mean);
  // k = 1 keeps only the centroid: the error is the mean distance to it.
  const Eigen::RowVector3d centroid = m.vertices.colwise().mean();
  CHECK(errors[1].mean == Approx((m.vertices.rowwise() - centroid).rowwise().norm().mean()).epsilon(1e-9));
  // A shape made of the first 10 vectors comes back exactly from 10 of them.
  const Eigen::MatrixX3d in_span = b.vectors.leftCols(10) * Eigen::MatrixXd::Random(10, 3);
  const auto span_errors = reconstruction_error(b.vectors, in_span, {9, 10});
  CHECK(span_errors[0].mean > 1e-3);
  CHECK(span_errors[1].max < 1e-12);
}

TEST_CASE("bad k and mismatched shapes are refused") {
  const Mesh m = test::sewn_tube(6, 6);
  CHECK_THROWS_AS(compute_eigenbasis(m, 0), ConfigError);
  CHECK_THROWS_WITH(compute_eigenbasis(m, m.num_vertices() + 1), Catch::Contains("outside [1, 72]"));
  const Eigenbasis b = compute_eigenbasis(m, 4);
  CHECK_THROWS_AS(reconstruction_error(b.vectors, m.vertices, {5}), ConfigError);
  CHECK_THROWS_AS(reconstruction_error(b.vectors, m.vertices.topRows(10), {2}), ConfigError);
}
