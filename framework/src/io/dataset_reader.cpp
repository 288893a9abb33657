// DatasetReader: samples (all, or one split) as float tensors, from one file
// or the files of a glob pattern read as one; slim files' bodies rebuilt;
// A-pose files read with posed ones at each body's rest angles.
#include "dataset_internal.hpp"

#include <drape/bodies/body.hpp>
#include <drape/bodies/garment_skinning.hpp>
#include <drape/bodies/posed_body.hpp>
#include <drape/io/shipped_files.hpp>

#include <glob.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <exception>
#include <mutex>
#include <unordered_map>

namespace fs = std::filesystem;

namespace drape {

using namespace dataset_detail;

namespace {

// One file of the dataset: its rows are the dataset's first .. first + rows - 1.
struct Part {
  h5::File file;
  std::size_t first = 0, rows = 0;
  bool bodies = true;  // false: a slim file, bodies rebuilt
  bool witness = false;  // a slim file with the witness of its bodies (checked as they are rebuilt)
  bool posed = true;   // false: an A-pose file read with posed ones (its bodies at their rest angles)
};

// The files matching a glob pattern, sorted by name (glob sorts); {a,b}
// alternatives expand in their order, so one pattern names several folders.
std::vector<fs::path> glob_files(const std::string& pattern) {
  glob_t g{};
  std::vector<fs::path> out;
  if (glob(pattern.c_str(), GLOB_BRACE, nullptr, &g) == 0)
    for (std::size_t i = 0; i < g.gl_pathc; ++i) out.emplace_back(g.gl_pathv[i]);
  globfree(&g);
  return out;
}

}  // namespace

struct DatasetReader::Impl {
  std::vector<fs::path> files;
  std::vector<Part> parts;
  std::string name;  // the path or pattern given, for messages
  // Bodies rebuilt for slim parts, by dataset row; made once each (20-90 ms), kept. The mutex guards both.
  mutable std::mutex rebuild_mutex;
  mutable std::unique_ptr<BodyModel> body_model;
  mutable std::unordered_map<std::size_t, std::vector<float>> rebuilt;
  // Posing data by dataset row (posing()), under rebuild_mutex too.
  struct PosingRow {
    std::vector<float> unposed, transforms, angles;
  };
  mutable std::unordered_map<std::size_t, PosingRow> posing;

  std::size_t part_of(std::size_t row) const {
    auto it = std::upper_bound(parts.begin(), parts.end(), row, [](std::size_t r, const Part& p) { return r < p.first; });
    return static_cast<std::size_t>(it - parts.begin()) - 1;
  }

  // Rows `indices` of `dataset` stacked in that order into `out` (row_size
  // values each). Consecutive indices within one file are read with one call.
  template <class T>
  void gather(const char* dataset, const std::vector<std::size_t>& indices, std::size_t row_size, T* out) const {
    std::size_t k = 0;
    while (k < indices.size()) {
      const Part& part = parts[part_of(indices[k])];
      std::size_t run = 1;
      while (k + run < indices.size() && indices[k + run] == indices[k] + run && indices[k + run] < part.first + part.rows) ++run;
      part.file.read_rows(dataset, indices[k] - part.first, run, out + k * row_size);
      k += run;
    }
  }

  // Rebuilds the bodies of `rows` (slim rows) not rebuilt yet, in parallel; then rebuilt.at(row) holds each.
  void rebuild(const std::vector<std::size_t>& rows, const DatasetLayout& layout) const;

  // An exception may not leave an OpenMP region (it ends the program): each
  // row's failure is kept, and the first one thrown after the loop as bad
  // input (exit 2) naming the file and the sample whose stored shape or pose
  // the body model refused (NaN, a weight outside its range, an unknown angle).
  void rethrow_row_failure(const std::vector<std::exception_ptr>& failures, const std::vector<std::size_t>& rows) const {
    for (std::size_t k = 0; k < failures.size(); ++k) {
      if (!failures[k]) continue;
      const Part& part = parts[part_of(rows[k])];
      try {
        std::rethrow_exception(failures[k]);
      } catch (const std::exception& e) {
        throw ConfigError(part.file.path().string() + ": sample " + std::to_string(rows[k] - part.first) +
                          ": its body cannot be made from the stored shape and pose: " + e.what());
      }
    }
  }

