#include <drape/data_parallel.hpp>
#include <drape/errors.hpp>
#include <drape/evaluation.hpp>
#include <drape/geometry/push_out.hpp>

#include <algorithm>
#include <cmath>
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

namespace {

void resize(SplitEvaluation& out, std::size_t n) {
  out.samples.resize(n);
  out.ground_truth_penetration.resize(n);
  out.ground_truth_crossings.resize(n);
  out.ground_truth_strain_max.resize(n);
}

// Sample k of `out`: the garment x against the simulated y on the body.
void measure(const MetricsContext& metrics, const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& y,
             const Eigen::MatrixX3d& body, SplitEvaluation& out, std::size_t k) {
  out.samples[k] = metrics.evaluate(x, y, body);
  out.ground_truth_penetration[k] = metrics.penetration(y, body);
  out.ground_truth_crossings[k] = metrics.crossings(y, body);
  out.ground_truth_strain_max[k] = metrics.strain_max(y);
}

}  // namespace

SplitEvaluation evaluate_model(Model& model, const DatasetReader& reader, const std::vector<std::size_t>& indices,
                               int batch_size, ProgressBar* progress, double push_out_margin) {
  if (batch_size < 1) throw ConfigError("evaluate: the batch size must be at least 1");
  const MetricsContext metrics(model.assets());
  SplitEvaluation out;
  resize(out, indices.size());
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
        measure(metrics, x, y, body, out, first + static_cast<std::size_t>(b));
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

std::vector<std::size_t> drape_sources(const DatasetReader& truth, const DatasetReader& drapes,
                                       const std::vector<std::size_t>& drape_indices) {
  if (!drapes.layout().has_stat("source_index"))
    throw ConfigError("the drapes have no statistic source_index: they are not drape optimize --data output of this dataset");
  const std::vector<double> source = drapes.stat("source_index", drape_indices);
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < source.size(); ++i) {
    if (!(source[i] >= 0 && source[i] < double(truth.layout().samples)) || source[i] != std::floor(source[i]))
      throw ConfigError("drape sample " + std::to_string(drape_indices[i]) + ": source_index " + std::to_string(source[i]) +
                        " is not a sample of the dataset (" + std::to_string(truth.layout().samples) + " samples)");
    out.push_back(static_cast<std::size_t>(source[i]));
  }
  return out;
}

SplitEvaluation evaluate_drapes(const Assets& assets, const DatasetReader& truth, const DatasetReader& drapes,
                                const std::vector<std::size_t>& drape_indices, ProgressBar* progress) {
  const std::vector<std::size_t> sources = drape_sources(truth, drapes, drape_indices);
  const MetricsContext metrics(assets);
  SplitEvaluation out;
  resize(out, drape_indices.size());
  constexpr std::size_t step = 16;
  for (std::size_t first = 0; first < drape_indices.size(); first += step) {
    const std::size_t last = std::min(drape_indices.size(), first + step);
    const std::vector<std::size_t> part(drape_indices.begin() + long(first), drape_indices.begin() + long(last));
    const std::vector<std::size_t> source(sources.begin() + long(first), sources.begin() + long(last));
    const Tensor garments = drapes.garment_vertices(part), bodies = drapes.body_vertices(part);
    const Tensor truth_garments = truth.garment_vertices(source), truth_bodies = truth.body_vertices(source);
    const int n = static_cast<int>(part.size());
    std::vector<std::string> errors(part.size());
#pragma omp parallel for schedule(dynamic)
    for (int b = 0; b < n; ++b) {
      try {
        const Eigen::MatrixX3d body = bodies.mat(b).cast<double>();
        // The same body (to 0.01 mm, a rebuilt body's round-off): a drape against another body's simulation means nothing.
        if ((bodies.mat(b) - truth_bodies.mat(b)).cwiseAbs().maxCoeff() > 1e-5f)
          throw ConfigError("its body is not the body of sample " + std::to_string(source[std::size_t(b)]) + " of the dataset");
        measure(metrics, garments.mat(b).cast<double>(), truth_garments.mat(b).cast<double>(), body, out,
                first + static_cast<std::size_t>(b));
      } catch (const std::exception& e) {
        errors[static_cast<std::size_t>(b)] = e.what();
      }
    }
    for (std::size_t b = 0; b < part.size(); ++b)
      if (!errors[b].empty()) throw Error("drape sample " + std::to_string(part[b]) + ": " + errors[b]);
    if (progress) progress->advance(part.size());
  }
  return out;
}

}  // namespace drape
