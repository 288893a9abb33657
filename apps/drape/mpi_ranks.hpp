#pragma once
// The ranks of `mpirun -np N drape train ...` (drape/training/ranks.hpp over MPI).
#include <drape/training/ranks.hpp>

#include <memory>
#include <string>
#include <vector>

namespace drape::cli {

// The MPI ranks when this process was started by mpirun (MPI initialised
// here, finalised when the object goes); null when it was not. A drape built
// without MPI that finds itself under an mpirun of several processes throws
// UsageError: each would train the whole model on its own.
std::unique_ptr<Ranks> mpi_ranks_if_launched();

// UsageError when this process is one of several an MPI launcher started to
// make one dataset whole: `generate` or `optimize --data` without --shard
// (only train is MPI-parallel). Each process would make the whole set into
// the same output (an outside check's mpirun -np 2 drape generate: rank 1
// died on the output's lock, an empty .partial left). Every other command,
// and these with a shard each (srun -n N ... --shard $SLURM_PROCID/N), runs
// as one process would.
void refuse_parallel_launch(const std::string& command, const std::vector<std::string>& args);

// Ends every rank of the job with this exit code (after an error on one rank,
// which would leave the others waiting in a collective for ever).
[[noreturn]] void abort_all_ranks(int code);

// Whether this drape was built with MPI.
bool built_with_mpi();

}  // namespace drape::cli
