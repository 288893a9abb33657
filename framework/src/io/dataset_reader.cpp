// DatasetReader: samples (all, or one split) as float tensors.
#include "dataset_internal.hpp"

#include <cmath>

namespace fs = std::filesystem;

namespace drape {

using namespace dataset_detail;

struct DatasetReader::Impl {
  h5::File file;

  // Rows `indices` of `dataset` stacked in that order into `out` (row_size
  // floats each). Consecutive indices are read with one call.
  template <class T>
  void gather(const char* dataset, const std::vector<std::size_t>& indices, std::size_t row_size, T* out) const {
    std::size_t k = 0;
    while (k < indices.size()) {
      std::size_t run = 1;
      while (k + run < indices.size() && indices[k + run] == indices[k] + run) ++run;
      file.read_rows(dataset, indices[k], run, out + k * row_size);
      k += run;
    }
  }
};

DatasetReader::DatasetReader(const fs::path& path) : impl_(std::make_unique<Impl>(Impl{h5::File::open(path)})) {
  layout_ = read_layout(impl_->file);
  split_ = impl_->file.read<std::int8_t>(kSplit);
  done_ = impl_->file.read<std::uint8_t>(kDone);
}

DatasetReader::~DatasetReader() = default;
DatasetReader::DatasetReader(DatasetReader&&) noexcept = default;

std::vector<std::size_t> DatasetReader::indices() const {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < done_.size(); ++i)
    if (done_[i]) out.push_back(i);
  return out;
}

std::vector<std::size_t> DatasetReader::indices(Split split) const {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < done_.size(); ++i)
    if (done_[i] && split_[i] == static_cast<std::int8_t>(split)) out.push_back(i);
  return out;
}

std::vector<std::size_t> DatasetReader::training_indices(double fraction) const {
  std::vector<std::size_t> out = indices(Split::Train);
  out.resize(static_cast<std::size_t>(std::ceil(fraction * static_cast<double>(out.size()))));
  return out;
}

namespace {

std::vector<bool> wanted_splits(const std::string& splits) {
  std::vector<bool> wanted(3, splits == "all");
  if (splits == "all") return wanted;
  std::size_t start = 0;
  while (start <= splits.size()) {
    const std::size_t comma = std::min(splits.find(',', start), splits.size());
    wanted[static_cast<std::size_t>(parse_split(splits.substr(start, comma - start)))] = true;
    start = comma + 1;
  }
  return wanted;
}

}  // namespace

void DatasetReader::check_splits(const std::string& splits) { wanted_splits(splits); }

std::vector<std::size_t> DatasetReader::indices(const std::string& splits) const {
  const std::vector<bool> wanted = wanted_splits(splits);
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < done_.size(); ++i)
    if (done_[i] && split_[i] >= 0 && split_[i] < 3 && wanted[static_cast<std::size_t>(split_[i])]) out.push_back(i);
  return out;
}

namespace {

void check_indices(const DatasetReader& reader, const std::vector<std::size_t>& indices, const fs::path& path) {
  for (std::size_t i : indices) {
    if (i >= reader.size())
      throw Error(path.string() + ": sample " + std::to_string(i) + " is out of range (the dataset holds " +
                  std::to_string(reader.size()) + ")");
    if (!reader.done()[i]) throw ConfigError(path.string() + ": sample " + std::to_string(i) + " was never written completely");
  }
}

}  // namespace

Tensor DatasetReader::body_params(const std::vector<std::size_t>& indices) const {
  check_indices(*this, indices, impl_->file.path());
  Tensor out(static_cast<int>(indices.size()), 1, layout_.body_params);
  impl_->gather(kParams, indices, static_cast<std::size_t>(layout_.body_params), out.data());
  return out;
}

Tensor DatasetReader::body_vertices(const std::vector<std::size_t>& indices) const {
  check_indices(*this, indices, impl_->file.path());
  if (!layout_.body_vertices_stored) {
    const std::string name = impl_->file.path().string();
    throw ConfigError(name + ": a slim dataset (the bodies' shape parameters without their vertices); rebuild the vertices with `drape dataset expand " +
                      name + " --out FULL.h5` and use that file");
  }
  Tensor out(static_cast<int>(indices.size()), layout_.body_vertices, 3);
  impl_->gather(kBodyVertices, indices, static_cast<std::size_t>(layout_.body_vertices) * 3, out.data());
  return out;
}

Tensor DatasetReader::garment_vertices(const std::vector<std::size_t>& indices) const {
  check_indices(*this, indices, impl_->file.path());
  Tensor out(static_cast<int>(indices.size()), layout_.garment_vertices, 3);
  impl_->gather(kGarmentVertices, indices, static_cast<std::size_t>(layout_.garment_vertices) * 3, out.data());
  return out;
}

std::vector<double> DatasetReader::stat(const std::string& name, const std::vector<std::size_t>& indices) const {
  if (std::find(layout_.stats.begin(), layout_.stats.end(), name) == layout_.stats.end())
    throw ConfigError(impl_->file.path().string() + ": no statistic '" + name + "'" + did_you_mean(name, layout_.stats));
  check_indices(*this, indices, impl_->file.path());
  std::vector<double> out(indices.size());
  impl_->gather(stat_path(name).c_str(), indices, 1, out.data());
  return out;
}

DatasetSample DatasetReader::sample(std::size_t index) const {
  DatasetSample s;
  s.body_params = Eigen::Map<const Eigen::VectorXf>(body_params({index}).data(), layout_.body_params);
  s.body_vertices = body_vertices({index}).mat(0);
  s.garment_vertices = garment_vertices({index}).mat(0);
  s.split = static_cast<Split>(split_[index]);
  for (const auto& name : layout_.stats) s.stats[name] = stat(name, {index})[0];
  return s;
}

std::vector<std::size_t> optimizer_results(const DatasetReader& reader, const std::vector<std::size_t>& indices) {
  if (!reader.layout().has_stat("separated")) return indices;
  const std::vector<double> separated = reader.stat("separated", indices);
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < indices.size(); ++i)
    if (separated[i] != 0.0) out.push_back(indices[i]);
  return out;
}

}  // namespace drape
