#pragma once
// The ranks of `mpirun -np N drape train ...` (drape/training/ranks.hpp over MPI).
#include <drape/training/ranks.hpp>

#include <memory>
#include <string>

namespace drape::cli {

// The MPI ranks when this process was started by mpirun (MPI initialised
// here, finalised when the object goes); null when it was not. A drape built
// without MPI that finds itself under an mpirun of several processes throws
// UsageError: each would train the whole model on its own.
std::unique_ptr<Ranks> mpi_ranks_if_launched();

// UsageError when this process is one of several an MPI launcher started
// and `command` is not MPI-parallel (only train is): each process would run
// the whole job on the same outputs (an outside check's mpirun -np 2 drape
// generate: rank 1 died on the output's lock, an empty .partial left).
void refuse_parallel_launch(const std::string& command);

// Ends every rank of the job with this exit code (after an error on one rank,
// which would leave the others waiting in a collective for ever).
[[noreturn]] void abort_all_ranks(int code);

// Whether this drape was built with MPI.
bool built_with_mpi();

}  // namespace drape::cli
