#include <drape/data_parallel.hpp>
#include <drape/errors.hpp>
#include <drape/evaluation.hpp>
#include <drape/geometry/surface_crossings.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
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

SplitEvaluation evaluate_model(Model& model, const DatasetReader& reader, const std::vector<std::size_t>& indices,
                               int batch_size, ProgressBar* progress) {
  if (batch_size < 1) throw ConfigError("evaluate: the batch size must be at least 1");
  const MetricsContext metrics(model.assets());
  SplitEvaluation out;
  out.samples.resize(indices.size());
  out.ground_truth_penetration.resize(indices.size());
  out.crossings.resize(indices.size());
  out.ground_truth_crossings.resize(indices.size());
  const Eigen::MatrixX3i& garment_faces = model.assets().garment->mesh.faces;  // MetricsContext checked there is one
  const Eigen::MatrixX3i& body_faces = model.assets().body.faces;
  const auto step = static_cast<std::size_t>(batch_size);
  for (std::size_t first = 0; first < indices.size(); first += step) {
    const std::vector<std::size_t> part(indices.begin() + static_cast<long>(first),
                                        indices.begin() + static_cast<long>(std::min(indices.size(), first + step)));
    const SampleBatch batch = read_samples(reader, part, model.graph(), false);
    const Tensor truth = reader.garment_vertices(part);
    const Tensor predicted = model.predict(batch);
    const int n = static_cast<int>(part.size());
    std::vector<std::string> errors(part.size());
#pragma omp parallel for schedule(dynamic)
    for (int b = 0; b < n; ++b) {
      try {  // no exception may leave an OpenMP region
        const Eigen::MatrixX3d x = predicted.mat(b).cast<double>(), y = truth.mat(b).cast<double>(),
                               body = batch.body.mat(b).cast<double>();
        out.samples[first + static_cast<std::size_t>(b)] = metrics.evaluate(x, y, body);
        out.ground_truth_penetration[first + static_cast<std::size_t>(b)] = metrics.penetration(y, body);
        const std::size_t i = first + static_cast<std::size_t>(b);
        out.crossings[i] = geometry::surface_crossings(x, garment_faces, body, body_faces).total();
        out.ground_truth_crossings[i] = geometry::surface_crossings(y, garment_faces, body, body_faces).total();
      } catch (const std::exception& e) {
        errors[static_cast<std::size_t>(b)] = e.what();
      }
    }
    for (std::size_t b = 0; b < part.size(); ++b)
      if (!errors[b].empty()) throw Error("sample " + std::to_string(part[b]) + ": " + errors[b]);
    if (progress) progress->advance(part.size());
  }
  return out;
}

CrossingsSummary summarize_crossings(const std::vector<int>& crossings) {
  CrossingsSummary s;
  if (crossings.empty()) return s;
  const auto n = static_cast<double>(crossings.size());
  for (int c : crossings) s.mean += c / n, s.crossed_fraction += (c > 0) / n;
  double var = 0, crossed_var = 0;
  for (int c : crossings) {
    var += (c - s.mean) * (c - s.mean);
    crossed_var += ((c > 0) - s.crossed_fraction) * ((c > 0) - s.crossed_fraction);
  }
  // Sample standard deviations, as summarize() in metrics.cpp.
  s.stddev = crossings.size() > 1 ? std::sqrt(var / (n - 1)) : 0.0;
  s.crossed_stddev = crossings.size() > 1 ? std::sqrt(crossed_var / (n - 1)) : 0.0;
  return s;
}

}  // namespace drape
