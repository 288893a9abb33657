// The seed's losses in one graph: ports bind by name (pred to the first output,
// target and body to the graph inputs of those names), every term equals the
// loss node run on its own, and a missing body input is a configuration error.
#include <drape/graph.hpp>

#include <catch2/catch.hpp>

#include "losses_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

const char* kGraph = R"(
inputs:
  rest: [garment_vertices, 3]
  target: [garment_vertices, 3]
  body: [body_vertices, 3]
nodes:
  garment: { type: scale, in: rest, params: { factor: 1.02 } }
outputs: { garment: garment }
losses:
  l2: 1.0
  v2v: 1.0
  direction: 0.5
  edge: 1.0
  deformation: 2.0
  laplacian: 1.0
  spectral_loss: { type: spectral_loss, weight: 3.0, params: { k: 16 } }
)";

// The coarse T-shirt's template data with a box "body" around its middle.
Assets tshirt_with_box() {
  Assets a = coarse_tshirt();
  const Mesh& g = a.garment->mesh;
  const Eigen::RowVector3d centre = 0.5 * (g.vertices.colwise().minCoeff() + g.vertices.colwise().maxCoeff());
  a.body = cube_body(0.12);
  a.body.vertices.rowwise() += centre;
  return a;
}

}  // namespace

TEST_CASE("the seed's losses bind pred, target and body by name in a graph", "[losses][graph]") {
  const Assets assets = tshirt_with_box();
  const int n = assets.garment->mesh.num_vertices();
  const std::map<std::string, int> dims{{"garment_vertices", n}, {"body_vertices", 8}};
  Graph graph(parse_graph_text(kGraph, "losses.yaml"), plugins(), {dims, &assets, 1});

  const Eigen::MatrixX3d rest = assets.garment->mesh.vertices;
  const Tensor noise = random_tensor(2, n, 3, 77, 0.01f);
  std::map<std::string, Tensor> in{{"rest", tensor_of(std::vector<Eigen::MatrixX3d>{rest, rest})},
                                   {"target", tensor_of(std::vector<Eigen::MatrixX3d>{rest, rest})},
                                   {"body", tensor_of(std::vector<Eigen::MatrixX3d>{assets.body.vertices, assets.body.vertices})}};
  for (int b = 0; b < 2; ++b) in["target"].mat(b) += noise.mat(b);
  graph.forward(in);
  const auto terms = graph.loss_terms();
  REQUIRE(terms.size() == 7);
  const Tensor pred = graph.output("garment");
  const std::map<std::string, std::pair<std::string, double>> expected_weights{
      {"l2", {"{}", 1.0}},          {"v2v", {"{}", 1.0}},       {"direction", {"{}", 0.5}},      {"edge", {"{}", 1.0}},
      {"deformation", {"{}", 2.0}}, {"laplacian", {"{}", 1.0}}, {"spectral_loss", {"{k: 16}", 3.0}}};
  double total = 0.0;
  for (const auto& [name, spec] : expected_weights) {
    const PluginDescriptor& d = plugins().get(name);
    std::map<std::string, Tensor> inputs{{"pred", pred}, {"target", in.at("target")}};
    for (const auto& port : d.inputs)
      if (port.name == "body") inputs["body"] = in.at("body");
    auto node = make_node(name, spec.first);
    const Tensor alone = run_forward(*node, inputs, {name, 0, &assets}).at("loss");
    INFO(name);
    CHECK(terms.at(name) == Approx(0.5 * (alone(0, 0, 0) + alone(1, 0, 0))).epsilon(1e-5));
    CHECK(terms.at(name) > 0.0);
    total += spec.second * terms.at(name);
  }
  CHECK(graph.loss() == Approx(total).epsilon(1e-6));
  graph.backward();  // every loss's backward runs inside the graph

  // Without a `body` input the body-aware losses cannot bind their port.
  std::string text = kGraph;
  text.erase(text.find("  body: [body_vertices, 3]\n"), std::string("  body: [body_vertices, 3]\n").size());
  const std::string message = message_of([&] { Graph(parse_graph_text(text, "losses.yaml"), plugins(), {dims, &assets, 1}); });
  CHECK_THAT(message, Catch::Contains("input 'body' is not connected"));
}
