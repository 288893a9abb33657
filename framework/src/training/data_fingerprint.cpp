// training_data_fingerprint (data_fingerprint.hpp).
#include "data_fingerprint.hpp"

#include <drape/fnv1a.hpp>
#include <drape/tensor.hpp>

#include <algorithm>

namespace drape {
namespace {

void add_samples(Fnv1a& f, const DatasetReader& reader, const std::vector<std::size_t>& rows) {
  const std::uint64_t count = rows.size();
  f.bytes(&count, sizeof count);
  constexpr std::size_t kChunk = 256;  // drapes read at once (991 vertices: 3 MB)
  for (std::size_t start = 0; start < rows.size(); start += kChunk) {
    const std::vector<std::size_t> chunk(rows.begin() + static_cast<std::ptrdiff_t>(start),
                                         rows.begin() + static_cast<std::ptrdiff_t>(std::min(rows.size(), start + kChunk)));
    for (const std::size_t r : chunk) {
      const std::uint64_t row = r;
      f.bytes(&row, sizeof row);
    }
    const Tensor g = reader.garment_vertices(chunk);
    f.bytes(g.data(), g.size() * sizeof(float));
  }
}

}  // namespace

std::string training_data_fingerprint(const DatasetReader& reader, const std::vector<std::size_t>& train,
                                      const std::vector<std::size_t>& val) {
  Fnv1a f;
  add_samples(f, reader, train);
  add_samples(f, reader, val);
  return f.hex();
}

}  // namespace drape
