#pragma once
// The ranks of `mpirun -np N drape train ...` (drape/training/ranks.hpp over MPI).
#include <drape/training/ranks.hpp>

#include <memory>

namespace drape::cli {

// The MPI ranks when this process was started by mpirun (MPI initialised
// here, finalised when the object goes); null when it was not. A drape built
// without MPI that finds itself under an mpirun of several processes throws
// UsageError: each would train the whole model on its own.
std::unique_ptr<Ranks> mpi_ranks_if_launched();

// Ends every rank of the job with this exit code (after an error on one rank,
// which would leave the others waiting in a collective for ever).
[[noreturn]] void abort_all_ranks(int code);

// Whether this drape was built with MPI.
bool built_with_mpi();

}  // namespace drape::cli
