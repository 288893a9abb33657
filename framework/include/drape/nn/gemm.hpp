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

// The kernel set OpenBLAS chose for this CPU ("" for another BLAS).
const char* blas_corename();
// OpenBLAS 0.3.21 (Debian 12) falls back to its SSE3 "Prescott" kernels on
// CPUs newer than itself, AVX-512 ones included (2-3x slower products). Then,
// unless $OPENBLAS_CORETYPE is set, this returns the core type the CPU can run
// ("SkylakeX" or "Haswell"), else nullptr. OpenBLAS reads the variable when it
// loads, so a program applies it by re-executing itself: see below.
const char* better_blas_coretype();
// When better_blas_coretype() names one, sets $OPENBLAS_CORETYPE and executes
// /proc/self/exe with argv again; else (or if that fails) returns. Called first
// thing in main() by the drape program and the test programs, so that the
// library, the command line and the tests compute with the same kernels.
void reexec_with_native_blas(char** argv);

}  // namespace drape::nn
