// drape-libtorch-bench: the network of graphs/drape.yaml written in libtorch
// (Debian's libtorch-dev, CPU), trained side by side with drape's own in one
// process on the same batches: samples/s of full training steps (forward, L2
// loss, backward, Adam) and of inference, on one core, best of several rounds
// that alternate the two so that both see the same machine load.
//
// The libtorch version is what a competent user would write: convolutions as
// torch::nn::Conv1d, the encoder's features gathered straight to the garment
// vertices, the multi-scale decoder's sparse products (pooling, up-sampling,
// per-vertex learned aggregation on each vertex's ring and itself) as
// index_select / index_add_ over the nonzeros, the spectral residual as one
// batched matmul with the eigenvectors. Every size, the hierarchy, the
// correspondences and the eigenbasis come from drape's assets for the dataset,
// and the program refuses to run when the two networks' weight counts differ.
#include <drape/assets/assets.hpp>
#include <drape/training/data_parallel.hpp>
#include <drape/io/dataset.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/adjacency.hpp>
#include <drape/graph.hpp>
#include <drape/training/model.hpp>
#include <drape/nn/gemm.hpp>
#include <drape/nn/mesh_graph.hpp>
#include <drape/training/optimizer.hpp>
#include <drape/registry.hpp>
#include <drape/training/trainer.hpp>

#include <torch/torch.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <stdexcept>
#include <type_traits>
#include <string>
#include <vector>

namespace {

using namespace drape;
using Clock = std::chrono::steady_clock;

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

constexpr double kSlope = 0.2;  // drape's leaky_relu default (nn::negative_slope_param)

// A fixed or learned sparse operator [rows, cols] (COO, values differentiable).
struct SparseTorch {
  torch::Tensor rows, cols, values;  // values [nnz]
  int64_t out_rows = 0;
  static SparseTorch of(const nn::SparseRM& m) {
    std::vector<int64_t> r, c;
    std::vector<float> v;
    for (int i = 0; i < m.outerSize(); ++i)
      for (nn::SparseRM::InnerIterator it(m, i); it; ++it) r.push_back(i), c.push_back(it.col()), v.push_back(it.value());
    SparseTorch s;
    s.rows = torch::tensor(r, torch::kLong);
    s.cols = torch::tensor(c, torch::kLong);
    s.values = torch::tensor(v);
    s.out_rows = m.rows();
    s.in_cols = m.cols();
    return s;
  }
  int64_t in_cols = 0;
  // x [n, B, C] (vertex-major, so that the product needs no copy) -> [out_rows, B, C].
  torch::Tensor apply(const torch::Tensor& x, const torch::Tensor& v) const {
    const auto s = torch::sparse_coo_tensor(torch::stack({rows, cols}), v, {out_rows, in_cols});
    return torch::mm(s, x.reshape({x.size(0), -1})).view({out_rows, x.size(1), x.size(2)});
  }
  torch::Tensor apply(const torch::Tensor& x) const { return apply(x, values); }
};

struct GraphConvImpl : torch::nn::Module {
  SparseTorch pattern;
  torch::Tensor theta;
  torch::nn::Linear dense{nullptr};
  GraphConvImpl(const nn::SparseRM& ring, int in, int out) : pattern(SparseTorch::of(ring)) {
    theta = register_parameter("theta", pattern.values.clone());
    dense = register_module("dense", torch::nn::Linear(in, out));
  }
  // A (x W) or (A x) W, whichever side is narrower, as drape does.
  torch::Tensor forward(const torch::Tensor& x) {
    const bool aggregate_first = dense->weight.size(1) <= dense->weight.size(0);
    const auto y = aggregate_first ? dense(pattern.apply(x, theta))
                                   : pattern.apply(torch::matmul(x, dense->weight.t()), theta) + dense->bias;
    return torch::leaky_relu(y, kSlope);
  }
};
TORCH_MODULE(GraphConv);

// graphs/drape.yaml: cnn1d [32, 64, 64] kernel 5 stride 4 -> gather -> linear 16
// -> msgcn [64, 64, 32, 32] layers [2, 2, 2, 1] + spectral [256] (all k) -> + template.
struct DrapeNetImpl : torch::nn::Module {
  torch::nn::Conv1d c0{nullptr}, c1{nullptr}, c2{nullptr};
  torch::nn::Linear transfer{nullptr}, head{nullptr}, s0{nullptr}, s1{nullptr};
  std::vector<GraphConv> convs;
  std::vector<int> stage_of;           // the stage (coarsest first) of each conv
  std::vector<SparseTorch> upsample;   // into stage i from stage i-1 (i >= 1)
  SparseTorch pool;                    // garment -> coarsest level
  torch::Tensor garment_rows;          // for each garment vertex, the encoder row it reads
  torch::Tensor mean_body, garment_template, basis;  // [Nb, 3], [Ng, 3], [Ng, k]
  int64_t k = 0;

