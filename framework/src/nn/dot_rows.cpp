#include <drape/nn/dot_rows.hpp>

#include "kernel_choice.hpp"

#ifdef DRAPE_NN_X86
#include <immintrin.h>
#endif

namespace drape::nn {
namespace detail {

void dot_rows_portable(const float* row, const float* others, int n, int stride, int count, float* out) {
  for (int r = 0; r < count; ++r) {
    const float* o = others + static_cast<long>(r) * stride;
    // Four partial sums: the compiler may not reorder a float reduction itself.
    float s0 = 0, s1 = 0, s2 = 0, s3 = 0;
    int j = 0;
    for (; j + 4 <= n; j += 4) {
      s0 += row[j] * o[j];
      s1 += row[j + 1] * o[j + 1];
      s2 += row[j + 2] * o[j + 2];
      s3 += row[j + 3] * o[j + 3];
    }
    for (; j < n; ++j) s0 += row[j] * o[j];
    out[r] = (s0 + s1) + (s2 + s3);
  }
}

void axpy_rows_portable(const float* row, const float* scale, int n, int stride, int count, float* others) {
  for (int r = 0; r < count; ++r) {
    float* o = others + static_cast<long>(r) * stride;
    const float a = scale[r];
    for (int j = 0; j < n; ++j) o[j] += a * row[j];
  }
}

}  // namespace detail

namespace {
using detail::axpy_rows_portable;
using detail::dot_rows_portable;

#ifdef DRAPE_NN_X86
__attribute__((target("avx2,fma"))) float hsum(__m256 v) {
  const __m128 s = _mm_add_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
  const __m128 t = _mm_add_ps(s, _mm_movehl_ps(s, s));
  return _mm_cvtss_f32(_mm_add_ss(t, _mm_shuffle_ps(t, t, 1)));
}

__attribute__((target("avx2,fma"))) void dot_rows_avx2(const float* row, const float* others, int n, int stride,
                                                       int count, float* out) {
  for (int r = 0; r < count; ++r) {
    const float* o = others + static_cast<long>(r) * stride;
    // Four independent chains hide the FMA latency (one chain runs at a quarter of the rate).
    __m256 a0 = _mm256_setzero_ps(), a1 = _mm256_setzero_ps(), a2 = _mm256_setzero_ps(), a3 = _mm256_setzero_ps();
    int j = 0;
    for (; j + 32 <= n; j += 32) {
      a0 = _mm256_fmadd_ps(_mm256_loadu_ps(row + j), _mm256_loadu_ps(o + j), a0);
      a1 = _mm256_fmadd_ps(_mm256_loadu_ps(row + j + 8), _mm256_loadu_ps(o + j + 8), a1);
      a2 = _mm256_fmadd_ps(_mm256_loadu_ps(row + j + 16), _mm256_loadu_ps(o + j + 16), a2);
      a3 = _mm256_fmadd_ps(_mm256_loadu_ps(row + j + 24), _mm256_loadu_ps(o + j + 24), a3);
    }
    for (; j + 8 <= n; j += 8) a0 = _mm256_fmadd_ps(_mm256_loadu_ps(row + j), _mm256_loadu_ps(o + j), a0);
    float s = hsum(_mm256_add_ps(_mm256_add_ps(a0, a1), _mm256_add_ps(a2, a3)));
    for (; j < n; ++j) s += row[j] * o[j];
    out[r] = s;
  }
}

__attribute__((target("avx2,fma"))) void axpy_rows_avx2(const float* row, const float* scale, int n, int stride,
                                                        int count, float* others) {
  for (int r = 0; r < count; ++r) {
    float* o = others + static_cast<long>(r) * stride;
    const __m256 a = _mm256_set1_ps(scale[r]);
    int j = 0;
    for (; j + 8 <= n; j += 8) _mm256_storeu_ps(o + j, _mm256_fmadd_ps(a, _mm256_loadu_ps(row + j), _mm256_loadu_ps(o + j)));
    for (; j < n; ++j) o[j] += scale[r] * row[j];
  }
}

#endif

}  // namespace

void dot_rows(const float* row, const float* others, int n, int stride, int count, float* out) {
#ifdef DRAPE_NN_X86
  if (detail::avx2_kernels()) return dot_rows_avx2(row, others, n, stride, count, out);
#endif
  dot_rows_portable(row, others, n, stride, count, out);
}

void axpy_rows(const float* row, const float* scale, int n, int stride, int count, float* others) {
#ifdef DRAPE_NN_X86
  if (detail::avx2_kernels()) return axpy_rows_avx2(row, scale, n, stride, count, others);
#endif
  axpy_rows_portable(row, scale, n, stride, count, others);
}

const char* dot_rows_version() {
#ifdef DRAPE_NN_X86
  if (detail::avx2_kernels()) return "avx2+fma";
#endif
  return "portable";
}

}  // namespace drape::nn
