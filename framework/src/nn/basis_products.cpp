#include <drape/nn/basis_products.hpp>

#include <drape/errors.hpp>
#include <drape/nn/dot_rows.hpp>
#include <drape/nn/gemm.hpp>

#include "kernel_choice.hpp"

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#ifdef DRAPE_NN_X86
// GCC 12 warns that _mm512_reduce_add_ps's "undefined" vectors are used
// uninitialized (they are placeholders the instruction ignores).
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#endif

namespace drape::nn {
namespace {

void check(bool ok, const char* what, long r1, long c1, long r2, long c2, long r3, long c3) {
  if (!ok)
    throw Error(std::string(what) + ": shapes [" + std::to_string(r1) + ", " + std::to_string(c1) + "] and [" +
                std::to_string(r2) + ", " + std::to_string(c2) + "] into [" + std::to_string(r3) + ", " +
                std::to_string(c3) + "] do not fit");
}

#ifdef DRAPE_NN_X86
// Sixteen lanes of a row as floats; with a mask, the lanes past k read as zero.
DRAPE_AVX512 inline __m512 load16(const float* p) { return _mm512_loadu_ps(p); }
DRAPE_AVX512 inline __m512 load16(const float* p, __mmask16 mask) { return _mm512_maskz_loadu_ps(mask, p); }
// bfloat16 is the top half of a float: widen and shift into place.
DRAPE_AVX512 inline __m512 load16(const std::uint16_t* p) {
  const __m512i wide = _mm512_cvtepu16_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(p)));
  return _mm512_castsi512_ps(_mm512_slli_epi32(wide, 16));
}
DRAPE_AVX512 inline __m512 load16(const std::uint16_t* p, __mmask16 mask) {
  const __m512i wide = _mm512_cvtepu16_epi32(_mm256_maskz_loadu_epi16(mask, p));
  return _mm512_castsi512_ps(_mm512_slli_epi32(wide, 16));
}

// out(i + p, r + q) = sum_j V(i + p, j) A(r + q, j) for p < P, q < R: P x R
// accumulators (at most 4 x 6 = 24 of the 32 registers), each lane of V and
// of A loaded once for the block.
template <int P, int R, class T>
DRAPE_AVX512 void dot_block(const T* v, long ldv, const float* a, long lda, long k, float* out, long ldo) {
  __m512 acc[P][R];
  for (int p = 0; p < P; ++p)
    for (int q = 0; q < R; ++q) acc[p][q] = _mm512_setzero_ps();
  long j = 0;
  for (; j + 16 <= k; j += 16) {
    __m512 x[R];
    for (int q = 0; q < R; ++q) x[q] = _mm512_loadu_ps(a + q * lda + j);
    for (int p = 0; p < P; ++p) {
      const __m512 y = load16(v + p * ldv + j);
      for (int q = 0; q < R; ++q) acc[p][q] = _mm512_fmadd_ps(y, x[q], acc[p][q]);
    }
  }
  if (j < k) {
    const __mmask16 mask = static_cast<__mmask16>((1u << (k - j)) - 1u);
    __m512 x[R];
    for (int q = 0; q < R; ++q) x[q] = load16(a + q * lda + j, mask);
    for (int p = 0; p < P; ++p) {
      const __m512 y = load16(v + p * ldv + j, mask);
      for (int q = 0; q < R; ++q) acc[p][q] = _mm512_fmadd_ps(y, x[q], acc[p][q]);
    }
  }
  for (int p = 0; p < P; ++p)
    for (int q = 0; q < R; ++q) out[p * ldo + q] = _mm512_reduce_add_ps(acc[p][q]);
}

template <int P, class T>
DRAPE_AVX512 void dot_rows_block(const T* v, long ldv, const float* a, long lda, long m, long k, float* out,
                                 long ldo) {
  long r = 0;
  for (; r + 6 <= m; r += 6) dot_block<P, 6, T>(v, ldv, a + r * lda, lda, k, out + r, ldo);
  switch (m - r) {
    case 5: dot_block<P, 5, T>(v, ldv, a + r * lda, lda, k, out + r, ldo); break;
    case 4: dot_block<P, 4, T>(v, ldv, a + r * lda, lda, k, out + r, ldo); break;
    case 3: dot_block<P, 3, T>(v, ldv, a + r * lda, lda, k, out + r, ldo); break;
    case 2: dot_block<P, 2, T>(v, ldv, a + r * lda, lda, k, out + r, ldo); break;
    case 1: dot_block<P, 1, T>(v, ldv, a + r * lda, lda, k, out + r, ldo); break;
    default: break;
  }
}