  // The stored witnesses of those of `rows` whose file keeps one, read in
  // runs (gather): witness_size values each; at[k] is row k's offset in
  // them, -1 for a row without.
  std::vector<double> witnesses(const std::vector<std::size_t>& rows, std::size_t witness_size,
                                std::vector<std::ptrdiff_t>& at) const {
    std::vector<std::size_t> kept;
    at.assign(rows.size(), -1);
    for (std::size_t k = 0; k < rows.size(); ++k)
      if (parts[part_of(rows[k])].witness) at[k] = static_cast<std::ptrdiff_t>(kept.size() * witness_size), kept.push_back(rows[k]);
    std::vector<double> out(kept.size() * witness_size);
    gather(kBodyWitness, kept, witness_size, out.data());
    return out;
  }

};

void DatasetReader::Impl::rebuild(const std::vector<std::size_t>& rows, const DatasetLayout& layout) const {
  std::vector<std::size_t> todo;
  for (std::size_t row : rows)
    if (!rebuilt.count(row)) todo.push_back(row);
  std::sort(todo.begin(), todo.end());  // a batch may name a row twice: rebuilt once
  todo.erase(std::unique(todo.begin(), todo.end()), todo.end());
  if (todo.empty()) return;
  if (!body_model) body_model = dataset_body_model(nullptr, layout, parts[part_of(todo.front())].file.path().string());
  const std::size_t p = static_cast<std::size_t>(layout.body_params);
  const std::size_t a = layout.pose_angles.size();
  std::vector<float> params(todo.size() * p), poses(todo.size() * a);
  std::vector<bool> posed(todo.size());
  for (std::size_t k = 0; k < todo.size(); ++k) {  // HDF5 reads stay on this thread
    const Part& part = parts[part_of(todo[k])];
    part.file.read_rows(kParams, todo[k] - part.first, 1, params.data() + k * p);
    posed[k] = part.posed;  // every part is A-pose when the layout has no angles
    if (posed[k]) part.file.read_rows(kPose, todo[k] - part.first, 1, poses.data() + k * a);
  }
  const std::vector<std::string> at_rest;  // an A-pose file's row: its body as stored, unposed
  // A body is ~20-90 ms of the body model's solve and the model is const: one body per thread.
  std::vector<std::vector<float>> bodies(todo.size());
  std::vector<std::exception_ptr> failures(todo.size());
  const auto n = static_cast<std::ptrdiff_t>(todo.size());
#pragma omp parallel for schedule(dynamic)
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    try {
      const std::vector<float> one(params.begin() + k * static_cast<std::ptrdiff_t>(p), params.begin() + (k + 1) * static_cast<std::ptrdiff_t>(p));
      const std::vector<float> pose(poses.begin() + k * static_cast<std::ptrdiff_t>(a), poses.begin() + (k + 1) * static_cast<std::ptrdiff_t>(a));
      bodies[static_cast<std::size_t>(k)] =
          rebuilt_bodies(*body_model, one, 1, p, posed[static_cast<std::size_t>(k)] ? layout.pose_angles : at_rest, pose);
    } catch (...) {
      failures[static_cast<std::size_t>(k)] = std::current_exception();
    }
  }
  rethrow_row_failure(failures, todo);
  // Each body checked against the witness of the one its drape was simulated on.
  std::vector<std::ptrdiff_t> at;
  const std::vector<double> stored = witnesses(todo, witness_blocks(layout.body_vertices) * 4, at);
  for (std::size_t k = 0; k < todo.size(); ++k) {
    if (at[k] < 0) continue;
    const Part& part = parts[part_of(todo[k])];
    if (const std::string refused = not_the_simulated_body(part.file.path().string(), todo[k] - part.first, bodies[k].data(),
                                                           layout.body_vertices, stored.data() + at[k]);
        !refused.empty())
      throw ConfigError(refused);
  }
  for (std::size_t k = 0; k < todo.size(); ++k) rebuilt[todo[k]] = std::move(bodies[k]);
}

