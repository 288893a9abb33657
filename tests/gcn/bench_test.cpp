// Hidden timing of the graph-convolution plugins at the default resolution
// (the default assets: 3505 garment and 6490 body vertices), one sample, best
// of several runs. Not a unit test: run `OMP_NUM_THREADS=1 test_gcn "[.bench]"`.
#include <drape/assets.hpp>
#include <drape/graph.hpp>

#include <catch2/catch.hpp>

#include <chrono>
#include <cstdio>

#include "gcn_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

template <typename F>
double best_ms(F&& f, int runs) {
  double best = 1e30;
  for (int r = 0; r < runs; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

void time_node(const std::string& plugin, const std::string& params, const std::map<std::string, Tensor>& inputs,
               const Assets& assets, int runs = 20) {
  auto node = make_node(plugin, params);
  ShapeMap shapes;
  TensorIn in;
  for (const auto& [k, t] : inputs) {
    shapes[k] = t.shape();
    in[k] = &t;
  }
  std::map<std::string, Tensor> outputs, grads_out, grads_in;
  TensorOut out, gin;
  TensorIn out_c, gout;
  for (const auto& [k, s] : node->setup(shapes, {plugin, 1, &assets})) {
    outputs[k] = Tensor(1, s);
    grads_out[k] = random_tensor(1, s.rows, s.cols, 3);
  }
  for (auto& [k, t] : outputs) {
    out[k] = &t;
    out_c[k] = &t;
  }
  for (auto& [k, t] : grads_out) gout[k] = &t;
  for (const auto& [k, t] : inputs) grads_in[k] = Tensor(1, t.shape());
  for (auto& [k, t] : grads_in) gin[k] = &t;
  const double fwd = best_ms([&] { node->forward(in, out); }, runs);
  const double bwd = best_ms([&] { node->backward(in, out_c, gout, gin); }, runs);
  std::size_t weights = 0;
  for (const auto& [k, w] : node->weights()) weights += w.value.size();
  std::printf("%-12s %-44s forward %7.3f ms  backward %7.3f ms  %8.2f M multiply-adds  %8zu weights\n", plugin.c_str(),
              params.c_str(), fwd, bwd, node->flops_per_sample() / 1e6, weights);
}

}  // namespace

TEST_CASE("timing of the graph-convolution plugins at the default resolution", "[.bench]") {
  const auto assets = build_assets(plugins(), AssetsSpec{});
  const int ng = assets->garment->mesh.num_vertices(), nb = assets->body.num_vertices();
  std::printf("garment %d vertices (levels", ng);
  for (const auto& l : assets->hierarchy.levels) std::printf(" %d", l.mesh.num_vertices());
  std::printf("), body %d vertices, %d eigenvectors\n", nb, int(assets->eigenvectors.cols()));
  const Tensor body = random_tensor(1, nb, 3, 1, 0.5f);
  const Tensor garment_features = random_tensor(1, ng, 64, 2);
  const Tensor global = random_tensor(1, 1, 128, 3);
  time_node("cnn1d", "{}", {{"body", body}}, *assets);
  time_node("gcn", "{}", {{"body", body}}, *assets);
  time_node("gcn_learned", "{}", {{"body", body}}, *assets);
  time_node("msgcn", "{}", {{"x", garment_features}}, *assets);
  time_node("gcn_decoder", "{}", {{"x", garment_features}}, *assets);
  time_node("spectral", "{}", {{"x", global}}, *assets);
  time_node("spectral", "{k: 256}", {{"x", global}}, *assets);

  // The seed's model (Fig. 6.2) with the default plugins: cnn1d -> 1-layer MLP ->
  // gather by the correspondences -> msgcn, plus the spectral residual on the global feature.
  std::string indices;
  for (std::size_t i = 0; i < assets->correspondence.size(); ++i)
    indices += (i ? "," : "") + std::to_string(assets->correspondence[i]);
  const std::string text = R"(
inputs:
  body: [body_vertices, 3]
  rest: [garment_vertices, 3]
nodes:
  encoder:  { type: cnn1d,    in: body }
  transfer: { type: linear,   in: encoder.features, params: { width: 64, activation: leaky_relu } }
  pick:     { type: gather,   in: transfer, params: { indices: [)" + indices + R"(] } }
  decoder:  { type: msgcn,    in: pick }
  residual: { type: spectral, in: encoder.global }
  offset:   { type: add,      in: [decoder, residual.out] }
  garment:  { type: add,      in: [offset, rest] }
outputs: { garment: garment }
)";
  Graph g(parse_graph_text(text, "model.yaml"), plugins(), {assets->dims(), assets.get(), 1});
  const std::map<std::string, Tensor> in{{"body", body}, {"rest", random_tensor(1, ng, 3, 4)}};
  const double ms = best_ms([&] { g.forward(in); }, 20);
  std::printf("full model (cnn1d, linear 64, gather, msgcn, spectral k=%d, add): forward %.3f ms, %.2f M multiply-adds\n",
              int(assets->eigenvectors.cols()), ms, g.flops_per_sample() / 1e6);
  SUCCEED();
}
