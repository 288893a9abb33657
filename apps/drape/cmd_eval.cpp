// `drape eval --model model.h5 --data data.h5 [--split test]`: the seed's
// metrics (drape/training/metrics.hpp) and surface crossings of a model's predictions on
// one split, or (--drapes) of garments stored by drape optimize.
#include "command.hpp"

#include <drape/services/model_body.hpp>
#include <drape/io/shipped_files.hpp>
#include <drape/assets/dataset_assets.hpp>
#include <drape/io/atomic_file.hpp>
#include <drape/io/dataset.hpp>
#include <drape/services/model_evaluation.hpp>
#include <drape/training/evaluation.hpp>
#include <drape/training/metrics.hpp>
#include <drape/training/model.hpp>
#include <drape/progress.hpp>
#include <drape/io/svg_figure.hpp>

#include <algorithm>
#include <numeric>
#include <optional>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <iostream>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

namespace fs = std::filesystem;

std::string format(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

// Three panels: the bodies of the split with the lowest, median and highest
// BMI (body volume when the dataset has no BMI statistic), each with the
// predicted garment coloured by its distance to the ground truth.
void draw_errors(const fs::path& file, Model& model, const DatasetReader& reader, const std::vector<std::size_t>& indices,
                 const std::string& split) {
  std::vector<double> key;
  const bool has_bmi = reader.layout().has_stat("bmi");
  if (has_bmi) key = reader.stat("bmi", indices);
  std::vector<std::size_t> order(indices.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  if (has_bmi) std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
  std::vector<std::size_t> chosen = {indices[order.front()], indices[order[order.size() / 2]], indices[order.back()]};
  chosen.erase(std::unique(chosen.begin(), chosen.end()), chosen.end());

  const SampleBatch batch = read_samples(reader, chosen, model.graph(), true);
  const Tensor& truth = batch.target;
  const Tensor predicted = model.predict(batch);
  SvgFigure figure("drape eval: " + model.file().filename().string() + ", " + split + " split, error of each garment vertex");
  std::vector<Eigen::VectorXd> errors;
  std::vector<double> all;
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    const int b = static_cast<int>(i);
    errors.push_back(100.0 * (predicted.mat(b) - truth.mat(b)).cast<double>().rowwise().norm());
    all.insert(all.end(), errors.back().data(), errors.back().data() + errors.back().size());
  }
  // The scale ends at the 98th percentile, so a few outliers do not turn the rest dark.
  std::sort(all.begin(), all.end());
  const double top = all[static_cast<std::size_t>(0.98 * double(all.size() - 1))];
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    const int b = static_cast<int>(i);
    Mesh body = model.assets().body, garment = model.assets().garment->mesh;
    body.vertices = batch.body.mat(b).cast<double>();
    garment.vertices = predicted.mat(b).cast<double>();
    std::string title = "sample " + std::to_string(chosen[i]);
    if (has_bmi) title += format(", BMI %.1f", reader.stat("bmi", {chosen[i]})[0]);
    title += format(", ME %.2f cm", errors[i].mean());
    figure.add_panel(drape_panel(title, body, garment, errors[i]));
  }
  figure.set_colour_scale({"distance to the simulated garment (cm)", 0.0, std::max(top, 0.1)});
  figure.write(file);
}

// The n samples with the largest ME, worst first: their metrics and the
// body statistics the dataset holds (drape generate records bmi, sex, height).
void print_worst(const DatasetReader& reader, const std::vector<std::size_t>& indices, const SplitEvaluation& evaluation,
                 int n) {
  const std::vector<GarmentMetrics>& samples = evaluation.samples;
  std::vector<std::size_t> order(samples.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return samples[a].me_cm > samples[b].me_cm; });
  order.resize(std::min(order.size(), static_cast<std::size_t>(n)));
  std::vector<std::size_t> chosen;
  for (std::size_t i : order) chosen.push_back(indices[i]);
  std::vector<std::string> stats;
  std::vector<std::vector<double>> values;  // per statistic, one read for the chosen samples
  for (const char* name : {"bmi", "sex", "height"})
    if (reader.layout().has_stat(name)) {
      stats.emplace_back(name);
      values.push_back(reader.stat(name, chosen));
    }
  std::printf("\nthe %zu bodies with the largest ME:\n\n| sample | ME (cm) | p (%%) | most strained edge (%%) | simulated: most strained edge (%%) |", order.size());
  for (const auto& name : stats) std::printf(" %s |", name.c_str());
  std::printf("\n|---|---|---|---|---|");
  for (std::size_t k = 0; k < stats.size(); ++k) std::printf("---|");
  std::printf("\n");
  for (std::size_t r = 0; r < order.size(); ++r) {
    const GarmentMetrics& m = samples[order[r]];
    std::printf("| %zu | %.3g | %.3g | %.3g | %.3g |", chosen[r], m.me_cm, m.penetration_percent, m.strain_max,
                100.0 * evaluation.ground_truth_strain_max[order[r]]);
    for (const auto& column : values) std::printf(" %.4g |", column[r]);
    std::printf("\n");
  }
}