namespace {

// A glob pattern, not a file: no file of that name, and glob characters in it.
bool is_pattern(const fs::path& path_or_pattern) {
  std::error_code ec;
  return !fs::exists(path_or_pattern, ec) && path_or_pattern.string().find_first_of("*?[{") != std::string::npos;
}

}  // namespace

std::vector<fs::path> dataset_inputs(const fs::path& path_or_pattern) {
  try {
    return dataset_files(path_or_pattern);
  } catch (const Error&) {
    return {};  // the reader names what is missing, later
  }
}

std::vector<fs::path> dataset_files(const fs::path& path_or_pattern) {
  std::error_code ec;
  const std::string text = path_or_pattern.string();
  if (fs::exists(path_or_pattern, ec)) return {path_or_pattern};
  if (!is_pattern(path_or_pattern)) {
    const fs::path shipped = locate_shipped_file(path_or_pattern);  // datasets/... from a build tree
    if (!shipped.empty()) return {shipped};
    // Only its unfinished file: a generation running or interrupted.
    if (const fs::path partial = DatasetWriter::partial_path(path_or_pattern); fs::exists(partial, ec))
      throw ConfigError(text + ": no such file, but " + partial.string() +
                        " is there: a generation still running or interrupted (rerun it to finish; its done samples "
                        "read from the .partial file as they are)");
    return {path_or_pattern};  // h5's "no such file"
  }
  std::vector<fs::path> files = glob_files(text);
  // (A pattern such as 'q.h5*' also matches drape's lock files, which hold no dataset.)
  files.erase(std::remove_if(files.begin(), files.end(), [](const fs::path& f) { return f.extension() == ".lock"; }),
              files.end());
  if (files.empty())
    for (const auto& dir : shipped_data_dirs())
      if (!path_or_pattern.is_absolute() && (files = glob_files((dir / path_or_pattern).string()), !files.empty())) break;
  if (files.empty()) throw ConfigError(text + ": no dataset file matches this pattern");
  return files;
}

std::string dataset_name(const fs::path& path_or_pattern) {
  return is_pattern(path_or_pattern) ? path_or_pattern.string() : path_or_pattern.filename().string();
}

const std::string& DatasetReader::name() const { return impl_->name; }

