// DatasetWriter: one sample at a time into `<out>.partial`, resumable after a kill.
#include "dataset_internal.hpp"

#include <drape/io/atomic_file.hpp>
#include <drape/warnings.hpp>

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace drape {

using namespace dataset_detail;

struct DatasetWriter::Impl {
  h5::File file;
};

namespace {

// A statistic's stored value: NaN when the sample has none.
double stat_value(const DatasetSample& sample, const std::string& name) {
  const auto it = sample.stats.find(name);
  return it == sample.stats.end() ? std::nan("") : it->second;
}

// The CRC-32 of a sample's rows as `write` stores them (kSampleCrc): params,
// body vertices (when stored), pose (when posed), garment vertices, split,
// stats by name. Never 0, which marks a sample without one. By name, not in
// the layout's order: a resumed writer's layout is the file's (read_layout
// lists the stats as HDF5 does, alphabetically), the first run's the
// generator's, and a resume found every sample of a killed run changed.
std::int64_t sample_crc(const DatasetLayout& layout, const DatasetSample& sample) {
  uLong crc = crc32(0L, Z_NULL, 0);
  const auto add = [&](const auto* data, std::size_t count) {
    crc = crc32(crc, reinterpret_cast<const Bytef*>(data), static_cast<uInt>(count * sizeof(*data)));
  };
  add(sample.body_params.data(), static_cast<std::size_t>(sample.body_params.size()));
  if (layout.body_vertices_stored) add(sample.body_vertices.data(), static_cast<std::size_t>(sample.body_vertices.size()));
  if (!layout.pose_angles.empty()) add(sample.pose.data(), static_cast<std::size_t>(sample.pose.size()));
  add(sample.garment_vertices.data(), static_cast<std::size_t>(sample.garment_vertices.size()));
  const auto split = static_cast<std::int8_t>(sample.split);
  add(&split, 1);
  std::vector<std::string> names = layout.stats;
  std::sort(names.begin(), names.end());
  for (const auto& name : names) {
    const double value = stat_value(sample, name);
    add(&value, 1);
  }
  return crc == 0 ? 1 : static_cast<std::int64_t>(crc);
}

// Sample `index`'s rows as they read back from the file now (what sample_crc hashes).
DatasetSample stored_sample(const h5::File& file, const DatasetLayout& layout, std::size_t index) {
  DatasetSample sample;
  sample.body_params.resize(layout.body_params);
  file.read_rows(kParams, index, 1, sample.body_params.data());
  if (layout.body_vertices_stored) {
    sample.body_vertices.resize(layout.body_vertices, 3);
    file.read_rows(kBodyVertices, index, 1, sample.body_vertices.data());
  }
  if (!layout.pose_angles.empty()) {
    sample.pose.resize(static_cast<Eigen::Index>(layout.pose_angles.size()));
    file.read_rows(kPose, index, 1, sample.pose.data());
  }
  sample.garment_vertices.resize(layout.garment_vertices, 3);
  file.read_rows(kGarmentVertices, index, 1, sample.garment_vertices.data());
  std::int8_t split = 0;
  file.read_rows(kSplit, index, 1, &split);
  sample.split = static_cast<Split>(split);
  for (const auto& name : layout.stats) file.read_rows(stat_path(name), index, 1, &sample.stats[name]);
  return sample;
}

}  // namespace

fs::path DatasetWriter::partial_path(const fs::path& path) { return path.string() + ".partial"; }

DatasetWriter::DatasetWriter(const fs::path& path, const DatasetLayout& layout, const Options& options)
    : path_(path), layout_(layout), options_(options) {
  const fs::path partial = partial_path(path);
  std::error_code ec;
  if (fs::exists(path, ec))
    throw ConfigError(path.string() + ": already exists (a finished dataset); delete it to generate it again");
  if (fs::exists(partial, ec)) {
    // Resume. A partial file that does not open was damaged outside our control
    // (our writes never leave it unreadable): say so instead of guessing.
    h5::File file = [&] {
      try {
        return h5::File::open(partial, h5::Access::ReadWrite);
      } catch (const h5::FileInUse&) {
        throw;  // busy, not damaged: never advise deleting it
      } catch (const ConfigError& e) {
        throw ConfigError(std::string(e.what()) + "; cannot resume from it, delete it to start over");
      }
    }();
    const DatasetLayout have = read_layout(file);
    // How the samples are made must be the same too: another generator would
    // fill the missing rows with other drapes while the file records the
    // first run's (made_difference).
    if (const std::string difference = layout_difference(have, layout); !difference.empty())
      throw ResumeRefused(partial.string() + ": cannot resume, " + difference + "; delete it to start over");
    if (const std::string difference = made_difference(have, layout); !difference.empty())
      throw ResumeRefused(partial.string() + ": cannot resume, " + difference + "; run it as it was begun, or delete it to "
                        "start over");
    layout_ = have;  // keeps `created` and the extra attributes of the first run
    impl_ = std::make_unique<Impl>(Impl{std::move(file)});
    resumed_ = true;
    check_kept_samples();
  } else {
    if (layout.created.empty()) layout_.created = now_utc();
    // Created whole in a temporary file, then renamed: `<out>.partial` exists
    // only once every dataset and attribute is in it.
    write_atomically(partial, [&](const fs::path& tmp) {
      h5::File file = h5::File::create(tmp);
      create_layout(file, layout_);
      file.create<std::int64_t>(kSampleCrc, {layout_.samples}, {.preallocate = true, .fill = 0.0});
      file.flush(options_.sync);
      file.close();
    });
    impl_ = std::make_unique<Impl>(Impl{h5::File::open(partial, h5::Access::ReadWrite)});
  }
  done_ = impl_->file.read<std::uint8_t>(kDone);
}

DatasetWriter::~DatasetWriter() = default;

void DatasetWriter::write(std::size_t index, const DatasetSample& sample) {
  if (!impl_) throw Error(path_.string() + ": the dataset writer is closed");
  const std::string where = partial_path(path_).string() + ": sample " + std::to_string(index);
  if (index >= layout_.samples)
    throw Error(where + " is out of range (the dataset holds " + std::to_string(layout_.samples) + ")");
  check_sample(layout_, sample, where);
  h5::File& file = impl_->file;
  const std::uint8_t not_done = 0, done = 1;
  if (done_[index]) {
    // Rewriting a finished sample: unmark it first, so a kill halfway through
    // leaves it "not done" rather than done with mixed contents.
    file.write_rows(kDone, index, 1, &not_done);
    file.flush(options_.sync);
    done_[index] = 0;
  }
  file.write_rows(kParams, index, 1, sample.body_params.data());
  if (layout_.body_vertices_stored) file.write_rows(kBodyVertices, index, 1, sample.body_vertices.data());
  if (!layout_.pose_angles.empty()) file.write_rows(kPose, index, 1, sample.pose.data());
  file.write_rows(kGarmentVertices, index, 1, sample.garment_vertices.data());
  const auto split = static_cast<std::int8_t>(sample.split);
  file.write_rows(kSplit, index, 1, &split);
  for (const auto& name : layout_.stats) {
    const double value = stat_value(sample, name);
    file.write_rows(stat_path(name), index, 1, &value);
  }
  if (file.exists(kSampleCrc)) {
    const std::int64_t crc = sample_crc(layout_, sample);
    file.write_rows(kSampleCrc, index, 1, &crc);
  }
  // Everything above reaches the file before the flag that says it is valid.
  file.flush(options_.sync);
  file.write_rows(kDone, index, 1, &done);
  file.flush(options_.sync);
  done_[index] = 1;
}

void DatasetWriter::check_kept_samples() {
  h5::File& file = impl_->file;
  done_ = file.read<std::uint8_t>(kDone);
  if (!file.exists(kSampleCrc)) return;  // begun by a writer without checksums: kept as it is
  const std::vector<std::int64_t> written = file.read<std::int64_t>(kSampleCrc);
  std::vector<std::size_t> changed;
  // A checksum of 0 is one never written (sample_crc gives 1 for a CRC of
  // 0, and the file was created with this dataset): a sample flagged done
  // without it was never written, whatever its flag says (a flipped bit of
  // /done kept an all-zero drape, sealed into a "complete" file).
  for (std::size_t i = 0; i < done_.size() && i < written.size(); ++i)
    if (done_[i] && (written[i] == 0 || sample_crc(layout_, stored_sample(file, layout_, i)) != written[i])) changed.push_back(i);
  if (changed.empty()) return;
  const std::uint8_t not_done = 0;
  std::string which;
  for (std::size_t k = 0; k < changed.size(); ++k) {
    file.write_rows(kDone, changed[k], 1, &not_done);
    done_[changed[k]] = 0;
    if (k < 8) which += (k ? ", " : "") + std::to_string(changed[k]);
  }
  file.flush(options_.sync);
  warn(partial_path(path_).string() + ": " + std::to_string(changed.size()) + " of the samples the interrupted run "
       "wrote no longer read back as written (the file was changed since: sample" + (changed.size() > 1 ? "s " : " ") +
       which + (changed.size() > 8 ? ", ..." : "") + "); they are made again");
}

std::vector<std::size_t> DatasetWriter::missing() const {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < done_.size(); ++i)
    if (!done_[i]) out.push_back(i);
  return out;
}

std::size_t DatasetWriter::done_count() const {
  std::size_t n = 0;
  for (auto d : done_) n += d != 0;
  return n;
}

void DatasetWriter::close() {
  if (!impl_) return;
  impl_->file.close();
  impl_.reset();
}

void DatasetWriter::finish() {
  const std::size_t missing_count = layout_.samples - done_count();
  if (missing_count)
    throw Error(partial_path(path_).string() + ": cannot finish, " + std::to_string(missing_count) + " of " +
                std::to_string(layout_.samples) + " samples are not written yet");
  if (impl_) impl_->file.flush(true);
  close();
  std::error_code ec;
  // <out> is never overwritten (checked at the start too): a file that
  // appeared there meanwhile was made by something that took no lock (an
  // outside check's `model domain --out` of the same name, before it took
  // one), and is kept, the finished dataset beside it.
  if (fs::exists(path_, ec))
    throw Error(path_.string() + " appeared while the dataset was made (written by another program?), and is not "
                "replaced: the finished dataset is " + partial_path(path_).string() + "; move one of them and rename it");
  fs::rename(partial_path(path_), path_, ec);
  if (ec) throw Error(path_.string() + ": cannot rename the finished dataset into place: " + ec.message());
}

}  // namespace drape