// Four rows of V at a time (16 KB at k = 1000, in L1 while A's rows pass them).
template <class T>
DRAPE_AVX512 void basis_times_avx512(const T* v, long ldv, long n, long k, const float* a, long lda, long m,
                                     float* out, long ldo) {
  long i = 0;
  for (; i + 4 <= n; i += 4) dot_rows_block<4, T>(v + i * ldv, ldv, a, lda, m, k, out + i * ldo, ldo);
  switch (n - i) {
    case 3: dot_rows_block<3, T>(v + i * ldv, ldv, a, lda, m, k, out + i * ldo, ldo); break;
    case 2: dot_rows_block<2, T>(v + i * ldv, ldv, a, lda, m, k, out + i * ldo, ldo); break;
    case 1: dot_rows_block<1, T>(v + i * ldv, ldv, a, lda, m, k, out + i * ldo, ldo); break;
    default: break;
  }
}

// out(r + q, j..j+15) += sum over rows i of the block of B(i, r + q) V(i, j..j+15),
// for q < R: R accumulators, each row of V's 16 lanes loaded once for all R.
template <int R, class T>
DRAPE_AVX512 void axpy_block(const float* b, long ldb, const T* v, long ldv, long rows, long k, float* out,
                             long ldo) {
  for (long j = 0; j < k; j += 16) {
    const __mmask16 mask = k - j >= 16 ? static_cast<__mmask16>(0xFFFF) : static_cast<__mmask16>((1u << (k - j)) - 1u);
    __m512 acc[R];
    for (int q = 0; q < R; ++q) acc[q] = _mm512_maskz_loadu_ps(mask, out + q * ldo + j);
    for (long i = 0; i < rows; ++i) {
      const __m512 y = load16(v + i * ldv + j, mask);
      const float* bi = b + i * ldb;
      for (int q = 0; q < R; ++q) acc[q] = _mm512_fmadd_ps(_mm512_set1_ps(bi[q]), y, acc[q]);
    }
    for (int q = 0; q < R; ++q) _mm512_mask_storeu_ps(out + q * ldo + j, mask, acc[q]);
  }
}

// Blocks of 64 rows of V (256 KB at k = 1000, in L2 while the column strips
// and out's rows pass them), out's rows eight at a time.
template <class T>
DRAPE_AVX512 void basis_transpose_times_avx512(const float* b, long ldb, long n, long m, const T* v, long ldv,
                                               long k, float* out, long ldo) {
  for (long r = 0; r < m; ++r)
    for (long j = 0; j < k; ++j) out[r * ldo + j] = 0.0f;
  constexpr long kRows = 64;
  for (long i = 0; i < n; i += kRows) {
    const long rows = n - i < kRows ? n - i : kRows;
    const float* bi = b + i * ldb;
    const T* vi = v + i * ldv;
    long r = 0;
    for (; r + 8 <= m; r += 8) axpy_block<8, T>(bi + r, ldb, vi, ldv, rows, k, out + r * ldo, ldo);
    switch (m - r) {
      case 7: axpy_block<7, T>(bi + r, ldb, vi, ldv, rows, k, out + r * ldo, ldo); break;
      case 6: axpy_block<6, T>(bi + r, ldb, vi, ldv, rows, k, out + r * ldo, ldo); break;
      case 5: axpy_block<5, T>(bi + r, ldb, vi, ldv, rows, k, out + r * ldo, ldo); break;
      case 4: axpy_block<4, T>(bi + r, ldb, vi, ldv, rows, k, out + r * ldo, ldo); break;
      case 3: axpy_block<3, T>(bi + r, ldb, vi, ldv, rows, k, out + r * ldo, ldo); break;
      case 2: axpy_block<2, T>(bi + r, ldb, vi, ldv, rows, k, out + r * ldo, ldo); break;
      case 1: axpy_block<1, T>(bi + r, ldb, vi, ldv, rows, k, out + r * ldo, ldo); break;
      default: break;
    }
  }
}

