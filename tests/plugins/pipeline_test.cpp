// The plugins together in a graph: cnn1d -> linear -> gather -> mlp, trained
// with the l2 loss by plain gradient descent.
#include <drape/graph.hpp>

#include <catch2/catch.hpp>

#include "plugin_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

const char* kGraph = R"(
inputs:
  body: [body_vertices, 3]
  target: [garment_vertices, 3]
nodes:
  encoder:  { type: cnn1d,  in: body,             params: { channels: [8, 16], kernel: 3 } }
  transfer: { type: linear, in: encoder.features, params: { width: 8, activation: leaky_relu } }
  pick:     { type: gather, in: transfer,         params: { indices: [0, 3, 5, 9, 12, 17] } }
  decoder:  { type: mlp,    in: pick,             params: { widths: [32] } }
outputs: { garment: decoder }
losses:
  l2: 1.0
)";

}  // namespace

TEST_CASE("cnn1d -> linear -> gather -> mlp builds with the expected shapes", "[pipeline]") {
  Graph g(parse_graph_text(kGraph, "pipeline.yaml"), plugins(), {{{"body_vertices", 20}, {"garment_vertices", 6}}});
  const auto nodes = g.describe();
  REQUIRE(nodes.size() == 5);
  std::map<std::string, Graph::NodeInfo> by_name;
  for (const auto& n : nodes) by_name[n.name] = n;
  CHECK(by_name["encoder"].outputs[0] == std::pair<std::string, Shape>{"features", {20, 16}});
  CHECK(by_name["encoder"].outputs[1] == std::pair<std::string, Shape>{"global", {1, 16}});
  CHECK(by_name["transfer"].outputs[0].second == Shape{20, 8});
  CHECK(by_name["pick"].outputs[0].second == Shape{6, 8});
  CHECK(by_name["decoder"].outputs[0].second == Shape{6, 3});
  CHECK(by_name["l2"].is_loss);
  CHECK(g.flops_per_sample() > 0.0);

  g.forward({{"body", random_tensor(3, 20, 3, 1)}, {"target", random_tensor(3, 6, 3, 2)}});
  const Tensor& out = g.output("garment");
  CHECK(out.batch() == 3);
  CHECK(out.shape() == Shape{6, 3});
  CHECK(std::isfinite(g.loss()));
}

TEST_CASE("plain gradient steps through the four plugins reduce the l2 loss", "[pipeline]") {
  Graph g(parse_graph_text(kGraph, "pipeline.yaml"), plugins(),
          {{{"body_vertices", 20}, {"garment_vertices", 6}}, nullptr, 17});
  const std::map<std::string, Tensor> in{{"body", random_tensor(4, 20, 3, 3)}, {"target", random_tensor(4, 6, 3, 4, 0.5f)}};
  g.forward(in);
  const double initial = g.loss();
  double previous = initial;
  int decreases = 0;
  for (int step = 0; step < 20; ++step) {
    g.zero_grad();
    g.backward();
    for (auto& [name, w] : g.weights()) w->value.vec() -= 0.02f * w->grad.vec();
    g.forward(in);
    decreases += g.loss() < previous;
    previous = g.loss();
  }
  INFO("loss " << initial << " -> " << previous);
  CHECK(decreases == 20);
  CHECK(previous < 0.5 * initial);
}
