// `drape bench infer --model model.h5` (or --graph g.yaml with fresh weights, Model::untrained):
// milliseconds per body of one forward pass on one core, best of N, with the
// graph's multiply-adds per sample (Node::flops_per_sample) and the rate.
#include "bench.hpp"

#include <drape/io/shipped_files.hpp>

#include <drape/training/data_parallel.hpp>
#include <drape/training/model.hpp>
#include <drape/services/model_body.hpp>
#include <drape/nn/basis_products.hpp>
#include <drape/nn/dot_rows.hpp>
#include <drape/registry.hpp>

#include <algorithm>
#include <array>
#include <map>
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

using Clock = std::chrono::steady_clock;

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape bench infer");
  opts.add_options()("model", po::value<std::string>(), "model file from drape train")(
      "graph", po::value<std::string>(), "or a graph YAML, timed with freshly initialised weights")(
      "resolution", po::value<std::string>()->default_value("default"), "with --graph: garment resolution")(
      "k", po::value<int>()->default_value(1000), "with --graph: eigenvectors in the assets")(
      "bmi", po::value<double>()->default_value(35),
      "BMI of the body fed to the model, in turn with one 10 BMI away (so a node that keeps state meets a new body)")(
      "batch", po::value<int>()->default_value(1), "bodies per forward pass (figures are per body)")(
      "repeats", po::value<int>()->default_value(20), "timed passes (the best is reported)")(
      "pose", po::value<std::string>()->default_value("shoulder_abduction=45,elbow_flexion=30,spine_twist=10"),
      "for a model of posed drapes: the pose of the body fed (docs/poses.md)");
  po::variables_map vm;
  const std::string usage = "drape bench infer (--model model.h5 | --graph g.yaml [--resolution default]) [--repeats 20]";
  if (!parse(usage, args, opts, {}, vm)) return 0;
  require_model_or_graph(vm);
  const int repeats = vm["repeats"].as<int>(), batch_size = vm["batch"].as<int>();
  if (repeats < 1) throw UsageError("--repeats " + std::to_string(repeats) + ": expected at least 1");
  if (batch_size < 1) throw UsageError("--batch " + std::to_string(batch_size) + ": expected at least 1");

  Registry& registry = Registry::load_default(plugin_path(vm));
  AssetsSpec fresh_assets;  // with --graph: the default template at the asked resolution
  fresh_assets.garment_params["resolution"] = vm["resolution"].as<std::string>();
  fresh_assets.eigen_k = vm["k"].as<int>();
  Model model = vm.count("model")
                    ? Model::load(registry, find_input_file(vm["model"].as<std::string>()))
                    : Model::untrained(registry, parse_graph_file(find_input_file(vm["graph"].as<std::string>())), fresh_assets);
  Graph& graph = model.graph();
  const Assets& assets = model.assets();
  const std::string& output = model.output();

  // Two bodies, fed in turn: a node that keeps state from the last body
  // (the push-out's refitted surface and the faces its searches start from)
  // meets a new body at every pass, as it does in predict over many bodies.
  const double bmi = vm["bmi"].as<double>();
  const Pose pose = model_takes_pose(model)
                        ? parse_pose(vm["pose"].as<std::string>(), model.body_model().pose_angles(), "--pose")
                        : Pose{};
  double posing_ms = -1;
  // A model of drapes in each body's own size gets the size predict gives
  // the body (the tailor's rule): a BMI 45 body in the design size is a
  // shirt three sizes too small, which the push-out's untangle spends most
  // of the pass on (5 ms of crumples on the posed human-rig model).
  const BodyPreparation sizing(model, std::nullopt);
  std::vector<std::string> size_notes;
  auto inputs_for = [&](double body_bmi) {
    BodyRequest request;
    request.bmi = body_bmi;
    SampleBatch batch = body_batch(model.body_model(), request, batch_size);
    // What predict feeds besides the body: the garment's size (above), and for a
    // model of posed drapes the body posed (timed apart: it is the input's making, not the network).
    if (model.needs_input("garment_grade") && !model_size_chart(model))  // (a graph's fresh weights: no chart)
      batch.garment_grade = Tensor(batch_size, 1, 1, 1.0f);
    else if (model.needs_input("garment_grade"))
      for (const Notice& notice : sizing.choose_sizes(batch)) size_notes.push_back(notice.text);
    if (model.needs_input("garment_size")) batch.garment_size = Tensor(batch_size, 1, 1, 0.0f);
    if (model_takes_pose(model)) {
      const auto t = Clock::now();
      pose_model_batch(model, batch, pose);
      posing_ms = std::chrono::duration<double, std::milli>(Clock::now() - t).count() / batch_size;
    }
    return batch;
  };
  const double other_bmi = bmi + (bmi < 40 ? 10.0 : -10.0);
  // The BMI given first: a BMI outside the body model's range is named as given, not as its companion.
  SampleBatch given = inputs_for(bmi);
  const std::array<SampleBatch, 2> batches{inputs_for(other_bmi), std::move(given)};
  const std::array<std::map<std::string, Tensor>, 2> bodies{graph_inputs(graph, batches[0], false),
                                                             graph_inputs(graph, batches[1], false)};
  // With the mirror average the pass is Model::predict's: the twin posed
  // (its body and joints in the mirrored pose), its network pass, the mean,
  // then the push-out; the node table shows the body's own pass.
  const bool mirror = !model.mirror_average_node().empty();
  const auto pass = [&](int r) {
    if (mirror) model.predict(batches[static_cast<std::size_t>(r % 2)]);
    else graph.forward(bodies[static_cast<std::size_t>(r % 2)], false);
  };

  const OmpThreadsScope one_core(1);
  pass(0);  // warm-up: allocations, caches
  std::vector<double> ms;
  std::vector<std::vector<double>> node_ms;  // per node, per repeat
  std::vector<Graph::NodeTime> nodes;
  for (int r = 0; r < repeats; ++r) {
    const auto t = Clock::now();
    pass(r);
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t).count() / batch_size);
    nodes = graph.last_forward_times();
    node_ms.resize(nodes.size());
    for (std::size_t n = 0; n < nodes.size(); ++n) node_ms[n].push_back(nodes[n].ms / batch_size);
  }
  const auto [best, median] = best_and_median(ms);
  const double macs = graph.flops_per_sample();  // (one pass's: with the mirror average the twin runs part of it again)
  std::size_t weights = 0;
  for (const auto& [name, w] : graph.weights()) weights += w->value.size();
  std::printf("## Inference on one core: %s\n\n", model.file().string().c_str());
  std::printf("garment %d vertices, body %d vertices, output '%s', %zu learnable weights, batch %d, basis products %s (rows: %s); "
              "bodies of BMI %g and %g in turn\n\n",
              assets.garment->mesh.num_vertices(), assets.body.num_vertices(), output.c_str(), weights, batch_size,
              nn::basis_products_version(), nn::dot_rows_version(), bmi, other_bmi);
  // Above the tables, not between them: each body's size as predict would choose it.
  for (const std::string& note : size_notes) std::printf("- garment size: %s\n", note.c_str());
  if (!size_notes.empty()) std::printf("\n");
  std::printf("| ms per body (best of %d) | median | multiply-adds per body | GFLOP/s (2 per multiply-add) |\n|---|---|---|---|\n",
              repeats);
  std::printf("| %.3f | %.3f | %.4g | %.2f |\n", best, median, macs, 2.0 * macs / (best * 1e-3) / 1e9);
  if (posing_ms >= 0)
    std::printf("\nposing the body and its joint transforms (the inputs unposed_body, joint_transforms, pose; not in the "
                "figures above): %.3f ms per body, once\n",
                posing_ms);
  // Where the time goes: the median pass of each node, so a reader sees which
  // node is far from the machine's peak (memory-bound or scalar code).
  std::printf("\n| node | type | ms per body (median) | share | multiply-adds | GFLOP/s |\n|---|---|---|---|---|---|\n");
  double total = 0.0;
  std::vector<double> node_median(nodes.size());
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    node_median[n] = best_and_median(node_ms[n]).median;
    total += node_median[n];
  }
  for (std::size_t n = 0; n < nodes.size(); ++n)
    std::printf("| %s | %s | %.3f | %.0f%% | %.3g | %.2f |\n", nodes[n].name.c_str(), nodes[n].type.c_str(), node_median[n],
                100.0 * node_median[n] / std::max(total, 1e-12), nodes[n].flops_per_sample,
                node_median[n] > 0 ? 2.0 * nodes[n].flops_per_sample / (node_median[n] * 1e-3) / 1e9 : 0.0);
  if (mirror)
    std::printf("\nmirror average before '%s': the median pass less the nodes above, %.3f ms per body (the twin "
                "posed in the mirrored pose, the nodes that read the pose run again for it, and the mean; the rest "
                "body's, the encoder's, are shared; the multiply-adds above are one pass's; --set "
                "%s.mirror_average=false in drape model set times the model without it)\n",
                model.mirror_average_node().c_str(), median - total, model.mirror_average_node().c_str());
  return 0;
}

const RegisterBench registration{{"infer", "ms per body of a model's forward pass on one core, with FLOPs and GFLOP/s", run}};

}  // namespace
}  // namespace drape::cli
