// samples_where, evaluate_on_dataset, write_evaluation_report (services/model_evaluation.hpp).
#include <drape/services/model_evaluation.hpp>
#include <drape/services/dataset_poses.hpp>

#include <drape/assets/dataset_assets.hpp>
#include <drape/errors.hpp>
#include <drape/io/atomic_file.hpp>
#include <drape/registry.hpp>
#include <drape/services/worn_garments.hpp>

#include <cstdio>
#include <sstream>

namespace drape {
namespace {

std::string format(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

GroundTruthReference ground_truth_reference(const SplitEvaluation& evaluation, std::size_t samples) {
  GroundTruthReference ref;
  for (double r : evaluation.ground_truth_penetration) ref.p += 100.0 * r / double(samples);
  for (int c : evaluation.ground_truth_crossings) {
    ref.crossings += c / double(samples);
    ref.crossed += (c > 0 ? 100.0 : 0.0) / double(samples);
  }
  return ref;
}

std::string quoted(const std::string& t) {
  std::string q = "\"";
  for (char ch : t) q += (ch == '"' || ch == '\\') ? std::string("\\") + ch : std::string(1, ch);
  return q + "\"";
}

}  // namespace

std::vector<std::size_t> samples_where(const DatasetReader& reader, const std::vector<std::size_t>& indices,
                                       const std::string& where) {
  const auto eq = where.find('=');
  double wanted = 0;
  try {
    if (eq == std::string::npos || eq == 0) throw std::invalid_argument("no =");
    wanted = std::stod(where.substr(eq + 1));
  } catch (const std::exception&) {
    throw UsageError("--where wants STAT=NUMBER, got '" + where + "'");
  }
  const std::vector<double> values = reader.stat(where.substr(0, eq), indices);
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < indices.size(); ++i)
    if (values[i] == wanted) kept.push_back(indices[i]);
  return kept;
}

std::vector<std::size_t> selected_samples(const DatasetReader& data, const DatasetReader* drapes,
                                          const EvaluationRequest& request) {
  // With stored drapes the split, `where` and the samples are the drapes
  // file's; the metrics then go through each drape's source sample.
  const DatasetReader& selected = drapes ? *drapes : data;
  std::vector<std::size_t> indices = selected.indices(request.split);
  if (!request.where.empty()) indices = samples_where(selected, indices, request.where);
  if (indices.empty())
    throw ConfigError((drapes ? request.drapes_file : request.data_file).string() + ": the " + request.split +
                      " split has no samples" + (request.where.empty() ? std::string() : " where " + request.where));
  return indices;
}

ModelEvaluation evaluate_on_dataset(Model& model, const DatasetReader& data, const DatasetReader* drapes,
                                    const EvaluationRequest& request, ProgressBar* progress) {
  check_dataset_template(data, request.data_file, model.assets());
  if (drapes) check_dataset_template(*drapes, request.drapes_file, model.assets());
  const std::vector<std::size_t> indices = selected_samples(data, drapes, request);
  ModelEvaluation result;
  // The strain against the garment each body wore (a size: auto dataset's sizes).
  result.samples = drapes ? drape_sources(data, *drapes, indices) : indices;
  // An A-pose model on posed bodies: refused, not measured (dataset_poses.hpp).
  check_model_takes_dataset_poses(model, data, result.samples);
  const WornGarments worn = worn_garments(Registry::load_default(), data, result.samples);
  if (drapes) {
    // Drapes that drape optimize did not finish on the true body are not results (docs/optimization.md).
    result.not_results = indices.size() - optimizer_results(*drapes, indices).size();
    result.evaluation = evaluate_drapes(model.assets(), data, *drapes, indices, progress, &worn);
  } else {
    result.evaluation = evaluate_model(model, data, indices, request.batch, progress, request.pushed_to, &worn);
  }
  result.reference = ground_truth_reference(result.evaluation, result.samples.size());
  result.summary = summarize(result.evaluation.samples);
  return result;
}

void write_evaluation_report(const std::filesystem::path& file, const std::string& model, const std::string& drapes,
                             const std::string& data, const std::string& split, const ModelEvaluation& result) {
  const MetricsSummary& s = result.summary;
  const GroundTruthReference& ref = result.reference;
  std::ostringstream o;
  if (file.extension() == ".csv") {
    o << "metric,unit,mean,std,max\n";
    for (const auto& c : metric_columns())
      o << c.name << "," << c.unit << "," << format("%.9g", s.mean.*c.field) << "," << format("%.9g", s.stddev.*c.field)
        << "," << format("%.9g", s.max.*c.field) << "\n";
  } else {
    o << "{\n  \"model\": " << quoted(model) << (drapes.empty() ? "" : ",\n  \"drapes\": " + quoted(drapes))
      << ",\n  \"data\": " << quoted(data) << ",\n  \"split\": " << quoted(split) << ",\n  \"samples\": " << s.samples
      << ",\n  \"ground_truth_p_percent\": " << format("%.9g", ref.p)
      << ",\n  \"ground_truth_crossings\": " << format("%.9g", ref.crossings)
      << ",\n  \"ground_truth_crossed_samples_percent\": " << format("%.9g", ref.crossed) << ",\n  \"metrics\": {\n";
    const auto& columns = metric_columns();
    for (std::size_t i = 0; i < columns.size(); ++i)
      o << "    " << quoted(columns[i].name) << ": {\"unit\": " << quoted(columns[i].unit)
        << ", \"mean\": " << format("%.9g", s.mean.*columns[i].field)
        << ", \"std\": " << format("%.9g", s.stddev.*columns[i].field)
        << ", \"max\": " << format("%.9g", s.max.*columns[i].field) << "}" << (i + 1 < columns.size() ? "," : "") << "\n";
    o << "  }\n}\n";
  }
  write_text_atomically(file, o.str());
}

}  // namespace drape