DatasetReader::DatasetReader(const fs::path& path) : impl_(std::make_unique<Impl>()) {
  impl_->name = path.string();
  impl_->files = dataset_files(path);
  // The size charts of the files that have one, joined as a merge joins them
  // (a file made before sizes were added to the chart, read with one made
  // after): a model trained on them knows every size.
  std::optional<SizeTable> size_chart;
  for (const auto& file : impl_->files) {
    Part part{h5::File::open(file)};
    DatasetLayout layout = read_layout(part.file);
    part.first = layout_.samples;
    part.rows = layout.samples;
    part.bodies = layout.body_vertices_stored;
    part.witness = !part.bodies && part.file.exists(kBodyWitness);
    if (part.witness) check_witness_shape(part.file, layout);
    part.posed = !layout.pose_angles.empty();
    if (impl_->parts.empty()) {
      layout_ = layout;
    } else {
      // Files read as one must agree as a merge requires (sizes, stats, scene,
      // template), or be A-pose and posed drapes of one scene (rest_pose_mix).
      DatasetLayout same = layout;
      same.samples = layout_.samples;
      same.body_vertices_stored = layout_.body_vertices_stored;
      if (const std::string d = layout_difference(layout_, same); !d.empty()) {
        if (const std::string m = rest_pose_mix_difference(layout_, same); !m.empty())
          throw ConfigError(file.string() + ": cannot be read as one dataset with " + impl_->files.front().string() + ": " + d +
                            (m == d ? "" : " (an A-pose file is read with posed ones when only their solvers differ; "
                                           "here " + m + ")"));
        mixed_poses_ = true;
        if (layout_.pose_angles.empty()) {  // the posed files' angles and scene describe the whole
          layout_.pose_angles = layout.pose_angles;
          layout_.scene = layout.scene;
        }
      }
      layout_.samples += layout.samples;
      layout_.body_vertices_stored = layout_.body_vertices_stored && layout.body_vertices_stored;
    }
    join_size_chart(size_chart, layout, file.string());
    const std::vector<std::int8_t> split = part.file.read<std::int8_t>(kSplit);
    const std::vector<std::uint8_t> done = part.file.read<std::uint8_t>(kDone);
    // A split code the format does not have (an edit by hand) put the sample
    // in no split: eval then said "the all split has no samples".
    for (std::size_t i = 0; i < split.size() && i < done.size(); ++i)
      if (done[i] && (split[i] < 0 || split[i] > 2))
        throw ConfigError(file.string() + ": sample " + std::to_string(i) + " has split code " + std::to_string(split[i]) +
                          " in " + kSplit + " (0 train, 1 val, 2 test): the file was edited or is damaged");
    split_.insert(split_.end(), split.begin(), split.end());
    done_.insert(done_.end(), done.begin(), done.end());
    impl_->parts.push_back(std::move(part));
  }
  if (size_chart) layout_.attributes["size_chart"] = size_chart->to_text();
}

DatasetReader::~DatasetReader() = default;
DatasetReader::DatasetReader(DatasetReader&&) noexcept = default;

const std::vector<fs::path>& DatasetReader::files() const { return impl_->files; }

std::size_t DatasetReader::witnessed_files() const {
  return static_cast<std::size_t>(std::count_if(impl_->parts.begin(), impl_->parts.end(), [](const Part& p) { return p.witness; }));
}

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
    try {
      wanted[static_cast<std::size_t>(parse_split(splits.substr(start, comma - start)))] = true;
    } catch (const ConfigError& e) {  // (a list of splits also takes `all`, which one split is not)
      throw ConfigError(std::string(e.what()) + "; a list of splits joins train, val and test with commas, or is all");
    }
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

// A sample with a NaN or inf among `what` (an edit by hand: a simulation
// never stores one), named with its file: a body's NaN was trained on until
// "the training loss is nan (try a smaller --lr)", a shape parameter's was
// taken silently into the model's domain.
static void check_finite(const Tensor& rows, const std::vector<std::size_t>& indices, const DatasetReader::Impl& impl,
                  const std::string& what);
// And for vertices (`what` a coordinate): none beyond a thousand kilometres (a flipped
// exponent's 1e30 was trained on to a loss of 1e27 and measured as an ME of
// 2e27 cm: an outside check), and not every vertex at the origin (a row
// marked done that was never written holds HDF5's fill value, zeros: its
// training loss five times the others', its potential inf).
static void check_vertices(const Tensor& rows, const std::vector<std::size_t>& indices, const DatasetReader::Impl& impl,
                           const std::string& what);

Tensor DatasetReader::body_params(const std::vector<std::size_t>& indices) const {
  check_indices(*this, indices, fs::path(impl_->name));
  Tensor out(static_cast<int>(indices.size()), 1, layout_.body_params);
  impl_->gather(kParams, indices, static_cast<std::size_t>(layout_.body_params), out.data());
  check_finite(out, indices, *impl_, "body shape parameter");
  return out;
}

