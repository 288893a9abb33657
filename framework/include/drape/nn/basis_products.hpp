#pragma once
// Products of a tall basis V [n, k] (row-major, n >> k >> m: the garment's
// eigenvectors, 3505 x 1000) with a few vectors (m = 3 x batch):
//
//   basis_times:           out [n, m] = V A'      out(i, r) = sum_j V(i, j) A(r, j)
//   basis_transpose_times: out [m, k] = B' V      out(r, j) = sum_i B(i, r) V(i, j)
//
// The spectral decoder and the spectral loss make one of each per training
// step, each way: four products of 84 MFLOP over V's 14 MB. Through the BLAS
// (OpenBLAS's AVX-512 kernels) each took ~2.8 ms, 14 % of a default-resolution
// training step, because every call first copies all of V into the library's
// blocked layout. These kernels read V in place, in blocks that stay in L1 or
// L2 while the small operand is reused from registers: AVX-512F, chosen at run
// time; on other CPUs, or with DRAPE_PORTABLE_KERNELS=1, the BLAS product (a
// float V) or one pass over V's rows through dot_rows/axpy_rows (a bfloat16
// V, widened a row at a time).
// The sums run in another order than the BLAS's: results agree to float
// rounding, and each path gives the same bits every time.
#include <drape/nn/refs.hpp>

#include <cstdint>

namespace drape::nn {

// out = V A'; V [n, k], A [m, k], out [n, m].
void basis_times(ConstMatRef v, ConstMatRef a, MatRef out);
// out = B' V; B [n, m], V [n, k], out [m, k].
void basis_transpose_times(ConstMatRef b, ConstMatRef v, MatRef out);

// V stored as bfloat16 (the top 16 bits of each float, as the spectral decoder
// keeps its basis): half the bytes to read, the same products of the widened
// values.
struct Bfloat16Matrix {
  const std::uint16_t* data;
  long rows, cols, stride;  // row i starts at data + i * stride
};
void basis_times(const Bfloat16Matrix& v, ConstMatRef a, MatRef out);
void basis_transpose_times(ConstMatRef b, const Bfloat16Matrix& v, MatRef out);

// Which version runs here: "avx512f" (with BW and VL) or "portable".
const char* basis_products_version();

}  // namespace drape::nn
