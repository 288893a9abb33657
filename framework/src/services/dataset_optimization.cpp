#include <drape/services/dataset_optimization.hpp>

#include "../io/dataset_internal.hpp"
#include "../training/data_fingerprint.hpp"

#include <drape/io/parallel_samples.hpp>

#include <drape/assets/dataset_assets.hpp>
#include <drape/geometry/self_intersection.hpp>
#include <drape/fnv1a.hpp>
#include <drape/io/dataset.hpp>
#include <drape/progress.hpp>
#include <drape/registry.hpp>
#include <drape/scene/garment_size.hpp>
#include <drape/scene/scene.hpp>
#include <drape/services/graded_scene.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <system_error>
#include <iomanip>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

namespace drape {

namespace {

// This shard's part of the split's samples.
std::vector<std::size_t> shard_samples(const DatasetReader& reader, const OptimizeDatasetOptions& o) {
  const std::vector<std::size_t> whole = reader.indices(o.split);
  if (whole.empty()) throw ConfigError(o.data.string() + ": the " + o.split + " split has no samples");
  const std::vector<std::size_t> source(whole.begin() + static_cast<long>(o.shard.first(whole.size())),
                                        whole.begin() + static_cast<long>(o.shard.last(whole.size())));
  if (source.empty())
    throw ConfigError("--shard " + std::to_string(o.shard.index) + "/" + std::to_string(o.shard.count) + ": the " + o.split +
                      " split of " + o.data.string() + " has only " + std::to_string(whole.size()) +
                      " samples, none for this shard (use fewer shards)");
  return source;
}

// Statistics of the source sample that still describe the optimised one.
std::vector<std::string> carried_stats(const DatasetReader& reader) {
  std::vector<std::string> carried;
  for (const char* s : {"bmi", "garment_size"})
    if (reader.layout().has_stat(s)) carried.push_back(s);
  return carried;
}

// The optimised dataset: the source's sizes and template, the optimisation's
// statistics, the scene whose energy was minimised, and how it was made.
DatasetLayout optimized_layout(const DatasetReader& reader, const Scene& scene, const OptimizeDatasetOptions& o,
                               const std::vector<std::size_t>& source, const std::string& model_weights,
                               const std::vector<std::string>& carried) {
  const std::size_t samples = source.size();
  DatasetLayout layout;
  layout.samples = samples;
  layout.body_params = reader.layout().body_params;
  layout.body_vertices = reader.layout().body_vertices;
  layout.garment_vertices = reader.layout().garment_vertices;
  for (const auto& e : scene.effects) layout.stats.push_back("energy_" + e.name);
  for (const char* s : {"energy_total", "energy_total_before", "penetration", "penetration_before", "best_iteration",
                        "separated", "refused_steps", "grown_iteration", "seconds", "source_index", "self_crossings",
                        "self_crossings_before"})
    layout.stats.push_back(s);
  layout.stats.insert(layout.stats.end(), carried.begin(), carried.end());
  layout.scene = scene.yaml();
  layout.template_hash = reader.layout().template_hash;
  layout.garment_faces = reader.layout().garment_faces;  // the same template (empty for a source without them)
  layout.pose_angles = reader.layout().pose_angles;      // posed bodies keep their angles
  layout.attributes = reader.layout().attributes;
  std::ostringstream what;
  what << "drape optimize: model " << o.model.filename().string() << ", data " << o.data.filename().string() << " ("
       << o.split << (o.shard.count > 1 ? ", shard " + std::to_string(o.shard.index) + "/" + std::to_string(o.shard.count) : "")
       << "), " << o.optimization.iterations << " iterations, lr " << o.optimization.learning_rate;
  layout.attributes["generator"] = what.str();
  // The generator names the model and the data by file; these name them by
  // content, so that a resume or a rerun with other weights or drapes under
  // the same names is refused (dataset_layout.cpp, made_difference).
  layout.attributes["source_drapes"] = training_data_fingerprint(reader, source, {});
  layout.attributes["model_weights"] = model_weights;
  return layout;
}

// The optimised drape and its statistics in place of the source sample's.
// `self_before`/`self_after`: the garment's edge-face pairs through itself
// (geometry::self_edge_crossings), as simulate and generate record them.
void store_result(DatasetSample& sample, const PhysicsOptimizationResult& r, const std::vector<std::string>& carried,
                  std::size_t index, std::size_t self_before, std::size_t self_after) {
  sample.garment_vertices = r.after.cast<float>();
  std::map<std::string, double> stats;
  for (const auto& name : carried) stats[name] = sample.stats.at(name);
  sample.stats = std::move(stats);
  for (const auto& t : r.energies_after) sample.stats["energy_" + t.name] = t.value;
  sample.stats["energy_total"] = r.potential_after;
  sample.stats["energy_total_before"] = r.potential_before;
  sample.stats["penetration"] = r.penetration_after;
  sample.stats["penetration_before"] = r.penetration_before;
  sample.stats["best_iteration"] = r.best_iteration;
  sample.stats["separated"] = r.separated ? 1 : 0;  // 0: still crossing the body (a barrier scene without a penalty to push it out)
  sample.stats["refused_steps"] = r.refused_steps;
  sample.stats["grown_iteration"] = r.grown_iteration;
  sample.stats["seconds"] = r.seconds;
  sample.stats["source_index"] = static_cast<double>(index);
  sample.stats["self_crossings"] = static_cast<double>(self_after);
  sample.stats["self_crossings_before"] = static_cast<double>(self_before);
}

// The optimised garments that cross themselves, said at the end of the run
// (an outside check found 3 of 8 crossing themselves unsaid). A contact
// keeps layers apart; it cannot undo a crossing the prediction had.
void report_self_crossing(std::vector<std::pair<std::size_t, std::size_t>>& crossing) {
  if (crossing.empty()) return;
  std::sort(crossing.begin(), crossing.end());
  std::string list;
  for (std::size_t k = 0; k < crossing.size() && k < 20; ++k)
    list += (k ? ", " : "") + std::to_string(crossing[k].first) + " (" + std::to_string(crossing[k].second) + ")";
  std::fprintf(stderr,
               "warning: %zu optimised garments cross themselves (sample, edge-face pairs; the statistic "
               "self_crossings): %s%s\n",
               crossing.size(), list.c_str(), crossing.size() > 20 ? ", ..." : "");
}

void report_stopped(std::vector<std::string>& stopped) {
  if (stopped.empty()) return;
  std::sort(stopped.begin(), stopped.end());
  std::fprintf(stderr, "%zu optimisations stopped before their iterations (written; not results unless said):\n",
               stopped.size());
  for (const std::string& line : stopped) std::fprintf(stderr, "  %s\n", line.c_str());
}

}  // namespace

std::size_t optimize_dataset(const Registry& registry, const OptimizeDatasetOptions& o) {
  const DatasetReader reader(o.data);
  const std::vector<std::size_t> source = shard_samples(reader, o);
  const Scene scene = load_scene(o.scene_file);
  const SceneSimulations simulations(registry, scene);
  const GradedScene graded(registry, simulations);
  std::string model_weights;
  {
    Model probe = Model::load(registry, o.model);
    check_dataset_template(reader, o.data, probe.assets());
    Fnv1a f;
    for (auto& [name, weight] : probe.graph().weights())
      f.text(name).bytes(weight->value.data(), weight->value.size() * sizeof(float));
    model_weights = f.hex();
  }
  // The scene's body model makes the dataset's bodies (an outside check's
  // human-rig scene over mannequin bodies wrote a file whose scene and
  // bodies disagree, which eval then took).
  if (const int scene_vertices = simulations.design().body_model().num_vertices();
      scene_vertices != reader.layout().body_vertices)
    throw ConfigError(o.scene_file.string() + ": its body model '" + scene.body_model + "' has " +
                      std::to_string(scene_vertices) + " vertices, the bodies of " + o.data.string() + " " +
                      std::to_string(reader.layout().body_vertices) + ": give the scene the dataset was made in (its "
                      "stored scene: drape dataset info)");
  const std::vector<std::string> carried = carried_stats(reader);
  const DatasetLayout layout = optimized_layout(reader, scene, o, source, model_weights, carried);
  // A finished output: this same job done before (a job array's retry, or
  // the whole array resubmitted) has nothing to do, as drape generate; one
  // made otherwise is refused, saying how. (The cluster scripts skipped any
  // task whose shard existed, and an outside check's rerun with other
  // settings merged the old shards with the new without a word.)
  if (const std::optional<std::size_t> done = dataset_detail::finished_by_same_request(o.out.string(), layout, "optimise again")) {
    std::printf("nothing to do: %s is finished (%zu samples), made by this same request\n", o.out.c_str(), *done);
    return 0;
  }
  DatasetWriter writer(o.out, layout);
  const std::vector<std::size_t> todo = writer.missing();
  const int threads = std::max(1, std::min(o.threads, static_cast<int>(todo.size())));
  std::printf("optimising %zu samples of %s (%s split) into %s%s, %d at a time\n", source.size(), o.data.c_str(),
              o.split.c_str(), o.out.c_str(),
              writer.resumed() ? (" (resuming: " + std::to_string(source.size() - todo.size()) + " done)").c_str() : "",
              threads);
  std::fflush(stdout);

  ProgressBar::Options bar_options;
  bar_options.start = source.size() - todo.size();
  ProgressBar bar("optimize", source.size(), std::cerr, bar_options);
  std::mutex io;  // the HDF5 files are read and written by one thread at a time
  std::vector<std::string> stopped;  // samples whose optimisation a failure ended early (under io)
  std::vector<std::pair<std::size_t, std::size_t>> crossing;  // (sample, edge-face pairs) of garments through themselves (under io)
  make_samples_in_parallel(writer, bar, todo, threads, [&]() -> SampleWorker {
    // Each worker fine-tunes its own copy of the network, restored before every sample.
    auto model = std::make_shared<Model>(Model::load(registry, o.model));
    auto initial = std::make_shared<std::vector<Tensor>>();
    for (const auto& [name, w] : model->graph().weights()) initial->push_back(w->value);
    return [&, model, initial](std::size_t local) {
      const std::size_t index = source[local];
      std::size_t w = 0;
      for (const auto& [name, weight] : model->graph().weights()) weight->value = (*initial)[w++];
      DatasetSample sample;
      {
        const std::lock_guard<std::mutex> lock(io);
        sample = reader.sample(index);
      }
      // The sample already holds the body: the network's input comes from it, not from a second read.
      SampleBatch batch = sample_batch(sample, reader.layout(), model->graph(), &model->body_model());
      // A model of several sizes: each sample against the garment it wears, which must be the scene's for its body.
      const Simulation& simulation = graded.for_model(*model, batch, true, o.data.string() + " sample " + std::to_string(index));
      const PhysicsOptimizationResult r = optimize_drape(*model, simulation, batch, o.optimization);
      const Eigen::MatrixX3i& faces = simulation.garment().mesh.faces;
      const std::size_t self_after = geometry::self_edge_crossings(r.after, faces, geometry::kCrossingsCountedAtMost).size();
      store_result(sample, r, carried, index, geometry::self_edge_crossings(r.before, faces, geometry::kCrossingsCountedAtMost).size(), self_after);
      {
        const std::lock_guard<std::mutex> lock(io);
        writer.write(local, sample);
        if (!r.stopped.empty())
          stopped.push_back("sample " + std::to_string(index) + (r.separated ? " (a result: its best drape came before)" : "") +
                            ": " + r.stopped);
        if (self_after > 0) crossing.emplace_back(index, self_after);
      }
      std::ostringstream status;
      status << "last: L_p " << std::setprecision(4) << r.potential_before << " -> " << r.potential_after << " J, "
             << std::setprecision(2) << r.seconds << " s";
      bar.set_status(status.str());
      bar.advance();
    };
  });
  // A resumed run's samples of earlier runs, read back from the finished
  // file (its statistic self_crossings): the warning named only this run's
  // (a kill and resume said "5" where the uninterrupted run said "1, 5": an
  // outside check), as generate's does (dataset_generation.cpp).
  if (todo.size() < source.size()) {
    std::vector<char> made_now(source.size(), 0);
    for (const std::size_t local : todo) made_now[local] = 1;
    std::vector<std::size_t> earlier;
    for (std::size_t local = 0; local < source.size(); ++local)
      if (!made_now[local]) earlier.push_back(local);
    const DatasetReader finished(o.out);
    if (finished.layout().has_stat("self_crossings")) {
      const std::vector<double> pairs = finished.stat("self_crossings", earlier);
      for (std::size_t k = 0; k < earlier.size(); ++k)
        if (pairs[k] > 0) crossing.emplace_back(source[earlier[k]], static_cast<std::size_t>(pairs[k]));
    }
  }
  report_stopped(stopped);
  report_self_crossing(crossing);
  return todo.size();
}

}  // namespace drape