Tensor DatasetReader::body_vertices(const std::vector<std::size_t>& indices) const {
  check_indices(*this, indices, impl_->name);
  const std::size_t row_size = static_cast<std::size_t>(layout_.body_vertices) * 3;
  Tensor out(static_cast<int>(indices.size()), layout_.body_vertices, 3);
  if (layout_.body_vertices_stored) {
    impl_->gather(kBodyVertices, indices, row_size, out.data());
    check_vertices(out, indices, *impl_, "body coordinate");
    return out;
  }
  // Some file is slim: stored rows read as they are, the others rebuilt (once each).
  std::vector<std::size_t> slim;
  for (std::size_t row : indices)
    if (!impl_->parts[impl_->part_of(row)].bodies) slim.push_back(row);
  const std::lock_guard<std::mutex> lock(impl_->rebuild_mutex);
  impl_->rebuild(slim, layout_);
  for (std::size_t k = 0; k < indices.size(); ++k) {
    if (impl_->parts[impl_->part_of(indices[k])].bodies) {
      impl_->gather(kBodyVertices, {indices[k]}, row_size, out.data() + k * row_size);
    } else {
      const std::vector<float>& body = impl_->rebuilt.at(indices[k]);
      std::copy(body.begin(), body.end(), out.data() + k * row_size);
    }
  }
  check_vertices(out, indices, *impl_, "body coordinate");
  return out;
}

Tensor DatasetReader::garment_vertices(const std::vector<std::size_t>& indices) const {
  check_indices(*this, indices, fs::path(impl_->name));
  Tensor out(static_cast<int>(indices.size()), layout_.garment_vertices, 3);
  impl_->gather(kGarmentVertices, indices, static_cast<std::size_t>(layout_.garment_vertices) * 3, out.data());
  // (Named here, with its file, not as "metrics: the ground truth has a
  // non-finite coordinate" further on.)
  check_vertices(out, indices, *impl_, "garment coordinate");
  return out;
}

void check_finite(const Tensor& rows, const std::vector<std::size_t>& indices, const DatasetReader::Impl& impl,
                  const std::string& what) {
  for (std::size_t k = 0; k < indices.size(); ++k)
    if (!rows.mat(static_cast<int>(k)).allFinite())
      throw ConfigError(impl.files[impl.part_of(indices[k])].string() + ": sample " + std::to_string(indices[k]) +
                        " has a non-finite " + what + " (NaN or inf): the file was edited or is damaged");
}

void check_vertices(const Tensor& rows, const std::vector<std::size_t>& indices, const DatasetReader::Impl& impl,
                    const std::string& what) {
  check_finite(rows, indices, impl, what);
  // m: a drape is made near the origin; a thousand kilometres is no body's
  // place (what a flipped exponent gives: 1e30, 5e15), and leaves room for
  // files of made-up rows (the tests' run to 1e4).
  constexpr float kFarthest = 1e6f;
  // (Every batch of a training reads through here: the message is made only for a row refused.)
  const auto where = [&](std::size_t k) {
    return impl.files[impl.part_of(indices[k])].string() + ": sample " + std::to_string(indices[k]);
  };
  for (std::size_t k = 0; k < indices.size(); ++k) {
    const float far = rows.mat(static_cast<int>(k)).cwiseAbs().maxCoeff();
    if (far > kFarthest) {
      char text[160];
      std::snprintf(text, sizeof text, " has a %s of %.3g m, beyond a thousand kilometres: the file was edited or is damaged",
                    what.c_str(), static_cast<double>(far));
      throw ConfigError(where(k) + text);
    }
    if (far == 0.0f && rows.rows() > 1)
      throw ConfigError(where(k) + ": every " + what.substr(0, what.find(' ')) +
                        " vertex is at (0, 0, 0), HDF5's fill value: a row marked done that was never written (the file "
                        "was edited or is damaged)");
  }
}

