#pragma once
// The drape dataset file (layout in docs/formats.md): N samples of body
// parameters, body vertices and draped garment vertices, a train/val/test split,
// per-sample statistics and a `done` flag, plus the scene and template hash.
//
// Crash safety. A DatasetWriter works on `<out>.partial`:
//  - the partial file is created complete but empty (every dataset allocated at
//    its final size, contiguous, attributes written) in a temporary file that is
//    renamed into place, so `<out>.partial` either does not exist or is valid;
//  - a sample write changes raw bytes at fixed offsets only, never HDF5
//    metadata: the arrays first, a flush, then done[i] = 1, another flush. A kill
//    at any point leaves the file readable with sample i either complete and
//    marked done or marked not done (and rewritten on resume);
//  - finish() renames `<out>.partial` to `<out>` once every sample is done, so
//    `<out>` always holds a complete dataset.
// Flushes hand the data to the operating system (safe against a killed process);
// `sync` in DatasetWriter::Options also fsyncs (safe against a power loss, slower).
#include <drape/errors.hpp>
#include <drape/mesh.hpp>
#include <drape/tensor.hpp>

#include <Eigen/Core>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace drape {

class BodyModel;

enum class Split : std::int8_t { Train = 0, Val = 1, Test = 2 };
const char* to_string(Split split);  // "train", "val", "test"
Split parse_split(const std::string& name);  // ConfigError for anything else

// What a dataset file holds, apart from the samples themselves.
struct DatasetLayout {
  std::size_t samples = 0;
  int body_params = 0;       // P
  int body_vertices = 0;     // Nb
  int garment_vertices = 0;  // Ng
  // False in a slim dataset (slim_dataset): /bodies/vertices is left out and
  // rebuilt from /bodies/params by expand_datasets; Nb is still recorded.
  bool body_vertices_stored = true;
  std::vector<std::string> stats;  // names of the per-sample statistics (/stats/<name>)
  // The garment template's triangles (/garments/faces, int32 [F, 3]), so that a
  // reader without drape (h5py) can draw or measure the drapes. Empty: not
  // stored (files written before 2026-11-29, which still load).
  Eigen::MatrixX3i garment_faces;
  // The joint angles of /bodies/pose (float32 [N, A], degrees), in column
  // order: every angle of the body model's pose space (BodyModel::
  // pose_angles), so that body i is the body of its shape in that pose
  // (BodyModel::posed_vertices at fraction 1). Empty: the bodies are in the
  // body model's A-pose and no pose is stored (every dataset before poses).
  std::vector<std::string> pose_angles;
  std::string scene;               // YAML text of the scene that generated it
  std::string template_hash;
  std::string drape_version = "0.1.0";
  std::string created;  // ISO 8601 UTC; empty: the writer fills in the time of creation
  std::map<std::string, std::string> attributes;  // any other root string attributes

  bool has_stat(const std::string& name) const;
};

struct DatasetSample {
  Eigen::VectorXf body_params;  // [P]
  MatrixRM body_vertices;       // [Nb, 3]
  MatrixRM garment_vertices;    // [Ng, 3]
  Eigen::VectorXf pose;         // [A] degrees, the layout's pose_angles; empty in an A-pose dataset
  Split split = Split::Train;
  // Values for some or all of the layout's stats; absent ones are stored as NaN.
  std::map<std::string, double> stats;
};

class DatasetWriter {
 public:
  struct Options {
    bool sync = false;  // fsync after each sample (survives a power loss)
  };
  // Creates `<path>.partial` for layout.samples samples, or reopens it to resume.
  // On resume the sizes, the stats names, scene and template_hash must match the
  // file (ConfigError naming the first difference), and so must the
  // `generator` attribute when both have one (how the samples are made:
  // seed, ranges, shard; model, iterations); `created` and the extra
  // attributes are kept from the first run. ConfigError when `<path>` already
  // exists (a finished dataset is never overwritten) or the partial file is
  // unreadable ("delete it to start over").
  DatasetWriter(const std::filesystem::path& path, const DatasetLayout& layout, const Options& options);
  DatasetWriter(const std::filesystem::path& path, const DatasetLayout& layout)
      : DatasetWriter(path, layout, Options{}) {}
  ~DatasetWriter();  // closes the partial file, leaving it for a later resume
  DatasetWriter(const DatasetWriter&) = delete;
  DatasetWriter& operator=(const DatasetWriter&) = delete;

  static std::filesystem::path partial_path(const std::filesystem::path& path);  // "<path>.partial"

