#include <drape/data_parallel.hpp>
#include <drape/errors.hpp>
#include <drape/evaluation.hpp>
#include <drape/geometry/push_out.hpp>

#include <algorithm>
#include <chrono>
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
                               int batch_size, ProgressBar* progress, double push_out_margin) {
  if (batch_size < 1) throw ConfigError("evaluate: the batch size must be at least 1");
  const MetricsContext metrics(model.assets());
  SplitEvaluation out;
  out.samples.resize(indices.size());
  out.ground_truth_penetration.resize(indices.size());
  out.ground_truth_crossings.resize(indices.size());
  out.ground_truth_strain_max.resize(indices.size());
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
        const Eigen::MatrixX3d y = truth.mat(b).cast<double>(), body = batch.body.mat(b).cast<double>();
        Eigen::MatrixX3d x = predicted.mat(b).cast<double>();
        if (push_out_margin >= 0)
          geometry::push_out(geometry::BodySurface(body, model.assets().body.faces), x, push_out_margin);
        out.samples[first + static_cast<std::size_t>(b)] = metrics.evaluate(x, y, body);
        out.ground_truth_penetration[first + static_cast<std::size_t>(b)] = metrics.penetration(y, body);
        out.ground_truth_crossings[first + static_cast<std::size_t>(b)] = metrics.crossings(y, body);
        out.ground_truth_strain_max[first + static_cast<std::size_t>(b)] = metrics.strain_max(y);
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

}  // namespace drape
