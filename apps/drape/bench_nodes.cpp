// `drape bench nodes`: forward and forward+backward time per sample of learning
// nodes (losses, decoders) on the template's assets, as training runs them:
// losses get the rest garment plus a few cm of noise as pred, the rest garment
// as target and the mean body; decoders get random per-garment-vertex features.
// Best of several runs, wall time; set OMP_NUM_THREADS=1 for one core.
#include "bench.hpp"

#include <drape/assets/assets.hpp>
#include <drape/registry.hpp>

#include <chrono>
#include <cstdio>
#include <functional>
#include <map>
#include <random>
#include <sstream>

namespace drape::cli {
namespace DRAPE_UNITY_ID {  // the anonymous namespace, or a unique one in a unity build (command.hpp)

double best_ms(int repeats, const std::function<void()>& action) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    action();
    best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

Tensor random_tensor(int batch, int rows, int cols, float scale, std::mt19937_64& rng) {
  std::normal_distribution<float> normal(0.0f, scale);
  Tensor t(batch, rows, cols);
  for (std::size_t i = 0; i < t.size(); ++i) t.data()[i] = normal(rng);
  return t;
}

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream s(list);
  for (std::string item; std::getline(s, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

// Best forward and forward+backward times (ms, whole batch) of one node with
// default parameters, and its multiply-adds per sample. ConfigError when the
// node refuses the inputs' shapes.
struct NodeTimes {
  double forward, both, flops;
};

NodeTimes time_node(const Registry& reg, const std::string& name, const std::map<std::string, Tensor>& inputs,
                    const Assets& assets, int batch, int repeats) {
  const PluginDescriptor& d = reg.get(name);
  auto node = reg.create_node(name, Params(d.params, {}, name));
  ShapeMap shapes;
  TensorIn in;
  TensorOut gin_map;
  std::map<std::string, Tensor> grads;
  for (const auto& port : d.inputs) {
    const auto it = inputs.find(port.name);
    if (it == inputs.end()) throw UsageError(name + ": no bench input for port '" + port.name + "'");
    shapes[port.name] = it->second.shape();
    in[port.name] = &it->second;
    grads[port.name] = Tensor(batch, it->second.shape());
  }
  for (auto& [port, t] : grads) gin_map[port] = &t;
  std::map<std::string, Tensor> outputs, ones;
  TensorOut out;
  TensorIn out_in, gout;
  for (const auto& [port, s] : node->setup(shapes, {name, 1, &assets, {}})) {
    outputs[port] = Tensor(batch, s);
    ones[port] = Tensor(batch, s, 1.0f);
  }
  for (auto& [port, t] : outputs) out[port] = &t, out_in[port] = &t;
  for (auto& [port, t] : ones) gout[port] = &t;
  const double forward = best_ms(repeats, [&] { node->forward(in, out); });
  const double both = best_ms(repeats, [&] {
    node->forward(in, out);
    node->backward(in, out_in, gout, gin_map);
  });
  return {forward, both, node->flops_per_sample()};
}

int run(const std::vector<std::string>& args) {
  po::options_description opts("drape bench nodes");
  opts.add_options()("nodes", po::value<std::string>()->default_value(
                                  "cnn1d,pointnet,gcn,gcn_learned,l2,v2v,direction,edge,deformation,laplacian,spectral_loss,"
                                  "mlp,msgcn,gcn_decoder,cnn1d_decoder,uvcnn,spectral"),
                     "comma-separated plugins (encoders, losses, decoders), default parameters")(
      "resolution", po::value<std::string>()->default_value("default"), "garment resolution (default | coarse | a count)")(
      "k", po::value<int>()->default_value(1000), "eigenvectors of the spectral basis")(
      "channels", po::value<int>()->default_value(32), "feature channels C of the decoders' input")(
      "batch", po::value<int>()->default_value(1), "samples per call")(
      "repeats", po::value<int>()->default_value(5), "runs per measurement; the best is shown");
  po::variables_map vm;
  if (!parse("drape bench nodes [--nodes a,b] [--resolution default] [--k 1000] [--batch 1]", args, opts, {}, vm)) return 0;
  const int batch = vm["batch"].as<int>(), repeats = std::max(1, vm["repeats"].as<int>()), channels = vm["channels"].as<int>();
  if (batch < 1 || channels < 1 || vm["k"].as<int>() < 1) throw UsageError("--batch, --channels and --k must be at least 1");
  const Registry& reg = Registry::load_default(plugin_path(vm));
  // Every name first (with its close matches): an unknown one failed after the nodes before it were timed.
  for (const std::string& name : split(vm["nodes"].as<std::string>())) reg.get(name);
  AssetsSpec spec;
  spec.garment_params["resolution"] = vm["resolution"].as<std::string>();
  spec.eigen_k = vm["k"].as<int>();
  const auto assets = build_assets(reg, spec);
  const Mesh& garment = assets->garment->mesh;
  const int ng = garment.num_vertices();
  std::printf("garment %d vertices, body %d vertices, k = %d, batch %d, C = %d\n", ng, assets->body.num_vertices(),
              static_cast<int>(assets->eigenvectors.cols()), batch, channels);

  std::mt19937_64 rng(1);
  std::map<std::string, Tensor> loss_inputs{{"target", Tensor(batch, ng, 3)}, {"body", Tensor(batch, assets->body.num_vertices(), 3)}};
  Tensor pred = random_tensor(batch, ng, 3, 0.02f, rng);
  for (int b = 0; b < batch; ++b) {
    loss_inputs["target"].mat(b) = garment.vertices.cast<float>();
    loss_inputs["body"].mat(b) = assets->body.vertices.cast<float>();
    pred.mat(b) += garment.vertices.cast<float>();
  }
  loss_inputs["pred"] = pred;
  const std::map<std::string, Tensor> decoder_inputs{{"x", random_tensor(batch, ng, channels, 1.0f, rng)}};

  const std::map<std::string, Tensor> encoder_inputs{{"body", loss_inputs.at("body")}};
  const std::map<std::string, Tensor> global_inputs{{"x", random_tensor(batch, 1, 128, 1.0f, rng)}};

  std::printf("%-16s %-8s %12s %14s %14s\n", "node", "kind", "forward ms", "fwd+bwd ms", "MFLOP/sample");
  for (const std::string& name : split(vm["nodes"].as<std::string>())) {
    const PluginDescriptor& d = reg.get(name);
    // Decoders take per-vertex features [Ng, C], or a global feature [1, 128]
    // (the spectral branch): the first the node accepts at setup.
    std::vector<const std::map<std::string, Tensor>*> candidates;
    if (d.kind == "loss")
      candidates = {&loss_inputs};
    else if (d.kind == "encoder")
      candidates = {&encoder_inputs};
    else
      candidates = {&decoder_inputs, &global_inputs};
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      try {
        const auto [forward, both, flops] = time_node(reg, name, *candidates[c], *assets, batch, repeats);
        std::printf("%-16s %-8s %12.3f %14.3f %14.2f\n", name.c_str(), d.kind.c_str(), forward / batch, both / batch,
                    flops / 1e6);
        break;
      } catch (const ConfigError&) {
        if (c + 1 == candidates.size()) throw;
      }
    }
  }
  return 0;
}

const RegisterBench registration{{"nodes", "time forward and backward of encoder, loss and decoder plugins on the template's assets", run}};

}  // namespace
}  // namespace drape::cli
