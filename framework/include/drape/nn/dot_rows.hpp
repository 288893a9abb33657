#pragma once
// Dot products of one long row against a few others, the inner loop of a
// matrix-times-few-vectors product that is too thin for a blocked GEMM (the
// spectral branch at one body: 3505 rows x 1000 x 3). The build targets plain
// x86-64 (SSE2) so that results do not depend on the machine; this one kernel
// also has an AVX2+FMA version chosen at run time when the CPU has it, because
// here it is the difference between 2 ms and under 1 ms per body.
namespace drape::nn {

// out[r] = sum_j row[j] * others[r * stride + j] for r < count.
void dot_rows(const float* row, const float* others, int n, int stride, int count, float* out);

// others[r * stride + j] += scale[r] * row[j] for r < count, j < n.
void axpy_rows(const float* row, const float* scale, int n, int stride, int count, float* others);

// Which version runs here: "avx2+fma" or "portable" (also forced by setting
// DRAPE_PORTABLE_KERNELS=1, for results that are the same on every x86-64).
const char* dot_rows_version();

namespace detail {  // the portable versions, callable directly so that tests cover both
void dot_rows_portable(const float* row, const float* others, int n, int stride, int count, float* out);
void axpy_rows_portable(const float* row, const float* scale, int n, int stride, int count, float* others);
}  // namespace detail

}  // namespace drape::nn