  explicit DrapeNetImpl(const Assets& a) {
    const int nb = a.body.num_vertices(), ng = a.garment->mesh.num_vertices();
    c0 = register_module("c0", torch::nn::Conv1d(torch::nn::Conv1dOptions(3, 32, 5).stride(4).padding(2)));
    c1 = register_module("c1", torch::nn::Conv1d(torch::nn::Conv1dOptions(32, 64, 5).stride(4).padding(2)));
    c2 = register_module("c2", torch::nn::Conv1d(torch::nn::Conv1dOptions(64, 64, 5).stride(4).padding(2)));
    // Row o of the last map sits at body vertex o * 4^3: each garment vertex reads
    // the row nearest its corresponding body vertex (drape: features, then gather).
    int last = nb;
    for (int l = 0; l < 3; ++l) last = (last + 3) / 4;
    std::vector<int64_t> rows(static_cast<std::size_t>(ng));
    for (int g = 0; g < ng; ++g)
      rows[std::size_t(g)] = std::min<int64_t>(last - 1, static_cast<int64_t>(std::floor(a.correspondence[std::size_t(g)] / 64.0 + 0.5)));
    garment_rows = torch::tensor(rows, torch::kLong);
    transfer = register_module("transfer", torch::nn::Linear(64, 16));
    const auto& h = a.hierarchy;
    const std::vector<int> channels{64, 64, 32, 32}, layers{2, 2, 2, 1};
    const int levels = 4;
    nn::SparseRM p = nn::restriction_of(h.levels[0].upsample);
    for (int l = 1; l + 1 < levels; ++l) p = nn::SparseRM(nn::restriction_of(h.levels[std::size_t(l)].upsample) * p);
    pool = SparseTorch::of(p);
    upsample.resize(levels);
    int in = 16;
    for (int i = 0; i < levels; ++i) {
      const int level = levels - 1 - i;
      const Mesh& mesh = h.levels[std::size_t(level)].mesh;
      if (i > 0) upsample[std::size_t(i)] = SparseTorch::of(h.levels[std::size_t(level)].upsample);
      const nn::SparseRM ring = nn::ring_mean(geometry::vertex_neighbours(mesh.faces, mesh.num_vertices()));
      for (int c = 0; c < layers[std::size_t(i)]; ++c) {
        convs.push_back(register_module("conv" + std::to_string(convs.size()), GraphConv(ring, in, channels[std::size_t(i)])));
        stage_of.push_back(i);
        in = channels[std::size_t(i)];
      }
    }
    head = register_module("head", torch::nn::Linear(in, 3));
    k = a.eigenvectors.cols();
    s0 = register_module("s0", torch::nn::Linear(64, 256));
    s1 = register_module("s1", torch::nn::Linear(256, 3 * k));
    auto from = [](const auto& m) {
      return torch::from_blob(const_cast<void*>(static_cast<const void*>(m.data())), {m.rows(), m.cols()},
                              std::is_same_v<typename std::decay_t<decltype(m)>::Scalar, double> ? torch::kDouble : torch::kFloat)
          .to(torch::kFloat)
          .clone();
    };
    // Eigen's MatrixX3d is column-major: transpose through a row-major copy.
    using RowD = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
    mean_body = from(RowD(a.body.vertices));
    garment_template = from(RowD(a.garment->mesh.vertices));
    basis = from(a.eigenvectors);
  }

