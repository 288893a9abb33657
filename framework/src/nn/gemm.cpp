#include <drape/errors.hpp>
#include "matrix_dims.hpp"
#include <drape/nn/gemm.hpp>
#include <drape/nn/blas_threads.hpp>

#include <drape/nn/skinny_gemm.hpp>

#include <algorithm>
#include <cstdlib>
#include <string>

#ifdef DRAPE_HAVE_BLAS
// The Fortran BLAS symbol: every BLAS exports it, so no cblas.h is needed.
extern "C" void sgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
                       const float* alpha, const float* a, const int* lda, const float* b, const int* ldb,
                       const float* beta, float* c, const int* ldc);
#endif

namespace drape::nn {

namespace {

// Below this many multiply-adds a BLAS call's fixed cost (dispatch, packing)
// is a large share of the product and Eigen's inline product is kept. Not
// tuned: at one sample the layers of graphs/drape.yaml that matter are far
// above it (the transfer 3505 x 64 x 16 is 3.6 M); the spectral MLP's layers
// (1 x 64 x 256, 1 x 256 x 3000) are matrix-vector products, kept in Eigen
// (below).
constexpr double kBlasMinimumWork = 32768;

bool use_blas(long m, long n, long k) {
#ifdef DRAPE_HAVE_BLAS
  // DRAPE_EIGEN_GEMM=1 keeps every product in Eigen (to compare, or to get
  // the same bits on every x86-64 CPU).
  static const bool allowed = [] {
    if (std::getenv("DRAPE_EIGEN_GEMM")) return false;
    set_blas_threads(1);
    return true;
  }();
  // One row or one column is a matrix-vector product: OpenBLAS's GEMM still
  // packs the whole other operand first (the spectral MLP's last layer at one
  // body: 3 MB of weights copied before they are read), where Eigen's product
  // reads it once in place. Measured on the posed model at one body (one core
  // of the 2-core EPYC, the push-out off, best of 1,000): the spectral node
  // 0.26-0.28 ms through BLAS, 0.15 ms through Eigen.
  if (m == 1 || n == 1) return false;
  return allowed && double(m) * double(n) * double(k) >= kBlasMinimumWork;
#else
  (void)m, (void)n, (void)k;
  return false;
#endif
}


}  // namespace

const char* gemm_backend(long m, long n, long k) { return use_blas(m, n, k) ? "blas" : "eigen"; }

void gemm(Op op_a, Op op_b, float alpha, ConstMatRef a, ConstMatRef b, float beta, MatRef c) {
  const bool ta = op_a == Op::Transpose, tb = op_b == Op::Transpose;
  const Eigen::Index m = ta ? a.cols() : a.rows(), k = ta ? a.rows() : a.cols();
  const Eigen::Index kb = tb ? b.cols() : b.rows(), n = tb ? b.rows() : b.cols();
  if (k != kb || c.rows() != m || c.cols() != n)
    throw Error("gemm: " + std::string(ta ? "a^T " : "a ") + dims(a.rows(), a.cols()) + (tb ? " times b^T " : " times b ") +
                dims(b.rows(), b.cols()) + " does not fit c " + dims(c.rows(), c.cols()));
  if (m == 0 || n == 0) return;
#ifdef DRAPE_HAVE_BLAS
  if (k > 0 && use_blas(m, n, k)) {
    // A small weight matrix against a tall stack of vertex features: read in
    // place instead of packed (skinny_gemm.hpp).
    if (detail::skinny_gemm(ta, tb, alpha, a, b, beta, c)) return;
    // Row-major X with leading dimension ld is column-major X^T: compute
    // c^T = op(b)^T op(a)^T in column-major terms.
    const int mi = int(n), ni = int(m), ki = int(k);
    // (A single row's outer stride may read 1; BLAS wants at least the row length.)
    const auto ld = [](const auto& x) { return int(std::max<Eigen::Index>({x.outerStride(), x.cols(), 1})); };
    const int lda = ld(b), ldb = ld(a), ldc = ld(c);
    sgemm_(tb ? "T" : "N", ta ? "T" : "N", &mi, &ni, &ki, &alpha, b.data(), &lda, a.data(), &ldb, &beta, c.data(), &ldc);
    return;
  }
#endif
  if (beta == 0.0f) c.setZero();
  else if (beta != 1.0f) c *= beta;
  if (k == 0) return;
  if (ta && tb) c.noalias() += alpha * (a.transpose() * b.transpose());
  else if (ta) c.noalias() += alpha * (a.transpose() * b);
  else if (tb) c.noalias() += alpha * (a * b.transpose());
  else c.noalias() += alpha * (a * b);
}

}  // namespace drape::nn
