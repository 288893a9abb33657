// The BLAS's thread count, looked up at run time so that drape builds and runs
// against any BLAS: OpenBLAS exports openblas_set_num_threads, BLIS
// bli_thread_set_num_threads; the reference BLAS has no threads to limit.
#include <drape/nn/blas_threads.hpp>

#include <dlfcn.h>

#include <initializer_list>

namespace drape {

bool set_blas_threads(int threads) {
  using SetThreads = void (*)(int);
  for (const char* symbol : {"openblas_set_num_threads", "bli_thread_set_num_threads"}) {
    if (void* f = dlsym(RTLD_DEFAULT, symbol)) {
      reinterpret_cast<SetThreads>(f)(threads);
      return true;
    }
  }
  return false;
}

}  // namespace drape
