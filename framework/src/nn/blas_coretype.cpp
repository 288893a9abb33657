// OpenBLAS picks its kernels for the CPU when it loads. Debian 12's OpenBLAS
// (0.3.21) does not know CPUs newer than itself and falls back to its SSE3
// "Prescott" kernels on them: on this project's Xeon (AVX-512, reported as a
// plain "Intel Xeon Processor" by its virtual machine) every product ran 2-3x
// slower than with the SkylakeX kernels it supports. Looked up at run time, so
// that drape builds and runs against any BLAS.
#include <drape/nn/gemm.hpp>

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>

namespace drape::nn {

const char* blas_corename() {
  using Corename = char* (*)();
  if (void* f = dlsym(RTLD_DEFAULT, "openblas_get_corename")) return reinterpret_cast<Corename>(f)();
  return "";
}

const char* better_blas_coretype() {
  if (std::getenv("OPENBLAS_CORETYPE")) return nullptr;  // the user's choice
  const char* core = blas_corename();
  if (std::strcmp(core, "Prescott") != 0 && std::strcmp(core, "prescott") != 0) return nullptr;
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw") &&
      __builtin_cpu_supports("avx512dq"))
    return "SkylakeX";
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "Haswell";
#endif
  return nullptr;
}

void reexec_with_native_blas(char** argv) {
  const char* core = better_blas_coretype();
  if (!core) return;
  setenv("OPENBLAS_CORETYPE", core, 1);
  execv("/proc/self/exe", argv);  // returns only on failure: carry on with the kernels there are
}

}  // namespace drape::nn
