#pragma once
// The network's dense matrix products, c = alpha op(a) op(b) + beta c, on
// row-major float views. Products big enough to pay for a library call go to
// the BLAS the framework was linked with (OpenBLAS on Debian), which picks
// AVX2 / AVX-512 kernels for the CPU it runs on; the rest, and builds without
// a BLAS, use Eigen (compiled for the baseline x86-64, SSE2). The BLAS runs on
// the calling thread only (set_blas_threads(1)): drape already runs one
// sample or one batch slice per core.
#include <drape/nn/refs.hpp>

namespace drape::nn {

enum class Op { None, Transpose };

void gemm(Op op_a, Op op_b, float alpha, ConstMatRef a, ConstMatRef b, float beta, MatRef c);

// Which path products of m x k times k x n take: "blas" or "eigen".
const char* gemm_backend(long m, long n, long k);

}  // namespace drape::nn