// `--by bmi:10,25,45,65`: the split's bodies in bands of one body statistic.
struct Bands {
  std::string stat;
  std::vector<double> edges;
};

// Read before the evaluation, so that a misspelt --by fails at once.
Bands parse_bands(const DatasetReader& reader, const std::string& spec) {
  const auto colon = spec.find(':');
  Bands bands;
  try {
    if (colon == std::string::npos || colon == 0) throw std::invalid_argument("no :");
    std::stringstream list(spec.substr(colon + 1));
    for (std::string item; std::getline(list, item, ',');) bands.edges.push_back(std::stod(item));
  } catch (const std::exception&) {
    throw UsageError("--by wants STAT:EDGE,EDGE[,...], e.g. bmi:10,25,45,65; got '" + spec + "'");
  }
  const auto& e = bands.edges;
  if (e.size() < 2 || !std::is_sorted(e.begin(), e.end()) || std::adjacent_find(e.begin(), e.end()) != e.end())
    throw UsageError("--by wants at least two increasing band edges, got '" + spec + "'");
  bands.stat = spec.substr(0, colon);
  if (!reader.layout().has_stat(bands.stat)) throw UsageError("--by: the dataset has no statistic '" + bands.stat + "'");
  return bands;
}

// Each band's ME (mean, median, worst), p (mean, worst, bodies above 1 %) and
// most strained edge, predicted and simulated: where in the body space the error is.
void print_by_band(const DatasetReader& reader, const std::vector<std::size_t>& indices, const SplitEvaluation& evaluation,
                   const Bands& bands) {
  const std::string& stat = bands.stat;
  const std::vector<double>& edges = bands.edges;
  const std::vector<double> key = reader.stat(stat, indices);
  std::printf("\nby %s:\n\n| %s | bodies | ME mean (cm) | median | worst | p mean (%%) | worst | above 1 %% | most strained edge (%%) | simulated (%%) |\n"
              "|---|---|---|---|---|---|---|---|---|---|\n",
              stat.c_str(), stat.c_str());
  std::size_t outside = 0;
  for (double k : key) outside += (k < edges.front() || k > edges.back()) ? 1 : 0;
  for (std::size_t band = 0; band + 1 < edges.size(); ++band) {
    // Half-open bands, the last one closed: every body in [first, last] is in exactly one.
    const bool last = band + 2 == edges.size();
    std::vector<double> me;
    double p_sum = 0, p_max = 0, strain_max = 0, truth_max = 0;
    int p_above = 0;
    for (std::size_t i = 0; i < key.size(); ++i) {
      if (key[i] < edges[band] || key[i] > edges[band + 1] || (!last && key[i] == edges[band + 1])) continue;
      const GarmentMetrics& m = evaluation.samples[i];
      me.push_back(m.me_cm);
      p_sum += m.penetration_percent;
      p_max = std::max(p_max, m.penetration_percent);
      p_above += m.penetration_percent > 1.0 ? 1 : 0;
      strain_max = std::max(strain_max, m.strain_max);
      truth_max = std::max(truth_max, 100.0 * evaluation.ground_truth_strain_max[i]);
    }
    std::printf("| %g-%g | %zu |", edges[band], edges[band + 1], me.size());
    if (me.empty()) {
      std::printf(" | | | | | | | |\n");
      continue;
    }
    const double mean = std::accumulate(me.begin(), me.end(), 0.0) / double(me.size());
    std::sort(me.begin(), me.end());
    const double median = me.size() % 2 ? me[me.size() / 2] : 0.5 * (me[me.size() / 2 - 1] + me[me.size() / 2]);
    std::printf(" %.3g | %.3g | %.3g | %.3g | %.3g | %d | %.3g | %.3g |\n", mean, median, me.back(), p_sum / double(me.size()),
                p_max, p_above, strain_max, truth_max);
  }
  if (outside) std::printf("(%zu bodies outside %g-%g are in no band)\n", outside, edges.front(), edges.back());
}