  torch::Tensor forward(const torch::Tensor& body) {  // [B, Nb, 3] -> [B, Ng, 3]
    auto x = (body - mean_body).transpose(1, 2);        // [B, 3, Nb]
    x = torch::leaky_relu(c0(x), kSlope);
    x = torch::leaky_relu(c1(x), kSlope);
    x = torch::leaky_relu(c2(x), kSlope);               // [B, 64, L]
    const auto global = x.mean(2);                      // [B, 64]
    // The decoder runs vertex-major, [n, B, C]: its sparse products then take
    // the activations as an [n, B*C] matrix without a copy.
    auto f = x.index_select(2, garment_rows).permute({2, 0, 1});  // [Ng, B, 64]
    f = torch::leaky_relu(transfer(f), kSlope);
    auto y = pool.apply(f);
    for (std::size_t c = 0; c < convs.size(); ++c) {
      if (c > 0 && stage_of[c] != stage_of[c - 1]) y = upsample[std::size_t(stage_of[c])].apply(y);
      y = convs[c]->forward(y);
    }
    const auto decoded = head(y).permute({1, 0, 2});                      // [B, Ng, 3]
    const auto coefficients = s1(torch::relu(s0(global))).view({-1, k, 3});  // [B, k, 3]
    return decoded + torch::matmul(basis, coefficients) + garment_template;
  }
};
TORCH_MODULE(DrapeNet);

torch::Tensor to_torch(const Tensor& t) {
  return torch::from_blob(const_cast<float*>(t.data()), {t.batch(), t.rows(), t.cols()}, torch::kFloat).clone();
}

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

int run(int argc, char** argv) {
  std::string data, graph_file = DRAPE_SOURCE_DIR "/graphs/drape.yaml";
  int batch_size = 8, steps = 10, rounds = 5, k = 1000;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError(a + " needs a value");
      return argv[++i];
    };
    if (a == "--data") data = value();
    else if (a == "--graph") graph_file = value();
    else if (a == "--batch") batch_size = std::stoi(value());
    else if (a == "--steps") steps = std::stoi(value());
    else if (a == "--rounds") rounds = std::stoi(value());
    else if (a == "--k") k = std::stoi(value());
    else if (a == "--help" || a == "-h") {
      std::cout << "usage: drape-libtorch-bench --data data.h5 [--graph graphs/drape.yaml] [--batch 8] [--steps 10] "
                   "[--rounds 5] [--k 1000]\n";
      return 0;
    } else
      throw UsageError("unknown argument '" + a + "'");
  }
  if (data.empty()) throw UsageError("--data FILE is required (a drape dataset of the resolution to measure)");
  torch::set_num_threads(1);
  torch::manual_seed(0);

  Registry& registry = Registry::load_default({});
  const DatasetReader reader(data);
  const auto assets = assets_for_dataset(registry, reader, data, k, default_cache_dir());
  // drape's network with the L2 loss only (the network alone, as the issue compares it).
  GraphSpec spec = parse_graph_file(graph_file);
  spec.nodes.erase(std::remove_if(spec.nodes.begin(), spec.nodes.end(), [](const NodeSpec& n) { return n.is_loss; }),
                   spec.nodes.end());
  NodeSpec l2;
  l2.name = l2.type = "l2";
  l2.is_loss = true;
  spec.nodes.push_back(l2);
  GraphOptions options;
  options.dims = graph_dims(*assets, reader.layout().body_params);
  options.assets = assets.get();
  DataParallelGraph dp(spec, registry, options, 1);
  Adam adam(dp.graph().weights());
  std::size_t drape_weights = 0;
  for (const auto& [name, w] : dp.graph().weights()) drape_weights += w->value.size();

  DrapeNet net(*assets);
  std::size_t torch_weights = 0;
  for (const auto& p : net->parameters()) torch_weights += static_cast<std::size_t>(p.numel());
  if (torch_weights != drape_weights)
    throw Error("the libtorch network has " + std::to_string(torch_weights) + " weights, drape's " + graph_file + " " +
                std::to_string(drape_weights) + ": they are not the same architecture");
  torch::optim::Adam torch_adam(net->parameters(), torch::optim::AdamOptions(1e-4));

  std::vector<std::size_t> pool = reader.indices(Split::Train);
  if (pool.empty()) pool = reader.indices();
  std::vector<std::size_t> indices;
  for (int i = 0; i < batch_size; ++i) indices.push_back(pool[std::size_t(i) % pool.size()]);
  SampleBatch batch;
  batch.body = reader.body_vertices(indices);
  batch.target = reader.garment_vertices(indices);
  if (reader.layout().body_params > 0) batch.body_params = reader.body_params(indices);
  const torch::Tensor body = to_torch(batch.body), target = to_torch(batch.target);
  const int ng = assets->garment->mesh.num_vertices();

  const OmpThreadsScope one(1);
  auto drape_train = [&] {
    dp.gradients(batch);
    adam.step(1e-4);
  };
  auto torch_train = [&] {
    torch_adam.zero_grad();
    const auto loss = (net->forward(body) - target).pow(2).sum({1, 2}).div(ng).mean();
    loss.backward();
    torch_adam.step();
  };
  Graph& g = dp.graph();
  const auto inputs = graph_inputs(g, batch, false);
  auto drape_infer = [&] { g.forward(inputs, false); };
  auto torch_infer = [&] {
    torch::NoGradGuard no_grad;
    (void)net->forward(body);
  };
  // Best of the rounds, alternating: a round times `steps` calls of each in turn.
  auto timed = [&](const auto& f) {
    const auto t = Clock::now();
    for (int s = 0; s < steps; ++s) f();
    return seconds_since(t) / steps;
  };
  drape_train(), torch_train(), drape_infer(), torch_infer();  // warm-up: allocations
  double best[4] = {1e9, 1e9, 1e9, 1e9};
  for (int r = 0; r < rounds; ++r) {
    best[0] = std::min(best[0], timed(drape_train));
    best[1] = std::min(best[1], timed(torch_train));
    best[2] = std::min(best[2], timed(drape_infer));
    best[3] = std::min(best[3], timed(torch_infer));
  }
  std::printf("## drape and libtorch side by side: the network of %s, L2 loss, one core\n\n", graph_file.c_str());
  std::printf("garment %d vertices, body %d vertices, %zu weights in both, batch %d, best of %d rounds of %d steps, "
              "libtorch %s, BLAS kernels %s\n\n",
              ng, assets->body.num_vertices(), drape_weights, batch_size, rounds, steps, TORCH_VERSION,
              nn::blas_corename());
  std::printf("| | training samples/s | ms per step | inference ms per body (batch %d) |\n|---|---|---|---|\n", batch_size);
  std::printf("| drape | %.1f | %.1f | %.3f |\n", batch_size / best[0], 1e3 * best[0], 1e3 * best[2] / batch_size);
  std::printf("| libtorch | %.1f | %.1f | %.3f |\n", batch_size / best[1], 1e3 * best[1], 1e3 * best[3] / batch_size);
  std::printf("\ndrape / libtorch: training %.2fx, inference %.2fx\n", best[1] / best[0], best[3] / best[2]);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  drape::nn::reexec_with_native_blas(argv);
  try {
    return run(argc, argv);
  } catch (const UsageError& e) {
    std::cerr << "drape-libtorch-bench: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "drape-libtorch-bench: failed: " << e.what() << "\n";
    return 1;
  }
}
