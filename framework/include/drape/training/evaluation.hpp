#pragma once
// A model's predictions on samples of a dataset, measured with the seed's
// metrics (metrics.hpp): what drape eval prints and drape bench tradeoff
// plots. Bodies are predicted in batches; the metrics of a batch run in
// parallel (OpenMP).
#include <drape/io/dataset.hpp>
#include <drape/training/metrics.hpp>
#include <drape/training/model.hpp>
#include <drape/progress.hpp>

#include <vector>

namespace drape {

struct SplitEvaluation {
  std::vector<GarmentMetrics> samples;          // in the order of the indices
  std::vector<double> ground_truth_penetration; // fraction of the simulated garment's vertices inside the body
  // Surface crossings of the simulated garment (MetricsContext::crossings).
  std::vector<int> ground_truth_crossings;
  // The simulated garment's most strained edge (MetricsContext::strain_max, fraction).
  std::vector<double> ground_truth_strain_max;
};

// The garment each sample wore, where it is not the template (a dataset made
// in each body's own size): the rest lengths strain_max measures against
// (face_edge_rest_lengths), one list per garment, and which list each
// sample's is, in the order of the indices measured (-1: the template's).
// Empty: the template's for every sample. services/worn_garments.hpp makes it.
struct WornGarments {
  std::vector<std::vector<double>> rest_lengths;
  std::vector<int> of_sample;
  // The rest lengths of sample k of the indices, or null for the template's.
  const std::vector<double>* rest_of(std::size_t k) const {
    if (k >= of_sample.size() || of_sample[k] < 0) return nullptr;
    return &rest_lengths[static_cast<std::size_t>(of_sample[k])];
  }
};

// Milliseconds of one prediction of a one-body batch on one core, as a user
// runs it: the best of `repeats` after a warm-up pass.
double prediction_ms(Model& model, const SampleBatch& one, int repeats = 20);

// Error naming the sample when a metric fails (a non-finite prediction).
// push_out_margin >= 0: each prediction is first pushed out of its body to
// that clearance (geometry::push_out, TailorNet's post-processing); < 0: the
// model's own output is measured (the seed's metrics). worn (optional): the
// garments the samples wore, for strain_max (predicted and simulated).
SplitEvaluation evaluate_model(Model& model, const DatasetReader& reader, const std::vector<std::size_t>& indices,
                               int batch_size = 16, ProgressBar* progress = nullptr, double push_out_margin = -1,
                               const WornGarments* worn = nullptr);

// Garments stored in a dataset of their own, measured against the simulated
// drapes of `truth` on the same metrics: the output of `drape optimize --data`,
// whose statistic source_index names each sample's row of `truth` (the seed's
// whole pipeline, prediction then optimisation, against the simulation).
// `drape_indices` are rows of `drapes`. Error naming the sample when a row has
// no source, its source is outside `truth`, or its body is not the source's.
// worn (optional): as evaluate_model's, in the order of drape_indices.
SplitEvaluation evaluate_drapes(const Assets& assets, const DatasetReader& truth, const DatasetReader& drapes,
                                const std::vector<std::size_t>& drape_indices, ProgressBar* progress = nullptr,
                                const WornGarments* worn = nullptr);

// The rows of `truth` the samples of `drapes` were made from (statistic source_index).
std::vector<std::size_t> drape_sources(const DatasetReader& truth, const DatasetReader& drapes,
                                       const std::vector<std::size_t>& drape_indices);

}  // namespace drape
