#include <drape/nn/skinny_gemm.hpp>

#include "kernel_choice.hpp"

#include <algorithm>
#include <vector>

#ifdef DRAPE_NN_X86
#include <immintrin.h>
#endif

namespace drape::nn::detail {

#ifdef DRAPE_NN_X86
namespace {

constexpr long kMaxSmall = 320;  // the small matrix's sides
constexpr long kMinTall = 64;    // the tall side
constexpr long kRowChunk = 128;  // tall output: rows of a kept in L1/L2 while every column panel passes them
constexpr long kDepthChunk = 256;  // weight gradient: rows of a and b kept in L2 while every block of c passes them

// The columns a vector covers: all 16, or the first `lanes` of the last.
inline __mmask16 lane_mask(long lanes) {
  return lanes >= 16 ? static_cast<__mmask16>(0xFFFF) : static_cast<__mmask16>((1u << lanes) - 1u);
}

// For r < R and vector j < NZ (columns 16 j .. 16 j + 15, the last masked):
//   c(r, .) = [c(r, .) if accumulate] + sum_{kk < k} A(r, kk) B(kk, .)
// with A(r, kk) = a[r rs + kk ks] and B's row kk at b + kk ldb. R x NZ <= 24
// accumulators; each B vector is loaded once per kk for all R rows.
template <int R, int NZ>
DRAPE_AVX512 void micro(const float* a, long rs, long ks, const float* b, long ldb, long k, float* c, long ldc,
                        __mmask16 last, bool accumulate) {
  // Every loop over R and NZ unrolled: the accumulators must live in registers.
  __m512 acc[R][NZ];
#pragma GCC unroll 24
  for (int r = 0; r < R; ++r)
#pragma GCC unroll 4
    for (int j = 0; j < NZ; ++j)
      acc[r][j] = accumulate ? _mm512_maskz_loadu_ps(j == NZ - 1 ? last : 0xFFFF, c + r * ldc + 16 * j)
                             : _mm512_setzero_ps();
  for (long kk = 0; kk < k; ++kk) {
    __m512 bv[NZ];
#pragma GCC unroll 4
    for (int j = 0; j < NZ; ++j) bv[j] = _mm512_maskz_loadu_ps(j == NZ - 1 ? last : 0xFFFF, b + kk * ldb + 16 * j);
    const float* ak = a + kk * ks;
#pragma GCC unroll 24
    for (int r = 0; r < R; ++r) {
      const __m512 x = _mm512_set1_ps(ak[r * rs]);
#pragma GCC unroll 4
      for (int j = 0; j < NZ; ++j) acc[r][j] = _mm512_fmadd_ps(x, bv[j], acc[r][j]);
    }
  }
#pragma GCC unroll 24
  for (int r = 0; r < R; ++r)
#pragma GCC unroll 4
    for (int j = 0; j < NZ; ++j) _mm512_mask_storeu_ps(c + r * ldc + 16 * j, j == NZ - 1 ? last : 0xFFFF, acc[r][j]);
}

// The last rows % R rows of a block, R - 1 down to 1 at a time.
template <int R, int NZ>
DRAPE_AVX512 void micro_tail(long rows, const float* a, long rs, long ks, const float* b, long ldb, long k, float* c,
                             long ldc, __mmask16 last, bool accumulate) {
  if constexpr (R > 0) {
    if (rows == R) return micro<R, NZ>(a, rs, ks, b, ldb, k, c, ldc, last, accumulate);
    micro_tail<R - 1, NZ>(rows, a, rs, ks, b, ldb, k, c, ldc, last, accumulate);
  }
}

// Rows [0, rows) of c, columns of one panel of NZ vectors, R rows at a time.
template <int NZ, int R>
DRAPE_AVX512 void panel(long rows, const float* a, long rs, long ks, const float* b, long ldb, long k, float* c,
                        long ldc, __mmask16 last, bool accumulate) {
  long r = 0;
  for (; r + R <= rows; r += R) micro<R, NZ>(a + r * rs, rs, ks, b, ldb, k, c + r * ldc, ldc, last, accumulate);
  if (r < rows) micro_tail<R - 1, NZ>(rows - r, a + r * rs, rs, ks, b, ldb, k, c + r * ldc, ldc, last, accumulate);
}

// Every column of c, in panels of up to 64 (four vectors). One vector of
// columns takes 12 rows at a time for a tall output (its rows of a are far
// apart) and 24 for a weight gradient (adjacent floats of a row of a):
// measured, each the faster there.
template <int Single>
DRAPE_AVX512 void panels(long rows, long n, const float* a, long rs, long ks, const float* b, long ldb, long k,
                         float* c, long ldc, bool accumulate) {
  for (long j0 = 0; j0 < n; j0 += 64) {
    const long width = std::min<long>(64, n - j0);
    const int vectors = static_cast<int>((width + 15) / 16);
    const __mmask16 last = lane_mask(width - 16 * (vectors - 1));
    switch (vectors) {
      case 1: panel<1, Single>(rows, a, rs, ks, b + j0, ldb, k, c + j0, ldc, last, accumulate); break;
      case 2: panel<2, 12>(rows, a, rs, ks, b + j0, ldb, k, c + j0, ldc, last, accumulate); break;
      case 3: panel<3, 8>(rows, a, rs, ks, b + j0, ldb, k, c + j0, ldc, last, accumulate); break;
      default: panel<4, 6>(rows, a, rs, ks, b + j0, ldb, k, c + j0, ldc, last, accumulate); break;
    }
  }
}

// A row-major view's row stride (a single row or column may report 1).
template <class M>
long stride(const M& x) {
  return std::max<long>({static_cast<long>(x.outerStride()), static_cast<long>(x.cols()), 1L});
}

}  // namespace

bool skinny_gemm(bool transpose_a, bool transpose_b, float alpha, ConstMatRef a, ConstMatRef b, float beta, MatRef c) {
  if (alpha != 1.0f || (beta != 0.0f && beta != 1.0f) || !avx512_kernels()) return false;
  const long m = c.rows(), n = c.cols(), k = transpose_a ? a.rows() : a.cols();
  if (m == 0 || n == 0 || k == 0) return false;
  const long lda = stride(a), ldb = stride(b), ldc = stride(c);
  if (!transpose_a) {
    // Tall output: c [m, n] = a [m, k] op(b). op(b) as a [k, n] row-major matrix.
    if (m < kMinTall || n > kMaxSmall || k > kMaxSmall) return false;
    const float* bk = b.data();
    long ldbk = ldb;
    thread_local std::vector<float> transposed;
    if (transpose_b) {
      transposed.resize(static_cast<std::size_t>(k * n));
      for (long j = 0; j < n; ++j)
        for (long kk = 0; kk < k; ++kk) transposed[static_cast<std::size_t>(kk * n + j)] = b.data()[j * ldb + kk];
      bk = transposed.data();
      ldbk = n;
    }
    for (long r0 = 0; r0 < m; r0 += kRowChunk)
      panels<12>(std::min(kRowChunk, m - r0), n, a.data() + r0 * lda, lda, 1, bk, ldbk, k, c.data() + r0 * ldc, ldc,
             beta == 1.0f);
    return true;
  }
  // Weight gradient: c [m, n] = a [k, m]' b [k, n], k long.
  if (transpose_b || k < kMinTall || m > kMaxSmall || n > kMaxSmall) return false;
  for (long k0 = 0; k0 < k; k0 += kDepthChunk)
    panels<24>(m, n, a.data() + k0 * lda, 1, lda, b.data() + k0 * ldb, ldb, std::min(kDepthChunk, k - k0), c.data(), ldc,
           k0 > 0 || beta == 1.0f);
  return true;
}

#else

bool skinny_gemm(bool, bool, float, ConstMatRef, ConstMatRef, float, MatRef) { return false; }

#endif

}  // namespace drape::nn::detail
