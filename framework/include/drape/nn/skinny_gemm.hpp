#pragma once
// Products where one side is a small weight matrix and the other a tall stack
// of per-vertex features (nn::gemm's first choice for them; declared here for
// its tests):
//
//   tall output:     c [m, n] = a [m, k] op(b),   m >= 64, n, k <= 320
//   weight gradient: c [m, n] = a [k, m]' b [k, n], k >= 64, m, n <= 320
//
// At batch 8 and the default resolution m (or k) is 28,040 garment vertices
// and the channels are 3-64. OpenBLAS packs both operands into its blocked
// layout before every call, and zeroes c when beta = 0; for these shapes that
// costs about as much as the multiply-adds. These kernels read the operands in
// place: the small matrix stays in L1/L2, the tall one streams through once,
// and a block of up to 24 of its rows meets up to 4 vector columns of the
// small one in at most 24 AVX-512 accumulators (the weight gradient in chunks
// of 256 rows of k that stay in L2 while every block of c passes them).
// Measured alone on one core (OpenBLAS 0.3.21 SkylakeX kernels against these):
// [28040 x 32] x [32 x 32] 0.71 -> 0.48 ms, the weight gradients
// [64 x 28040] x [28040 x 16] 1.04 -> 0.60 ms and [32 x 28040] x [28040 x 32]
// 0.94 -> 0.49 ms, the encoder's [3248 x 160] x [160 x 64] 0.53 -> 0.45 ms.
//
// Takes alpha = 1 and beta 0 or 1 (all nn uses) and returns true; anything
// else, other shapes, CPUs without AVX-512 and DRAPE_PORTABLE_KERNELS=1 return
// false, c untouched, for the caller's BLAS or Eigen path. The sums run in a
// fixed order: the same bits every call, agreeing with the BLAS to float
// rounding.
#include <drape/nn/refs.hpp>

namespace drape::nn::detail {

bool skinny_gemm(bool transpose_a, bool transpose_b, float alpha, ConstMatRef a, ConstMatRef b, float beta, MatRef c);

}  // namespace drape::nn::detail
