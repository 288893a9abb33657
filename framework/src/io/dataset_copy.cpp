// copy_done_samples (io/dataset_copy.hpp).
#include <drape/io/dataset_copy.hpp>

#include <algorithm>
#include <map>
#include <string>

namespace drape {

void copy_done_samples(const DatasetReader& reader, DatasetWriter& writer, const SampleChange& change,
                       const std::function<void()>& done) {
  const std::vector<std::size_t> rows = reader.indices();
  constexpr std::size_t kSlice = 64;
  for (std::size_t first = 0; first < rows.size(); first += kSlice) {
    const std::vector<std::size_t> slice(rows.begin() + static_cast<std::ptrdiff_t>(first),
                                         rows.begin() + static_cast<std::ptrdiff_t>(std::min(rows.size(), first + kSlice)));
    const Tensor garments = reader.garment_vertices(slice), params = reader.body_params(slice);
    std::map<std::string, std::vector<double>> stats;
    for (const std::string& name : reader.layout().stats) stats[name] = reader.stat(name, slice);
    std::vector<DatasetSample> samples(slice.size());
    for (std::size_t k = 0; k < slice.size(); ++k) {
      const int i = static_cast<int>(k);
      DatasetSample& s = samples[k];
      s.body_params = params.mat(i).row(0).transpose();
      s.garment_vertices = garments.mat(i);
      s.split = static_cast<Split>(reader.splits()[slice[k]]);
      for (const auto& [name, values] : stats) s.stats[name] = values[k];
    }
    change(slice, samples);
    for (std::size_t k = 0; k < slice.size(); ++k) {
      writer.write(first + k, samples[k]);
      if (done) done();
    }
  }
}

}  // namespace drape
