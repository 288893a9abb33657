#include <drape/training/data_parallel.hpp>
#include <drape/errors.hpp>
#include <drape/training/evaluation.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/geometry/push_out.hpp>

#include <algorithm>
#include <cstdio>
#include <array>
#include <cmath>
#include <chrono>
#include <functional>
#include <string>

namespace drape {

double prediction_ms(Model& model, const SampleBatch& one, int repeats) {
  const OmpThreadsScope one_core(1);
  model.predict(one);  // warm-up: allocations, caches
  double best = 1e300;
  for (int r = 0; r < std::max(1, repeats); ++r) {
    const auto start = std::chrono::steady_clock::now();
    model.predict(one);
    best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

namespace {

// One batch of a split to measure, each [n, N, 3]: the garments measured, the
// simulated garments and the bodies.
struct MeasuredBatch {
  Tensor garments, truth, bodies;
};

// The metrics of `count` samples, loaded `step` at a time by load(first, last)
// and measured in parallel (OpenMP); push_out_margin >= 0 pushes each garment
// out of its body first. An error names the sample (name(k)).
SplitEvaluation measure_in_batches(const Assets& assets, std::size_t count, std::size_t step, ProgressBar* progress,
                                   const std::function<MeasuredBatch(std::size_t, std::size_t)>& load,
                                   const std::function<std::string(std::size_t)>& name, double push_out_margin,
                                   const WornGarments* worn) {
  const MetricsContext metrics(assets);
  // The push-out lifts the garment's edges (and faces a peak of the body
  // rises through) as the push_out node does by default.
  const std::vector<std::array<int, 2>> edges =
      push_out_margin >= 0 ? geometry::edge_list(assets.garment->mesh.faces) : std::vector<std::array<int, 2>>{};
  SplitEvaluation out;
  out.samples.resize(count);
  out.ground_truth_penetration.resize(count);
  out.ground_truth_crossings.resize(count);
  out.ground_truth_strain_max.resize(count);
  for (std::size_t first = 0; first < count; first += step) {
    const std::size_t last = std::min(count, first + step);
    const MeasuredBatch batch = load(first, last);
    const int n = static_cast<int>(last - first);
    std::vector<std::string> errors(last - first);
#pragma omp parallel for schedule(dynamic)
    for (int b = 0; b < n; ++b) {
      try {  // no exception may leave an OpenMP region
        const std::size_t k = first + static_cast<std::size_t>(b);
        const Eigen::MatrixX3d y = batch.truth.mat(b).cast<double>(), body = batch.bodies.mat(b).cast<double>();
        Eigen::MatrixX3d x = batch.garments.mat(b).cast<double>();
        if (push_out_margin >= 0) {
          geometry::PushOutOptions options;
          options.margin = push_out_margin;
          options.edges = &edges;
          options.faces = &assets.garment->mesh.faces;
          geometry::push_out(geometry::BodySurface(body, assets.body.faces), x, options);
        }
        const std::vector<double>* rest = worn ? worn->rest_of(k) : nullptr;
        out.samples[k] = metrics.evaluate(x, y, body, rest);
        out.ground_truth_penetration[k] = metrics.penetration(y, body);
        out.ground_truth_crossings[k] = metrics.crossings(y, body);
        out.ground_truth_strain_max[k] = metrics.strain_max(y, rest);
      } catch (const std::exception& e) {
        errors[static_cast<std::size_t>(b)] = e.what();
      }
    }
    for (std::size_t b = 0; b < errors.size(); ++b)
      if (!errors[b].empty()) throw Error(name(first + b) + ": " + errors[b]);
    if (progress) progress->advance(last - first);
  }
  return out;
}

std::vector<std::size_t> slice(const std::vector<std::size_t>& v, std::size_t first, std::size_t last) {
  return {v.begin() + static_cast<long>(first), v.begin() + static_cast<long>(last)};
}

}  // namespace

SplitEvaluation evaluate_model(Model& model, const DatasetReader& reader, const std::vector<std::size_t>& indices,
                               int batch_size, ProgressBar* progress, double push_out_margin,
                               const WornGarments* worn) {
  if (batch_size < 1) throw ConfigError("evaluate: the batch size must be at least 1");
  const auto load = [&](std::size_t first, std::size_t last) {
    const std::vector<std::size_t> part = slice(indices, first, last);
    const SampleBatch batch = read_samples(reader, part, model.graph(), false);
    return MeasuredBatch{model.predict(batch), reader.garment_vertices(part), batch.body};
  };
  const auto name = [&](std::size_t k) { return "sample " + std::to_string(indices[k]); };
  return measure_in_batches(model.assets(), indices.size(), static_cast<std::size_t>(batch_size), progress, load, name,
                            push_out_margin, worn);
}

namespace {
std::string source_text(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}
}  // namespace

std::vector<std::size_t> drape_sources(const DatasetReader& truth, const DatasetReader& drapes,
                                       const std::vector<std::size_t>& drape_indices) {
  if (!drapes.layout().has_stat("source_index"))
    throw ConfigError("the drapes have no statistic source_index: they are not drape optimize --data output of this dataset");
  const std::vector<double> source = drapes.stat("source_index", drape_indices);
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < source.size(); ++i) {
    if (!(source[i] >= 0 && source[i] < double(truth.layout().samples)) || source[i] != std::floor(source[i]))
      throw ConfigError(drapes.name() + ": drape sample " + std::to_string(drape_indices[i]) + ": source_index " +
                        source_text(source[i]) + " is not a sample of " + truth.name() + " (" +
                        std::to_string(truth.layout().samples) + " samples): the drapes were optimised from another dataset");
    out.push_back(static_cast<std::size_t>(source[i]));
  }
  return out;
}

SplitEvaluation evaluate_drapes(const Assets& assets, const DatasetReader& truth, const DatasetReader& drapes,
                                const std::vector<std::size_t>& drape_indices, ProgressBar* progress,
                                const WornGarments* worn) {
  const std::vector<std::size_t> sources = drape_sources(truth, drapes, drape_indices);
  const auto name = [&](std::size_t k) { return drapes.name() + ": drape sample " + std::to_string(drape_indices[k]); };
  const auto load = [&](std::size_t first, std::size_t last) {
    const std::vector<std::size_t> part = slice(drape_indices, first, last), source = slice(sources, first, last);
    MeasuredBatch batch{drapes.garment_vertices(part), truth.garment_vertices(source), drapes.body_vertices(part)};
    // The same body (to 0.01 mm, a rebuilt body's round-off): a drape against another body's simulation means nothing.
    const Tensor truth_bodies = truth.body_vertices(source);
    for (std::size_t b = 0; b < part.size(); ++b)
      if ((batch.bodies.mat(int(b)) - truth_bodies.mat(int(b))).cwiseAbs().maxCoeff() > 1e-5f)
        throw ConfigError(name(first + b) + ": its body is not the body of sample " + std::to_string(source[b]) +
                          " of " + truth.name() + " (the drapes were optimised from another dataset)");
    return batch;
  };
  return measure_in_batches(assets, drape_indices.size(), 16, progress, load, name, -1, worn);
}

}  // namespace drape
