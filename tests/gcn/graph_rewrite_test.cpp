// The graph runs a row gather before a concat of one repeated row
// (graph_rewrite.hpp): the same outputs and gradients, bit for bit, as the
// graph as written; the graph as written is what errors name.
#include <drape/errors.hpp>
#include <drape/graph.hpp>

#include <catch2/catch.hpp>

#include "gcn_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

// The sized models' pattern in miniature: the encoder's per-vertex features
// with the grade appended, then gathered to the garment. `grade_rows` is how
// the grade input's rows are declared: "1" lets the rewrite apply, a
// symbolic size of one does not (the same graph as written).
std::string sized_model(const Assets& a, const std::string& grade_rows, const std::string& extra = "") {
  std::string indices;
  for (int i = 0; i < a.garment->mesh.num_vertices(); ++i)
    indices += (i ? ", " : "") + std::to_string((7 * i) % a.body.num_vertices());
  return R"(
inputs:
  body: [body_vertices, 3]
  rest: [garment_vertices, 3]
  target: [garment_vertices, 3]
  grade: [)" + grade_rows + R"(, 1]
nodes:
  encoder:  { type: cnn1d,    in: body, params: { channels: [8, 12], kernel: 3 } }
  graded:   { type: concat,   in: { a: encoder.features, b: grade } }
  gathered: { type: gather,   in: graded, params: { indices: [)" + indices + R"(] } }
  transfer: { type: linear,   in: gathered, params: { width: 6, activation: leaky_relu } }
  decoder:  { type: msgcn,    in: transfer, params: { channels: [8, 8, 6, 6], layers: [1] } }
  garment:  { type: add,      in: [decoder, rest] }
)" + extra + R"(
outputs: { garment: garment }
losses:
  l2: 1.0
)";
}

GraphOptions sized_options(const Assets& a) {
  return {{{"body_vertices", a.body.num_vertices()}, {"garment_vertices", a.garment->mesh.num_vertices()}, {"one", 1}},
          &a, 5};
}

std::vector<std::string> built_node_names(const Graph& g) {
  std::vector<std::string> names;
  for (const auto& n : g.describe()) names.push_back(n.name + " (" + n.type + ")");
  return names;
}

}  // namespace

TEST_CASE("a gather after a concat of one repeated row runs first, with the same outputs and gradients", "[gcn][graph]") {
  const auto assets = gcn_assets();
  const int ng = assets->garment->mesh.num_vertices(), nb = assets->body.num_vertices();
  Graph rewritten(parse_graph_text(sized_model(*assets, "1"), "sized.yaml"), plugins(), sized_options(*assets));
  Graph as_written(parse_graph_text(sized_model(*assets, "one"), "sized.yaml"), plugins(), sized_options(*assets));

  const auto names = built_node_names(rewritten);
  CHECK(std::count(names.begin(), names.end(), "gathered_rows (gather)") == 1);
  CHECK(std::count(names.begin(), names.end(), "gathered (concat)") == 1);
  CHECK(std::count(names.begin(), names.end(), "graded (concat)") == 0);
  const auto written = built_node_names(as_written);
  CHECK(std::count(written.begin(), written.end(), "graded (concat)") == 1);
  CHECK(std::count(written.begin(), written.end(), "gathered (gather)") == 1);
  // The spec stays as written (checkpoints store it).
  CHECK(rewritten.spec().text.find("gathered_rows") == std::string::npos);

  Tensor grade(3, 1, 1);
  for (int b = 0; b < 3; ++b) grade(b, 0, 0) = 0.8f + 0.2f * static_cast<float>(b);
  const std::map<std::string, Tensor> in{{"body", random_tensor(3, nb, 3, 1)},
                                         {"rest", random_tensor(3, ng, 3, 2)},
                                         {"target", random_tensor(3, ng, 3, 3)},
                                         {"grade", grade}};
  for (Graph* g : {&rewritten, &as_written}) {
    g->forward(in);
    g->zero_grad();
    g->backward();
  }
  REQUIRE(rewritten.output("garment").vec().size() == as_written.output("garment").vec().size());
  CHECK((rewritten.output("garment").vec().array() == as_written.output("garment").vec().array()).all());
  CHECK(rewritten.loss() == as_written.loss());
  auto wa = rewritten.weights(), wb = as_written.weights();
  REQUIRE(wa.size() == wb.size());
  for (std::size_t k = 0; k < wa.size(); ++k) {
    INFO(wa[k].first);
    CHECK(wa[k].first == wb[k].first);
    CHECK((wa[k].second->value.vec().array() == wb[k].second->value.vec().array()).all());
    CHECK((wa[k].second->grad.vec().array() == wb[k].second->grad.vec().array()).all());
    CHECK(wa[k].second->grad.vec().norm() > 0);
  }
}

TEST_CASE("the gather stays after the concat when the concat's rows are read elsewhere", "[gcn][graph]") {
  const auto assets = gcn_assets();
  // A second reader of `graded`: the whole concat is needed.
  const std::string extra = "  pooled: { type: gather, in: graded, params: { indices: [0, 1] } }\n";
  std::string text = sized_model(*assets, "1", extra);
  text.replace(text.find("outputs: { garment: garment }"), 29, "outputs: { garment: garment, pooled: pooled }");
  Graph g(parse_graph_text(text, "sized.yaml"), plugins(), sized_options(*assets));
  const auto names = built_node_names(g);
  CHECK(std::count(names.begin(), names.end(), "graded (concat)") == 1);
  CHECK(std::count(names.begin(), names.end(), "gathered (gather)") == 1);
}

TEST_CASE("a mistake in a graph the rewrite applies to is named as written", "[gcn][graph]") {
  const auto assets = gcn_assets();
  std::string text = sized_model(*assets, "1");
  text.replace(text.find("a: encoder.features"), 19, "a: encoder.featurez");
  try {
    Graph g(parse_graph_text(text, "sized.yaml"), plugins(), sized_options(*assets));
    FAIL("built a graph with an unknown port");
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(what.find("node 'graded' (concat)") != std::string::npos);
    CHECK(what.find("featurez") != std::string::npos);
    CHECK(what.find("gathered_rows") == std::string::npos);
  }
}