#endif

}  // namespace

void basis_times(ConstMatRef v, ConstMatRef a, MatRef out) {
  check(v.cols() == a.cols() && out.rows() == v.rows() && out.cols() == a.rows(), "basis_times", v.rows(), v.cols(),
        a.rows(), a.cols(), out.rows(), out.cols());
#ifdef DRAPE_NN_X86
  if (detail::avx512_kernels() && v.rows() > 0 && a.rows() > 0)
    return basis_times_avx512(v.data(), v.outerStride(), v.rows(), v.cols(), a.data(), a.outerStride(), a.rows(),
                              out.data(), out.outerStride());
#endif
  gemm(Op::None, Op::Transpose, 1.0f, v, a, 0.0f, out);
}

void basis_transpose_times(ConstMatRef b, ConstMatRef v, MatRef out) {
  check(b.rows() == v.rows() && out.rows() == b.cols() && out.cols() == v.cols(), "basis_transpose_times", b.rows(),
        b.cols(), v.rows(), v.cols(), out.rows(), out.cols());
#ifdef DRAPE_NN_X86
  if (detail::avx512_kernels() && b.cols() > 0 && v.cols() > 0)
    return basis_transpose_times_avx512(b.data(), b.outerStride(), b.rows(), b.cols(), v.data(), v.outerStride(),
                                        v.cols(), out.data(), out.outerStride());
#endif
  gemm(Op::Transpose, Op::None, 1.0f, b, v, 0.0f, out);
}

namespace {

// Row i of a bfloat16 matrix widened into `row` (k floats).
void widen_row(const Bfloat16Matrix& v, long i, float* row) {
  for (long j = 0; j < v.cols; ++j) {
    const std::uint32_t u = std::uint32_t(v.data[i * v.stride + j]) << 16;
    std::memcpy(row + j, &u, sizeof u);
  }
}

}  // namespace

void basis_times(const Bfloat16Matrix& v, ConstMatRef a, MatRef out) {
  check(v.cols == a.cols() && out.rows() == v.rows && out.cols() == a.rows(), "basis_times", v.rows, v.cols, a.rows(),
        a.cols(), out.rows(), out.cols());
#ifdef DRAPE_NN_X86
  if (detail::avx512_kernels() && v.rows > 0 && a.rows() > 0)
    return basis_times_avx512(v.data, v.stride, v.rows, v.cols, a.data(), a.outerStride(), a.rows(), out.data(),
                              out.outerStride());
#endif
  // Elsewhere one pass over V's rows, each widened into a buffer that stays in
  // L1 for its m dot products (dot_rows: AVX2 where the CPU has it).
  std::vector<float> row(static_cast<std::size_t>(v.cols));
  for (long i = 0; i < v.rows; ++i) {
    widen_row(v, i, row.data());
    dot_rows(row.data(), a.data(), static_cast<int>(v.cols), static_cast<int>(a.outerStride()), static_cast<int>(a.rows()),
             out.data() + i * out.outerStride());
  }
}

void basis_transpose_times(ConstMatRef b, const Bfloat16Matrix& v, MatRef out) {
  check(b.rows() == v.rows && out.rows() == b.cols() && out.cols() == v.cols, "basis_transpose_times", b.rows(),
        b.cols(), v.rows, v.cols, out.rows(), out.cols());
#ifdef DRAPE_NN_X86
  if (detail::avx512_kernels() && b.cols() > 0 && v.cols > 0)
    return basis_transpose_times_avx512(b.data(), b.outerStride(), b.rows(), b.cols(), v.data, v.stride, v.cols,
                                        out.data(), out.outerStride());
#endif
  std::vector<float> row(static_cast<std::size_t>(v.cols));
  for (long r = 0; r < out.rows(); ++r) out.row(r).setZero();
  for (long i = 0; i < v.rows; ++i) {
    widen_row(v, i, row.data());
    axpy_rows(row.data(), b.data() + i * b.outerStride(), static_cast<int>(v.cols), static_cast<int>(out.outerStride()),
              static_cast<int>(b.cols()), out.data());
  }
}

const char* basis_products_version() {
#ifdef DRAPE_NN_X86
  if (detail::avx512_kernels()) return "avx512f";
#endif
  return "portable";
}

}  // namespace drape::nn
