#pragma once
// A dataset of simulated drapes (the seed's ground truth), the service behind
// `drape generate` and `drape.generate`: bodies drawn uniformly in BMI (and
// height, sex, girths), each draped by the scene's simulation in parallel over
// samples, an 8:1:1 split of the whole set, resumable after a kill, shardable
// across a cluster job array (merge the shards with merge_datasets). The two
// faces parse their arguments into a GenerateRequest and print; everything
// that decides what is in the file is here, so they write the same bytes.
#include <drape/registry.hpp>
#include <drape/scene/scene.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace drape {

// Values drawn uniformly from [lo, hi]; lo == hi is that one value.
struct SampleRange {
  double lo = 0, hi = 0;
};

// Part `index` of `count` of a list: the contiguous block [n i / N, n (i + 1) / N),
// so the shards of a job array cover every item once, in order.
struct Shard {
  std::size_t index = 0, count = 1;
  std::size_t first(std::size_t n) const { return n * index / count; }
  std::size_t last(std::size_t n) const { return n * (index + 1) / count; }  // one past
};

struct GenerateRequest {
  std::size_t count = 0;  // samples in the whole set (all shards), >= 1
  SampleRange bmi{10, 65};
  SampleRange height{1.75, 1.75};  // m
  SampleRange sex{1, 1};           // a range draws one of its two ends per sample
  // Spread of the body's girths as a fraction of the body model's range
  // (draw_proportions), in [0, 1]; 0 keeps the mean build.
  double girths = 0.0;
  // Poses (docs/poses.md). false: every body in the scene's pose (the A-pose
  // when the scene has none); true: each body in a pose drawn from the body
  // model's pose space by rejection (draw_free_pose), on a seeded stream of
  // its own, so the shapes are those the seed draws without poses. A posed
  // dataset stores every sample's joint angles (DatasetLayout::pose_angles).
  bool draw_poses = false;
  // With draw_poses: sampling ranges replacing the pose space's
  // ("shoulder_abduction=60:90,spine_twist=30:45", with_sampling_ranges), for
  // a training set narrower than the space or a held-out set outside it.
  std::string pose_ranges;
  std::uint64_t seed = 0;  // of the bodies, the poses and the split
  Shard shard;
  int threads = 0;  // samples simulated at once; 0: all cores
};

// The statistics every generated sample records, in the file's order after
// one energy_<effect> per effect of the scene. Written once here; readers
// look them up by these names (DatasetReader::stat).
namespace sample_stat {
inline constexpr const char* energy_total = "energy_total";
inline constexpr const char* penetration = "penetration";
inline constexpr const char* crossings = "crossings";
inline constexpr const char* residual = "residual";
inline constexpr const char* stationarity = "stationarity";
inline constexpr const char* converged = "converged";
inline constexpr const char* iterations = "iterations";
inline constexpr const char* steps = "steps";
inline constexpr const char* seconds = "seconds";
inline constexpr const char* bmi = "bmi";
inline constexpr const char* height = "height";
inline constexpr const char* sex = "sex";
inline constexpr const char* global_index = "global_index";
inline constexpr const char* garment_size = "garment_size";
// The grade of the garment the sample wears: its size's girth over the design
// size's (size_table.hpp), times the scene's `garment: {grade}`; 1 for the
// design size. What a graph with the input garment_grade reads.
inline constexpr const char* garment_grade = "garment_grade";
}  // namespace sample_stat
// The statistic names of a scene's samples, in file order: energy_<effect>
// per effect, then the sample_stat names above.
std::vector<std::string> generated_statistics(const Scene& scene);

// What a run is about to do, for the face to print before the work starts.
struct GeneratePlan {
  std::string out;
  std::size_t total = 0;            // the whole set
  std::size_t first = 0, last = 0;  // this shard's global indices [first, last)
  std::size_t samples = 0;          // last - first
  std::size_t already = 0;          // done by an earlier run (resumed)
  bool resumed = false;
  int threads = 1;
  std::string ranges;  // "bmi 10:65, height 1.75:1.75, ..., shard 0/1": also the file's generator attribute
};

// What the run did (this run's samples only).
struct GenerateSummary {
  std::size_t samples = 0;  // in the file
  // The output was finished already, by this same request: nothing was
  // simulated (a retry of a job that had completed). The counts are 0.
  bool already_finished = false;
  int not_settled = 0, penetrating = 0, crossing = 0;
  // Drapes whose garment crosses itself (SimulationResult::self_crossings),
  // by their index in the whole set, ascending: this run's, and on a resumed
  // run those of earlier runs, checked again in the finished file
  // (checked_again of them). Not a statistic of the file: the shards made
  // before it have none, and the sets merge.
  std::vector<std::size_t> crossing_itself;
  std::size_t checked_again = 0;
};

struct GenerateObserver {
  std::function<void(const GeneratePlan&)> on_start;  // after the output is opened, before the first sample
  std::ostream* progress = nullptr;                   // a progress bar there; none when null
  // Called on the calling thread every tenth of a second while samples are
  // made; when it throws, every simulation under way stops at its next step,
  // the samples done are kept to resume, and its exception is rethrown
  // (Python's Ctrl-C: its handlers run in the main thread only).
  std::function<void()> poll;
};

// Generates (or resumes) `out`. Takes the output's lock first (output_lock.hpp),
// so a second job on `out` is refused before anything else. ConfigError for a
// request the scene cannot do (a BMI range its body model does not reach, a
// body its size chart cannot dress), naming the sample when a body is refused.
GenerateSummary generate_dataset(const Registry& registry, const Scene& scene, const GenerateRequest& request,
                                 const std::string& out, const GenerateObserver& observer = {});

}  // namespace drape
