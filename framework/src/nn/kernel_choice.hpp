#pragma once
// Which hand-written vector kernels the nn building blocks run here (internal
// to framework/src/nn): chosen once per process from the CPU, and off with
// DRAPE_PORTABLE_KERNELS=1 (the portable paths, to compare or to get the same
// bits on every x86-64 CPU). basis_products, skinny_gemm and dot_rows ask here.
#if defined(__x86_64__) && defined(__GNUC__)
#define DRAPE_NN_X86 1
// Functions compiled for AVX-512 (F, BW, VL) in a file built for the baseline.
#define DRAPE_AVX512 __attribute__((target("avx512f,avx512bw,avx512vl")))
#endif

namespace drape::nn::detail {

// AVX-512 F, BW and VL, and not DRAPE_PORTABLE_KERNELS.
bool avx512_kernels();
// AVX2 and FMA, and not DRAPE_PORTABLE_KERNELS.
bool avx2_kernels();

}  // namespace drape::nn::detail
