#pragma once
// The processes of one data-parallel training started together (mpirun): each
// is a rank, 0..size-1, and every rank runs the same steps on its own part of
// every batch. The framework only needs the collective operations below; the
// drape program implements them with MPI when it was built with MPI
// (apps/drape/mpi_ranks.cpp), so the library itself never depends on MPI.
#include <cstddef>
#include <cstdint>

namespace drape {

class Ranks {
 public:
  virtual ~Ranks() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  // On every rank: each rank's `count` values of `mine` (the same count on
  // all), one rank after another in rank order, into `all` (size * count).
  virtual void all_gather(const float* mine, std::size_t count, float* all) const = 0;
  virtual void all_gather(const double* mine, std::size_t count, double* all) const = 0;
  // Bytes, copied unchanged (the ranks of one run are one binary on one machine type).
  virtual void all_gather(const std::uint8_t* mine, std::size_t count, std::uint8_t* all) const = 0;
  // Returns once every rank has called it.
  virtual void barrier() const = 0;
};

}  // namespace drape
