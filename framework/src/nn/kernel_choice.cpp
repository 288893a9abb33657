#include "kernel_choice.hpp"

#include <cstdlib>

namespace drape::nn::detail {

namespace {
bool portable_requested() { return std::getenv("DRAPE_PORTABLE_KERNELS") != nullptr; }
}  // namespace

bool avx512_kernels() {
#ifdef DRAPE_NN_X86
  static const bool yes = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                          __builtin_cpu_supports("avx512vl") && !portable_requested();
  return yes;
#else
  return false;
#endif
}

bool avx2_kernels() {
#ifdef DRAPE_NN_X86
  static const bool yes = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && !portable_requested();
  return yes;
#else
  return false;
#endif
}

}  // namespace drape::nn::detail