DatasetReader::Posing DatasetReader::posing(const std::vector<std::size_t>& indices) const {
  check_indices(*this, indices, impl_->name);
  const std::lock_guard<std::mutex> lock(impl_->rebuild_mutex);
  if (!impl_->body_model) impl_->body_model = dataset_body_model(nullptr, layout_, impl_->files.front().string());
  const BodyModel& model = *impl_->body_model;
  if (!model.poseable()) throw ConfigError(impl_->name + ": its body model has no skeleton, so it gives no pose inputs");
  std::vector<std::size_t> todo;
  for (std::size_t row : indices)
    if (!impl_->posing.count(row)) todo.push_back(row);
  std::sort(todo.begin(), todo.end());
  todo.erase(std::unique(todo.begin(), todo.end()), todo.end());
  const std::size_t p = static_cast<std::size_t>(layout_.body_params), a = layout_.pose_angles.size();
  std::vector<float> params(todo.size() * p), stored(todo.size() * a);
  std::vector<bool> posed(todo.size());
  for (std::size_t k = 0; k < todo.size(); ++k) {  // HDF5 reads stay on this thread
    const Part& part = impl_->parts[impl_->part_of(todo[k])];
    part.file.read_rows(kParams, todo[k] - part.first, 1, params.data() + k * p);
    posed[k] = part.posed;
    if (posed[k]) part.file.read_rows(kPose, todo[k] - part.first, 1, stored.data() + k * a);
  }
  const std::vector<PoseAngle> angles = model.pose_angles();
  const std::size_t joints = model.joints().size();
  std::vector<Impl::PosingRow> made(todo.size());
  // A slim row whose file keeps a witness: its body as the generator posed it
  // (rebuilt_bodies) checked against it; refused[k] says why not (HDF5 reads
  // and the throw stay on this thread).
  std::vector<std::ptrdiff_t> at;
  const std::vector<double> stored_witness = impl_->witnesses(todo, witness_blocks(layout_.body_vertices) * 4, at);
  for (std::size_t k = 0; k < todo.size(); ++k)
    if (impl_->rebuilt.count(todo[k])) at[k] = -1;  // checked when body_vertices rebuilt it: not posed again
  std::vector<std::string> refused(todo.size());
  const auto n = static_cast<std::ptrdiff_t>(todo.size());
  std::vector<std::exception_ptr> failures(todo.size());
#pragma omp parallel for schedule(dynamic)
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    const auto u = static_cast<std::size_t>(k);
    try {
      const Eigen::VectorXd shape =
          Eigen::Map<const Eigen::VectorXf>(params.data() + u * p, static_cast<Eigen::Index>(p)).cast<double>();
      const Eigen::MatrixX3d unposed = model.vertices(shape);
      if (at[u] >= 0) {
        const Part& part = impl_->parts[impl_->part_of(todo[u])];
        const MatrixRM body =
            (posed[u] ? model.posed_vertices(unposed, pose_of_row(layout_.pose_angles, stored.data() + u * a), 1.0) : unposed)
                .cast<float>();
        refused[u] = not_the_simulated_body(part.file.path().string(), todo[u] - part.first, body.data(), layout_.body_vertices,
                                            stored_witness.data() + at[u]);
      }
      const Pose pose = full_pose(model, posed[u] ? pose_of_row(layout_.pose_angles, stored.data() + u * a) : Pose{}, unposed);
      const MatrixRM transforms = posed[u] ? transforms_rows(model.joint_transforms(unposed, pose))
                                           : transforms_rows(std::vector<skinning::Rigid>(joints));
      Impl::PosingRow& row = made[u];
      row.unposed.resize(static_cast<std::size_t>(unposed.size()));
      for (Eigen::Index v = 0; v < unposed.rows(); ++v)
        for (int c = 0; c < 3; ++c) row.unposed[static_cast<std::size_t>(v * 3 + c)] = static_cast<float>(unposed(v, c));
      row.transforms.assign(transforms.data(), transforms.data() + transforms.size());
      for (const PoseAngle& angle : angles)
        row.angles.push_back(static_cast<float>(pose.angles.at(angle.name) * M_PI / 180.0));
    } catch (...) {
      failures[u] = std::current_exception();
    }
  }
  impl_->rethrow_row_failure(failures, todo);
  for (const std::string& why : refused)
    if (!why.empty()) throw ConfigError(why);
  for (std::size_t k = 0; k < todo.size(); ++k) impl_->posing[todo[k]] = std::move(made[k]);
  const int count = static_cast<int>(indices.size());
  Posing out{Tensor(count, layout_.body_vertices, 3), Tensor(count, static_cast<int>(joints), 12),
             Tensor(count, 1, static_cast<int>(angles.size()))};
  for (int i = 0; i < count; ++i) {
    const Impl::PosingRow& row = impl_->posing.at(indices[static_cast<std::size_t>(i)]);
    std::copy(row.unposed.begin(), row.unposed.end(), out.unposed.data() + static_cast<std::size_t>(i) * row.unposed.size());
    std::copy(row.transforms.begin(), row.transforms.end(), out.transforms.data() + static_cast<std::size_t>(i) * row.transforms.size());
    std::copy(row.angles.begin(), row.angles.end(), out.angles.data() + static_cast<std::size_t>(i) * row.angles.size());
  }
  return out;
}

