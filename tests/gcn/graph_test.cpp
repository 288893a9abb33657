// The graph-convolution plugins together, as the seed's model (Fig. 6.2) in
// miniature: encoder -> 1-layer MLP -> gather to garment vertices -> msgcn,
// plus the spectral residual, trained with L2; and the encoders swap in place.
#include <drape/energy.hpp>
#include <drape/graph.hpp>

#include <catch2/catch.hpp>

#include "gcn_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

std::string model(const std::string& encoder, const Assets& a) {
  // Garment vertex i takes body vertex i mod Nb (a stand-in for the correspondences).
  std::string indices;
  for (int i = 0; i < a.garment->mesh.num_vertices(); ++i)
    indices += (i ? ", " : "") + std::to_string(i % a.body.num_vertices());
  return R"(
inputs:
  body: [body_vertices, 3]
  rest: [garment_vertices, 3]
  target: [garment_vertices, 3]
nodes:
  encoder:  { type: )" + encoder + R"( }
  transfer: { type: linear,   in: encoder.features, params: { width: 6, activation: leaky_relu } }
  pick:     { type: gather,   in: transfer, params: { indices: [)" + indices + R"(] } }
  decoder:  { type: msgcn,    in: pick, params: { channels: [8, 8, 6, 6], layers: [1] } }
  residual: { type: spectral, in: encoder.global, params: { widths: [16], init_scale: 0.1 } }
  offset:   { type: add,      in: [decoder, residual.out] }
  garment:  { type: add,      in: [offset, rest] }
outputs: { garment: garment }
losses:
  l2: 1.0
)";
}

GraphOptions options_for(const Assets& a, std::uint64_t seed = 3) {
  return {{{"body_vertices", a.body.num_vertices()}, {"garment_vertices", a.garment->mesh.num_vertices()}}, &a, seed};
}

}  // namespace

TEST_CASE("encoder -> transfer -> gather -> msgcn + spectral builds with every encoder in place", "[gcn][graph]") {
  const auto assets = gcn_assets();
  const int ng = assets->garment->mesh.num_vertices();
  for (const char* encoder : {"{ type: gcn_learned, in: body, params: { channels: [8, 12], stride: 2 } }",
                              "{ type: gcn, in: body, params: { channels: [8, 12] } }",
                              "{ type: cnn1d, in: body, params: { channels: [8, 12], kernel: 3 } }"}) {
    INFO(encoder);
    std::string text = model("X", *assets);
    text.replace(text.find("{ type: X }"), 11, encoder);
    Graph g(parse_graph_text(text, "model.yaml"), plugins(), options_for(*assets));
    CHECK(g.flops_per_sample() > 0.0);
    g.forward({{"body", random_tensor(2, assets->body.num_vertices(), 3, 1)},
               {"rest", random_tensor(2, ng, 3, 2)},
               {"target", random_tensor(2, ng, 3, 3)}});
    CHECK(g.output("garment").shape() == Shape{ng, 3});
    CHECK(std::isfinite(g.loss()));
  }
}

TEST_CASE("plain gradient steps through gcn_learned, msgcn and spectral reduce the loss", "[gcn][graph]") {
  const auto assets = gcn_assets();
  const int ng = assets->garment->mesh.num_vertices(), nb = assets->body.num_vertices();
  std::string text = model("X", *assets);
  text.replace(text.find("{ type: X }"), 11, "{ type: gcn_learned, in: body, params: { channels: [8, 12], stride: 2 } }");
  Graph g(parse_graph_text(text, "model.yaml"), plugins(), options_for(*assets, 11));
  // The target is the rest shape moved by a displacement the decoder can learn:
  // a shift plus a smooth field over the garment.
  const Tensor rest = random_tensor(4, ng, 3, 5);
  Tensor target = rest;
  for (int b = 0; b < 4; ++b)
    for (int v = 0; v < ng; ++v) {
      const double s = assets->garment->mesh.vertices(v, 0) / 0.15;
      target(b, v, 0) += 0.3f;
      target(b, v, 1) += float(-0.2 + 0.3 * s);
      target(b, v, 2) += float(0.1 * s * s);
    }
  const std::map<std::string, Tensor> in{{"body", random_tensor(4, nb, 3, 4)}, {"rest", rest}, {"target", target}};
  g.forward(in);
  const double initial = g.loss();
  double previous = initial;
  int decreases = 0;
  for (int step = 0; step < 30; ++step) {
    g.zero_grad();
    g.backward();
    for (auto& [name, w] : g.weights()) w->value.vec() -= 0.02f * w->grad.vec();
    g.forward(in);
    decreases += g.loss() < previous;
    previous = g.loss();
  }
  INFO("loss " << initial << " -> " << g.loss());
  CHECK(decreases == 30);
  CHECK(g.loss() < 0.3 * initial);
}
