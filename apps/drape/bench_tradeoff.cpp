// `drape bench tradeoff --data data.h5 --model a.h5 --model b.h5 [--svg tradeoff.svg]`:
// what accuracy costs in time. For each model: ms per body on one core and its
// ME and p on a split; for the simulation that made the data: its seconds per
// drape (the dataset's statistics) and the ground truth's own p. A table, and
// a chart of error against time.
#include "bench.hpp"

#include <drape/assets/dataset_assets.hpp>
#include <drape/io/dataset.hpp>
#include <drape/io/shipped_files.hpp>
#include <drape/services/dataset_poses.hpp>
#include <drape/training/evaluation.hpp>
#include <drape/training/model.hpp>
#include <drape/registry.hpp>
#include <drape/io/svg_chart.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

struct Row {
  std::string name;
  double ms = 0, me_cm = 0, p_percent = 0;
};

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0 : s / double(v.size());
}

Row measure(const Registry& registry, const std::string& file, const DatasetReader& reader,
            const std::vector<std::size_t>& indices, int repeats) {
  Model model = Model::load(registry, find_input_file(file));  // models/... from anywhere
  // (The dataset is named: "has 991 garment and 6904 body vertices per sample" is its count, not the model's.)
  check_dataset_template(reader, reader.name(), model.assets());
  check_model_takes_dataset_poses(model, reader, indices);
  Row row;
  row.name = std::filesystem::path(file).stem().string();
  const SplitEvaluation evaluation = evaluate_model(model, reader, indices);
  std::vector<double> me, p;
  for (const GarmentMetrics& m : evaluation.samples) {
    me.push_back(m.me_cm);
    p.push_back(m.penetration_percent);
  }
  row.me_cm = mean(me);
  row.p_percent = mean(p);
  row.ms = prediction_ms(model, read_samples(reader, {indices.front()}, model.graph(), false), repeats);
  return row;
}

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape bench tradeoff");
  opts.add_options()("data", po::value<std::string>(), "dataset (drape generate) the models were trained on")(
      "model", po::value<std::vector<std::string>>(), "model file (repeatable)")(
      "split", po::value<std::string>()->default_value("test"), "split to measure on")(
      "repeats", po::value<int>()->default_value(10), "timed predictions per model (the best is reported)")(
      "svg", po::value<std::string>(), "also draw the chart of error against time");
  po::variables_map vm;
  const std::string usage = "drape bench tradeoff --data data.h5 --model a.h5 [--model b.h5 ...] [--svg tradeoff.svg]";
  if (!parse(usage, args, opts, {}, vm)) return 0;
  if (!vm.count("data")) throw UsageError("--data FILE is required");
  if (!vm.count("model")) throw UsageError("give at least one --model FILE");
  const std::string data = vm["data"].as<std::string>(), split = vm["split"].as<std::string>();
  const DatasetReader reader(data);
  const std::vector<std::size_t> indices = reader.indices(parse_split(split));
  if (indices.empty()) throw ConfigError(data + ": the " + split + " split has no samples");
  Registry& registry = Registry::load_default(plugin_path(vm));

  std::vector<Row> rows;
  for (const std::string& file : vm["model"].as<std::vector<std::string>>())
    rows.push_back(measure(registry, file, reader, indices, count_option(vm, "repeats")));
  if (reader.layout().has_stat("seconds") && reader.layout().has_stat("penetration"))
    rows.push_back({"simulation (the ground truth)", 1000.0 * mean(reader.stat("seconds", indices)), 0.0,
                    100.0 * mean(reader.stat("penetration", indices))});

  std::printf("## What accuracy costs in time: %s, %s split (%zu samples)\n\n", data.c_str(), split.c_str(), indices.size());
  std::printf("| method | ms per drape (1 core) | ME (cm) | p (%%) |\n|---|---|---|---|\n");
  for (const Row& r : rows) std::printf("| %s | %.3g | %.3g | %.3g |\n", r.name.c_str(), r.ms, r.me_cm, r.p_percent);
  std::printf("\nThe simulation's time is its mean per drape when the dataset was made (drape generate, one drape per "
              "core); its ME is 0 by definition.\n");
  if (vm.count("svg")) {
    ScatterChart chart;
    chart.title = "What accuracy costs in time (" + std::filesystem::path(data).filename().string() + ", " + split + ")";
    chart.x_label = "milliseconds per drape on one core";
    chart.y_label = "mean vertex error ME (cm)";
    for (const Row& r : rows) {
      char label[160];
      std::snprintf(label, sizeof label, "%s: %.2g ms, ME %.2f cm, p %.2f%%", r.name.c_str(), r.ms, r.me_cm, r.p_percent);
      chart.points.push_back({r.ms, r.me_cm, label});
    }
    chart.write(vm["svg"].as<std::string>());
    std::printf("wrote %s\n", vm["svg"].as<std::string>().c_str());
  }
  return 0;
}

const RegisterBench registration{
    {"tradeoff", "what accuracy costs in time: models' ms per drape against their error, next to the simulation", run}};

}  // namespace
}  // namespace drape::cli