Tensor DatasetReader::poses(const std::vector<std::size_t>& indices) const {
  if (layout_.pose_angles.empty())
    throw ConfigError(impl_->name + ": holds A-pose bodies, no joint angles (a dataset generated without poses)");
  check_indices(*this, indices, fs::path(impl_->name));
  const int a = static_cast<int>(layout_.pose_angles.size());
  Tensor out(static_cast<int>(indices.size()), 1, a);
  if (!mixed_poses_) {
    impl_->gather(kPose, indices, static_cast<std::size_t>(a), out.data());
    return out;
  }
  // Mixed: a posed file's rows as stored; an A-pose file's rows at their
  // bodies' rest angles, which posing() makes for all of them at once
  // (radians, in the body model's order: mapped to the layout's columns).
  std::vector<std::size_t> rest_rows, rest_at;
  for (std::size_t k = 0; k < indices.size(); ++k) {
    const Part& part = impl_->parts[impl_->part_of(indices[k])];
    if (part.posed) {
      part.file.read_rows(kPose, indices[k] - part.first, 1, out.data() + k * static_cast<std::size_t>(a));
    } else {
      rest_rows.push_back(indices[k]);
      rest_at.push_back(k);
    }
  }
  if (rest_rows.empty()) return out;
  const Posing rest = posing(rest_rows);
  const std::vector<PoseAngle> angles = impl_->body_model->pose_angles();
  for (std::size_t j = 0; j < angles.size(); ++j) {
    const auto column = std::find(layout_.pose_angles.begin(), layout_.pose_angles.end(), angles[j].name);
    if (column == layout_.pose_angles.end()) continue;
    for (std::size_t r = 0; r < rest_rows.size(); ++r)
      out(static_cast<int>(rest_at[r]), 0, static_cast<int>(column - layout_.pose_angles.begin())) =
          static_cast<float>(rest.angles(static_cast<int>(r), 0, static_cast<int>(j)) * 180.0 / M_PI);
  }
  return out;
}

std::vector<double> DatasetReader::stat(const std::string& name, const std::vector<std::size_t>& indices) const {
  if (std::find(layout_.stats.begin(), layout_.stats.end(), name) == layout_.stats.end())
    throw ConfigError(fs::path(impl_->name).string() + ": no statistic '" + name + "'" + did_you_mean(name, layout_.stats));
  check_indices(*this, indices, fs::path(impl_->name));
  std::vector<double> out(indices.size());
  impl_->gather(stat_path(name).c_str(), indices, 1, out.data());
  return out;
}

DatasetSample DatasetReader::sample(std::size_t index) const {
  DatasetSample s;
  s.body_params = Eigen::Map<const Eigen::VectorXf>(body_params({index}).data(), layout_.body_params);
  s.body_vertices = body_vertices({index}).mat(0);
  s.garment_vertices = garment_vertices({index}).mat(0);
  if (!layout_.pose_angles.empty())
    s.pose = Eigen::Map<const Eigen::VectorXf>(poses({index}).data(), static_cast<Eigen::Index>(layout_.pose_angles.size()));
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
