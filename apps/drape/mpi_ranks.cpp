// drape::Ranks over MPI (OpenMPI), compiled with DRAPE_HAVE_MPI when CMake
// finds MPI; without it, only the check that no mpirun expects it.
#include "mpi_ranks.hpp"

#include "command.hpp"

#ifdef DRAPE_HAVE_MPI
#define OMPI_SKIP_MPICXX 1  // the C API only: the deprecated C++ bindings need libmpi_cxx
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace drape::cli {
namespace {

// The number of processes the launcher started, from the variables OpenMPI,
// MPICH/Hydra and Slurm's PMI put in every process's environment; 0 when none.
int launched_processes() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
    if (const char* v = std::getenv(name)) return std::atoi(v);
  return 0;
}

#ifdef DRAPE_HAVE_MPI
void check(int code, const char* what) {
  if (code == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  throw std::runtime_error(std::string("MPI: ") + what + " failed: " + std::string(text, static_cast<std::size_t>(length)));
}

class MpiRanks final : public Ranks {
 public:
  MpiRanks() {
    int provided = 0;
    // Only the main thread calls MPI; OpenMP threads compute between calls.
    check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
    check(MPI_Comm_rank(MPI_COMM_WORLD, &rank_), "MPI_Comm_rank");
    check(MPI_Comm_size(MPI_COMM_WORLD, &size_), "MPI_Comm_size");
  }
  ~MpiRanks() override { MPI_Finalize(); }
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  void all_gather(const float* mine, std::size_t count, float* all) const override {
    check(MPI_Allgather(mine, static_cast<int>(count), MPI_FLOAT, all, static_cast<int>(count), MPI_FLOAT, MPI_COMM_WORLD),
          "MPI_Allgather");
  }
  void all_gather(const double* mine, std::size_t count, double* all) const override {
    check(MPI_Allgather(mine, static_cast<int>(count), MPI_DOUBLE, all, static_cast<int>(count), MPI_DOUBLE, MPI_COMM_WORLD),
          "MPI_Allgather");
  }
  void all_gather(const std::uint8_t* mine, std::size_t count, std::uint8_t* all) const override {
    check(MPI_Allgather(mine, static_cast<int>(count), MPI_BYTE, all, static_cast<int>(count), MPI_BYTE, MPI_COMM_WORLD),
          "MPI_Allgather");
  }
  void barrier() const override { check(MPI_Barrier(MPI_COMM_WORLD), "MPI_Barrier"); }

 private:
  int rank_ = 0, size_ = 1;
};
#endif

}  // namespace

bool built_with_mpi() {
#ifdef DRAPE_HAVE_MPI
  return true;
#else
  return false;
#endif
}

std::unique_ptr<Ranks> mpi_ranks_if_launched() {
  const int launched = launched_processes();
  if (launched <= 0) return nullptr;
#ifdef DRAPE_HAVE_MPI
  return std::make_unique<MpiRanks>();
#else
  if (launched > 1)
    throw UsageError("started by mpirun as one of " + std::to_string(launched) +
                     " processes, but this drape was built without MPI (install libopenmpi-dev and rebuild): each "
                     "process would train the whole model on its own");
  return nullptr;
#endif
}

void refuse_parallel_launch(const std::string& command, const std::vector<std::string>& args) {
  // An option as the command's parser takes it: whole, with "=value", or
  // cut short to a prefix of it ("--dat", "--sh"; the parser takes any
  // unambiguous one, and an outside check's "--dat" got past a whole-name test).
  const auto has = [&](const std::string& flag) {
    return std::any_of(args.begin(), args.end(), [&](const std::string& a) {
      const std::string name = a.substr(0, a.find('='));
      return name == flag || (name.size() > 2 && name.rfind("--", 0) == 0 && flag.rfind(name, 0) == 0);
    });
  };
  const bool whole_set = (command == "generate" || (command == "optimize" && has("--data"))) && !has("--shard");
  if (!whole_set || has("--help") || has("-h")) return;
  if (const int launched = launched_processes(); launched > 1)
    throw UsageError("started by an MPI launcher as one of " + std::to_string(launched) + " processes, but drape " + command +
                     " is not MPI-parallel (drape train is): each process would make the whole set into the same "
                     "output. Run it once, or give each process its own shard (--shard i/" + std::to_string(launched) +
                     ", then drape dataset merge: scripts/cluster/, docs/cluster.md)");
}

void abort_all_ranks(int code) {
#ifdef DRAPE_HAVE_MPI
  MPI_Abort(MPI_COMM_WORLD, code);
#endif
  std::exit(code);
}

}  // namespace drape::cli