  const DatasetLayout& layout() const { return layout_; }
  bool resumed() const { return resumed_; }
  // Writes (or rewrites) sample `index`, marking it done last. Error when a size differs.
  void write(std::size_t index, const DatasetSample& sample);
  bool is_done(std::size_t index) const { return done_.at(index) != 0; }
  std::vector<std::size_t> missing() const;  // indices not yet done, ascending
  std::size_t done_count() const;
  // Closes the file and renames it to the final path. Error when samples are missing.
  void finish();
  // Closes without finishing (what a killed process leaves behind, minus the kill).
  void close();

  struct Impl;

 private:
  // On resume: each done sample read back against the CRC written with it
  // (/sample_crc); one that differs (the file changed since) is marked not
  // done, to be made again, and a warning names it.
  void check_kept_samples();

  std::filesystem::path path_;
  DatasetLayout layout_;
  Options options_;
  bool resumed_ = false;
  std::vector<std::uint8_t> done_;
  std::unique_ptr<Impl> impl_;
};

// Reads a dataset file (finished, or a `.partial` one: then only done samples count).
//
// `path` may also be a glob pattern ('shards/shard-*-of-40.h5', quoted so that
// the shell leaves it alone): its files, in name order, read as one dataset
// (they must agree as `drape dataset merge` requires; sample i of the second
// file is row size(first) + i). Slim files (no body vertices) read as whole
// ones: body_vertices() rebuilds each body from its shape parameters with the
// stored scene's body model, once (about 20 ms a body on the parametric model;
// kept for the reader's lifetime), loading the default plugins when it must.
class DatasetReader {
 public:
  // One file, or the files of a glob pattern ({a,b} alternatives too) read
  // as one. They must agree as merge_datasets requires, except that A-pose
  // files may be read with posed files of the same scene, whose solvers may
  // differ (rest_pose_mix_difference in dataset_internal.hpp): layout() then
  // has the posed files' angles and scene, and an A-pose file's body is its
  // body at its rest angles (poses() gives those angles, posing() identity
  // transforms), so a graph of posed drapes learns from both.
  explicit DatasetReader(const std::filesystem::path& path);
  ~DatasetReader();
  DatasetReader(DatasetReader&&) noexcept;

  const DatasetLayout& layout() const { return layout_; }
  std::size_t size() const { return layout_.samples; }
  const std::string& name() const;  // the path or pattern it was opened with, for messages
  const std::vector<std::filesystem::path>& files() const;  // the file, or the pattern's files in order
  // Of files(), the slim ones that keep the witness of their simulated bodies
  // (/bodies/witness, docs/formats.md): their rebuilt bodies are checked.
  std::size_t witnessed_files() const;
  const std::vector<std::int8_t>& splits() const { return split_; }
  const std::vector<std::uint8_t>& done() const { return done_; }
  bool mixed_poses() const { return mixed_poses_; }  // A-pose files read with posed ones

  std::vector<std::size_t> indices() const;             // every done sample
  std::vector<std::size_t> indices(Split split) const;  // done samples of one split
  // What drape train --fraction trains on: the first ceil(fraction n) done
  // training samples (the model's domain records the same ones).
  std::vector<std::size_t> training_indices(double fraction = 1.0) const;
  // Done samples of the splits a text names: "test", "train,val" or "all", in
  // file order. ConfigError for an unknown split name.
  std::vector<std::size_t> indices(const std::string& splits) const;
  static void check_splits(const std::string& splits);  // the same ConfigError, without a file

  // Rows in the order of `indices`, as network-ready float tensors.
  Tensor body_params(const std::vector<std::size_t>& indices) const;       // [n, 1, P]
  Tensor body_vertices(const std::vector<std::size_t>& indices) const;     // [n, Nb, 3]
  Tensor garment_vertices(const std::vector<std::size_t>& indices) const;  // [n, Ng, 3]
  // The joint angles, degrees, in the layout's pose_angles order; ConfigError
  // for an A-pose dataset (layout().pose_angles empty).
  Tensor poses(const std::vector<std::size_t>& indices) const;  // [n, 1, A]
  // What the unposing graphs take (docs/poses.md), made by the stored scene's
  // body model once per sample and kept for the reader's lifetime (about
  // 20-90 ms a sample): the sample's body in its rest pose, the joints'
  // transforms from it into the sample's pose (garment_skinning.hpp's rows),
  // and the pose's angles in radians in the body model's pose_angles order.
  // An A-pose dataset's samples are at rest: identity transforms and each
  // body's rest angles. ConfigError when the body model has no skeleton.
  struct Posing {
    Tensor unposed;     // [n, Nb, 3]
    Tensor transforms;  // [n, J, 12]
    Tensor angles;      // [n, 1, A] radians
  };
  Posing posing(const std::vector<std::size_t>& indices) const;
  std::vector<double> stat(const std::string& name, const std::vector<std::size_t>& indices) const;
  DatasetSample sample(std::size_t index) const;

