#pragma once
// The BLAS's own threads. drape parallelises itself (over samples, batch
// parts, element loops), so both the network's products (nn/gemm.cpp) and
// CHOLMOD's supernodal factorisation (physics/sparse_cholesky.cpp) keep the
// BLAS on the calling thread.

namespace drape {

// Threads the BLAS may use, for the whole process (OpenBLAS, BLIS). Creating a
// CHOLMOD solver sets it to 1 (sparse_cholesky.cpp says why). Returns false
// when the BLAS linked offers no such control.
bool set_blas_threads(int threads);

}  // namespace drape
