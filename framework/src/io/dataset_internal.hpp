#pragma once
// Private to the dataset files: dataset names, creating the empty layout,
// reading it back and comparing two layouts.
#include <drape/bodies/pose.hpp>
#include <drape/io/dataset.hpp>
#include <drape/io/h5.hpp>
#include <drape/scene/size_table.hpp>

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace drape::dataset_detail {

inline constexpr const char* kParams = "/bodies/params";
inline constexpr const char* kBodyVertices = "/bodies/vertices";
inline constexpr const char* kPose = "/bodies/pose";  // float32 [N, A] degrees; only in posed datasets
// Root attribute of a posed dataset: the angle names of kPose's columns, comma-separated.
inline constexpr const char* kPoseAngles = "pose_angles";
inline constexpr const char* kGarmentVertices = "/garments/vertices";
inline constexpr const char* kGarmentFaces = "/garments/faces";  // int32 [F, 3]; absent in files before 2026-11-29
inline constexpr const char* kSplit = "/split";
inline constexpr const char* kDone = "/done";
// int64 [N]: the CRC-32 of each sample's rows as the writer wrote them
// (params, body vertices, pose, garment vertices, split, stats, in that
// order), checked when a `.partial` is resumed; 0 for a sample not written
// (or by a writer before 2026-12-07, which had none: not checked).
inline constexpr const char* kSampleCrc = "/sample_crc";
inline constexpr const char* kStats = "/stats";
// A slim dataset's witness of the bodies it left out (float64 [N, B, 4], B =
// witness_blocks(Nb); slim files made before 2026-12-01 have none): for each
// of B blocks of consecutive body vertices, their mean x, y, z and the RMS
// distance from that mean, of the body the drape was simulated on. A body
// rebuilt from the parameters must match within kWitnessTolerance, or the
// body model changed since the dataset was made.
inline constexpr const char* kBodyWitness = "/bodies/witness";
inline constexpr std::size_t kWitnessBlocks = 64;
// 0.1 mm: a hundred times the float parameters' rounding in a rebuilt body
// (tests/cli/dataset_cli_test.cpp), a tenth of the barrier's 1 mm.
inline constexpr double kWitnessTolerance = 1e-4;
std::size_t witness_blocks(int body_vertices);
// The witness of one body (float [Nb, 3], row-major) into `out` (B x 4 values).
void body_witness(const float* body, int body_vertices, double* out);
// "" when `rebuilt`, the body of sample `row` of `file` rebuilt from its
// parameters, matches the sample's stored witness (B x 4 values); else the
// message a reader refuses it with (file, sample, the vertices that moved).
std::string not_the_simulated_body(const std::string& file, std::size_t row, const float* rebuilt, int body_vertices,
                                   const double* stored);
// ConfigError naming the file when its witness is not [N, B, 4] for its layout.
void check_witness_shape(const h5::File& file, const DatasetLayout& layout);

// Root attribute of a slim dataset: the body vertex count Nb, as text.
inline constexpr const char* kBodyVerticesOmitted = "body_vertices_omitted";
inline constexpr const char* kFormat = "drape dataset 1";  // root attribute `format`

inline std::string stat_path(const std::string& name) { return std::string(kStats) + "/" + name; }

// The current time as ISO 8601 UTC ("2024-05-01T12:00:00Z").
std::string now_utc();

// Creates every dataset at its final size (contiguous, preallocated, so that
// sample writes never touch metadata) and the root attributes.
void create_layout(h5::File& file, const DatasetLayout& layout);

// Reads and checks the layout of an existing file (ConfigError naming the
// dataset or attribute that is missing or inconsistent).
DatasetLayout read_layout(const h5::File& file);

// "" when `now` may continue / be merged with `have`, else the first difference
// ("body_vertices is 100 in the file, 120 now"; a merge says where each is).
std::string layout_difference(const DatasetLayout& have, const DatasetLayout& now, const std::string& have_is = "in the file",
                              const std::string& now_is = "now");
// "" when a file of layout `have` was made as `now` asks: the same layout and
// the same `generator` attribute (how the samples are made: generate's seed,
// body ranges and shard; optimize's model, iterations and learning rate),
// else the first difference. What a resume and a rerun on a finished file
// must share (not merge, which joins shards made alike in all but these).
std::string made_difference(const DatasetLayout& have, const DatasetLayout& now);
// A finished output `out` of a job that would make `now`: nullopt when there
// is none; its sample count when the same request made it (a job array's
// retry has nothing to do); else a ConfigError naming the difference, and
// `redo` ("generate it again") in the advice to delete it.
std::optional<std::size_t> finished_by_same_request(const std::string& out, const DatasetLayout& now, const std::string& redo);
// Empty when two layouts are A-pose and posed drapes of one scene, which
// DatasetReader reads as one (the A-pose bodies at their rest angles): one
// has pose angles and the other none, their scenes differ at most in the
// description and the solver (how the body got there: a posed scene carries
// the cloth with a rising arm), and all else agrees as layout_difference
// requires; else what differs (layout_difference's for two A-pose or two
// posed layouts).
std::string rest_pose_mix_difference(const DatasetLayout& a, const DatasetLayout& b);

// Joins the size_chart attribute of `layout` (the file `file`), when it has
// one, into `chart`: files of one garment made before and after sizes were
// added to its chart are one chart (SizeTable::join), as `dataset merge` and
// a pattern read as one dataset both need. ConfigError naming `file` when the
// charts disagree on a size they share (another garment).
void join_size_chart(std::optional<SizeTable>& chart, const DatasetLayout& layout, const std::string& file);

// Checks a sample's sizes against the layout (Error naming the array).
void check_sample(const DatasetLayout& layout, const DatasetSample& sample, const std::string& where);

// body_model.vertices(params) of `count` rows of float parameters, as floats
// (the bodies a slim dataset left out), each posed in its row of `poses`
// (count x angles.size() degrees) when `angles` is not empty; `rebuilt` is
// called after each body.
std::vector<float> rebuilt_bodies(const BodyModel& body_model, const std::vector<float>& params, std::size_t count,
                                  std::size_t body_params, const std::vector<std::string>& angles,
                                  const std::vector<float>& poses, const std::function<void()>& rebuilt = {});

// The Pose of one stored row of angles (names in column order).
Pose pose_of_row(const std::vector<std::string>& angles, const float* row);

// The body model of a dataset's stored scene, checked against its vertex and
// parameter counts: the one that generated its bodies (ConfigError naming
// `file` when it is not).
std::unique_ptr<BodyModel> dataset_body_model(const BodyModel* given, const DatasetLayout& layout, const std::string& file);

}  // namespace drape::dataset_detail