// What --drapes measured against what, and how many of them are not results.
void print_drapes_heading(const po::variables_map& vm, const std::string& drapes_file, const std::string& data,
                          const std::string& split, std::size_t samples, std::size_t not_results) {
  std::printf("the drapes of %s (%s split, %zu samples) against the simulations of %s%s\n", drapes_file.c_str(),
              split.c_str(), samples, data.c_str(), vm.count("where") ? (", where " + vm["where"].as<std::string>()).c_str() : "");
  if (not_results)
    std::printf("%zu of them are not results: drape optimize could not bring them onto the true body (separated 0); "
                "--where separated=1 measures the others alone\n",
                not_results);
  std::printf("\n");
}

// The metrics' table, and the ground truth's own p, crossings and strain.
void print_metrics(const MetricsSummary& s, const GroundTruthReference& ref, const SplitEvaluation& evaluation) {
  std::printf("| metric | mean | std | max (worst sample) | unit |\n|---|---|---|---|---|\n");
  for (const auto& c : metric_columns())
    std::printf("| %s | %.4g | %.3g | %.4g | %s |\n", c.name.c_str(), s.mean.*c.field, s.stddev.*c.field, s.max.*c.field,
                c.unit.c_str());
  std::printf("\nthe ground truth itself has p = %.3g %%, %.4g surface crossings per sample (%.3g %% of samples with any)\n",
              ref.p, ref.crossings, ref.crossed);
  const auto& truth_strain = evaluation.ground_truth_strain_max;
  std::printf("and its most strained edge (strain_max) is %.3g %% on average, %.3g %% at worst\n",
              100.0 * std::accumulate(truth_strain.begin(), truth_strain.end(), 0.0) / double(truth_strain.size()),
              100.0 * *std::max_element(truth_strain.begin(), truth_strain.end()));
}

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape eval");
  opts.add_options()("model", po::value<std::string>(), "model file from drape train")(
      "data", po::value<std::string>(), "dataset (drape generate) with ground-truth drapes")(
      "split", po::value<std::string>()->default_value("test"), "train | val | test | all, or a list: train,val")(
      "batch", po::value<int>()->default_value(16), "bodies per forward pass")(
      "where", po::value<std::string>(), "only the samples whose statistic has this value, e.g. garment_size=1 (the small "
                                          "shirts of a dataset of two sizes)")(
      "set", po::value<std::vector<std::string>>(), "node.param=value: change a parameter of the model's graph that leaves "
                                                    "the weights alone, e.g. post.enabled=true (repeatable)")(
      "worst", po::value<int>(), "also list the N bodies with the largest ME, with their body statistics (BMI, sex, height)")(
      "by", po::value<std::string>(), "also break the metrics down by bands of a body statistic, e.g. bmi:10,25,35,45,55,65 "
                                      "(ME mean, median and worst, p, bodies with p above 1 %, most strained edge per band, predicted and simulated)")(
      "out", po::value<std::string>(), "also write the table: metrics.csv or metrics.json")(
      "drapes", po::value<std::string>(), "measure the garments of this dataset instead of the model's predictions: "
                                          "drape optimize --data output made from --data (the prediction then the "
                                          "optimisation, against the simulation); the model gives the template")(
      "svg", po::value<std::string>(), "also draw the per-vertex error of the thinnest, median and heaviest body of the split (.svg, or .html: a 3D viewer)");
  add_push_out_option(opts, "measure the predictions after pushing their vertices out of the body to this clearance in m");
  po::variables_map vm;
  const std::string usage =
      "drape eval --model model.h5 --data data.h5 [--split test] [--out metrics.csv|json] [--svg errors.svg]\n"
      "       drape eval --model model.h5 --data data.h5 --drapes optimized.h5 [--where separated=1]";
  if (!parse(usage, args, opts, {}, vm)) return 0;
  if (!vm.count("model")) throw UsageError("--model FILE is required (from drape train)");
  if (!vm.count("data")) throw UsageError("--data FILE is required (a dataset from drape generate)");
  if (vm.count("out")) {
    const std::string ext = fs::path(vm["out"].as<std::string>()).extension().string();
    if (ext != ".csv" && ext != ".json") throw UsageError("--out must end in .csv or .json");
  }
  if (vm.count("worst") && vm["worst"].as<int>() < 1) throw UsageError("--worst wants a count of at least 1");
  const double pushed_to = push_out_margin(vm);
  const int batch_size = vm["batch"].as<int>();
  if (batch_size < 1) throw UsageError("--batch must be at least 1");
  const std::string split = vm["split"].as<std::string>();
  const std::string model_file = find_input_file(vm["model"].as<std::string>()).string(), data = vm["data"].as<std::string>();

  const bool stored = vm.count("drapes") > 0;
  if (stored && (vm.count("svg") || pushed_to >= 0 || vm.count("set")))
    throw UsageError("--drapes measures stored garments: --svg, --push-out and --set are for the model's predictions");

  Registry& registry = Registry::load_default(plugin_path(vm));
  Model model = Model::load(registry, model_file, parse_param_overrides(vm));
  const DatasetReader reader(data);
  std::optional<DatasetReader> drapes;
  if (stored) drapes.emplace(vm["drapes"].as<std::string>());
  EvaluationRequest request;
  request.data_file = data;
  if (stored) request.drapes_file = vm["drapes"].as<std::string>();
  request.split = split;
  if (vm.count("where")) request.where = vm["where"].as<std::string>();
  request.batch = batch_size;
  request.pushed_to = pushed_to;
  std::optional<Bands> bands;
  if (vm.count("by")) bands = parse_bands(reader, vm["by"].as<std::string>());

  // An A-pose model measured on posed drapes drapes every body at rest: its
  // error there (45 cm on an outside check's run) says nothing of the model.
  if (!stored && !reader.layout().pose_angles.empty() && !model_takes_pose(model))
    std::cerr << "warning: " << data << " holds drapes on posed bodies and " << model_file
              << " drapes bodies in the A-pose only (its graph takes no pose): it is measured draping each body as if "
                 "it stood at rest\n";
  ProgressBar bar("eval", selected_samples(reader, stored ? &*drapes : nullptr, request).size(), std::cerr);
  const ModelEvaluation result = evaluate_on_dataset(model, reader, stored ? &*drapes : nullptr, request, &bar);
  bar.finish();
  const MetricsSummary& s = result.summary;
  if (stored)
    print_drapes_heading(vm, request.drapes_file.string(), data, split, s.samples, result.not_results);
  else
    std::printf("%s on %s, %s split (%zu samples)%s\n\n", model_file.c_str(), data.c_str(), split.c_str(), s.samples,
                pushed_to >= 0 ? format(", every prediction pushed out of the body to %.4g m", pushed_to).c_str() : "");
  print_metrics(s, result.reference, result.evaluation);
  if (vm.count("worst")) print_worst(reader, result.samples, result.evaluation, vm["worst"].as<int>());
  if (bands) print_by_band(reader, result.samples, result.evaluation, *bands);
  if (vm.count("out")) {
    write_evaluation_report(vm["out"].as<std::string>(), model_file, stored ? request.drapes_file.string() : std::string(),
                            data, split, result);
    std::printf("wrote %s\n", vm["out"].as<std::string>().c_str());
  }
  if (vm.count("svg")) {
    draw_errors(vm["svg"].as<std::string>(), model, reader, result.samples, split);
    std::printf("wrote %s\n", vm["svg"].as<std::string>().c_str());
  }
  return 0;
}

const RegisterCommand registered{
    {"eval", "the seed's metrics (ME, L_l, L_e, L_s, L_d, p) and the surface crossings of a model on a dataset split", run}};

}  // namespace
}  // namespace drape::cli
