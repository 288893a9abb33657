#pragma once
// The service behind `drape eval` and the experiment runner's evaluate steps:
// a model's metrics (training/metrics.hpp) on a dataset split, or the
// metrics of stored drapes (drape optimize's output) against the split's
// simulations, and the report file (CSV or JSON) a table is built from.
#include <drape/io/dataset.hpp>
#include <drape/training/evaluation.hpp>
#include <drape/training/metrics.hpp>
#include <drape/training/model.hpp>

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace drape {

class ProgressBar;

struct EvaluationRequest {
  std::filesystem::path data_file, drapes_file;  // the files' names, for messages (drapes_file: with stored drapes)
  std::string split = "test";  // train | val | test | all, or a list: train,val
  std::string where;           // "STAT=NUMBER": only the samples whose statistic has that value (empty: all)
  int batch = 16;              // bodies per forward pass
  double pushed_to = -1;       // >= 0: measure predictions pushed out of the body to this clearance (m)
};

// The ground truth's own p and surface crossings, over the samples.
struct GroundTruthReference {
  double p = 0, crossings = 0, crossed = 0;  // %, per sample, % of samples with any
};

struct ModelEvaluation {
  std::vector<std::size_t> samples;  // the dataset's samples measured (with stored drapes: each drape's source)
  std::size_t not_results = 0;       // stored drapes drape optimize did not finish on the true body
  SplitEvaluation evaluation;
  MetricsSummary summary;
  GroundTruthReference reference;
};

// The samples of `indices` whose statistic has the value `where` asks for
// ("STAT=NUMBER"); UsageError naming --where when it is malformed.
std::vector<std::size_t> samples_where(const DatasetReader& reader, const std::vector<std::size_t>& indices,
                                       const std::string& where);

// The samples a request measures: the split of the drapes file (with stored
// drapes) or of `data`, narrowed by `where`. ConfigError when nothing is selected.
std::vector<std::size_t> selected_samples(const DatasetReader& data, const DatasetReader* drapes,
                                          const EvaluationRequest& request);

// The model's predictions (or, with `drapes`, those stored garments) on the
// request's samples of `data`, measured against its simulations. `progress`
// (optional) is advanced once per selected sample.
ModelEvaluation evaluate_on_dataset(Model& model, const DatasetReader& data, const DatasetReader* drapes,
                                    const EvaluationRequest& request, ProgressBar* progress = nullptr);

// Writes the report atomically: `file` ends in .csv (metric, unit, mean, std,
// max) or .json (the same with the model, data, split and ground-truth
// reference; what `drape experiment` reads). `drapes` is empty without stored drapes.
void write_evaluation_report(const std::filesystem::path& file, const std::string& model, const std::string& drapes,
                             const std::string& data, const std::string& split, const ModelEvaluation& result);

}  // namespace drape