  struct Impl;

 private:
  DatasetLayout layout_;
  std::vector<std::int8_t> split_;
  std::vector<std::uint8_t> done_;
  bool mixed_poses_ = false;
  std::unique_ptr<Impl> impl_;
};

// The files a dataset argument names: the path itself when it exists (or has
// no glob characters), else the files matching it as a glob pattern, sorted.
// ConfigError when a pattern matches nothing.
std::vector<std::filesystem::path> dataset_files(const std::filesystem::path& path_or_pattern);
// The same, but none (no error) when nothing matches: for the checks a
// command makes before the reader's own error (refuse_output_among_inputs).
std::vector<std::filesystem::path> dataset_inputs(const std::filesystem::path& path_or_pattern);
// What a model records as the data it was trained on: a file's name, or a
// glob pattern whole (its last component alone would cut a {a,b} alternative
// in half: "shard-*-of-2.h5}").
std::string dataset_name(const std::filesystem::path& path_or_pattern);

// The samples among `indices` that are results: all but those drape optimize
// --data marked `separated` 0, the drapes it could not bring onto the true
// body (they lie inside it, so nothing may learn from or average them). A
// dataset without that statistic: all of them.
std::vector<std::size_t> optimizer_results(const DatasetReader& reader, const std::vector<std::size_t>& indices);

// The `template_hash` of a dataset (DatasetLayout::template_hash): FNV-1a over
// the garment template's vertices, faces and UVs and the body model's faces,
// as 16 hex digits. A dataset is only usable with the template it was made for.
std::string template_hash(const Mesh& garment, const Eigen::MatrixX3i& body_faces);

// Concatenates the done samples of several shard files (in order) into `out`,
// written atomically. The shards must agree on sizes, stats, scene and
// template hash (ConfigError naming the shard that differs). With
// require_complete, a shard with samples not done is an error; otherwise those
// samples are skipped. Returns the number of samples written.
//
// With mixed_sizes, the shards may come from scenes that differ in the garment
// (another size of the same template topology: the seed's small and regular
// T-shirts); every shard must then record the garment_size statistic, which
// tells a graph trained on them which size each sample wears. The merged file
// keeps the first shard's scene and template hash (a model trained on it uses
// that template) and lists every shard's hash in the attribute `templates`.
//
// `drop` leaves out the samples of those global indices (the global_index
// statistic drape generate records, and names a drape by in its report: a
// drape an independent check rejected, e.g. a garment through itself). Each
// must be in some shard (ConfigError otherwise, and for a shard without the
// statistic); a dropped sample counts as done for require_complete. The
// output lists them, with those its shards' own merges dropped, in the
// attribute `dropped` (comma-separated global indices).
std::size_t merge_datasets(const std::vector<std::filesystem::path>& shards, const std::filesystem::path& out,
                           bool require_complete = true, bool mixed_sizes = false, const std::vector<long>& drop = {});

// A list of global indices as --drop and the attribute `dropped` write it
// ("450,539"): parsed (ConfigError naming `what` and the item for anything
// but whole numbers >= 0), and written.
std::vector<long> parse_global_indices(const std::string& text, const std::string& what);
std::string global_index_list(const std::vector<long>& indices);

// A slim copy of a finished dataset: every array and attribute but the body
// vertices, which the body model rebuilds from the stored shape parameters
// (a tenth of the size for the coarse shirt on the parametric body; what the
// repository keeps of long generations, datasets/). ConfigError when `in` has
// samples not done or is slim already. Returns the number of samples. `drop`
// as merge_datasets's.
std::size_t slim_dataset(const std::filesystem::path& in, const std::filesystem::path& out, const std::vector<long>& drop = {});

// merge_datasets for slim shards (full ones are copied as merge does): the
// body vertices of each sample are rebuilt as body_model.vertices(params),
// the model that generated them (the scene's body model). ConfigError when the
// model's vertex or parameter count differs from the shards'. The rebuilt
// vertices come from the stored float parameters, so they differ from the
// simulated body by the parameters' rounding (under a micrometre here). A
// posed dataset's bodies are posed in their stored angles (drape generate
// rounds the angles it draws to float before it simulates).
// `rebuilt`, when given, is called after each body is rebuilt (a progress bar:
// about 20 ms a body on the parametric model).
std::size_t expand_datasets(const std::vector<std::filesystem::path>& shards, const std::filesystem::path& out,
                            const BodyModel& body_model, bool require_complete = true,
                            const std::function<void()>& rebuilt = {}, bool mixed_sizes = false);

}  // namespace drape
