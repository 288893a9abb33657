#include <drape/gradcheck.hpp>
#include <drape/graph.hpp>

#include <catch2/catch.hpp>

#include <fstream>
#include <utility>

#include "test_nodes.hpp"

using namespace drape;

namespace {

const char* kGraph = R"(
inputs:
  rest: [n, 3]
  target: [n, 3]
nodes:
  lift:  { type: test_affine, in: rest }
  twice: { type: scale, in: lift.y, params: { factor: 2.0 } }
  sum:   { type: add, in: [twice, rest] }
outputs: { garment: sum }
losses:
  l2: 1.0
)";

std::string error_of(const std::string& yaml, const std::map<std::string, int>& dims = {{"n", 4}}) {
  try {
    Graph g(parse_graph_text(yaml, "g.yaml"), test::registry_with_test_nodes(), {dims});
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

void write(const std::filesystem::path& p, const std::string& text) { std::ofstream(p) << text; }

Tensor random_tensor(int b, int r, int c, float scale = 1.0f) {
  Tensor t(b, r, c);
  for (std::size_t i = 0; i < t.size(); ++i) t.data()[i] = scale * std::sin(0.7f * static_cast<float>(i) + 0.3f);
  return t;
}

}  // namespace

TEST_CASE("a graph builds, orders its nodes and infers shapes", "[graph]") {
  Graph g(parse_graph_text(kGraph, "g.yaml"), test::registry_with_test_nodes(), {{{"n", 5}}});
  const auto nodes = g.describe();
  REQUIRE(nodes.size() == 4);
  CHECK(nodes[0].name == "lift");
  CHECK(nodes[3].name == "l2");
  CHECK(nodes[3].is_loss);
  CHECK(nodes[2].outputs[0].second == Shape{5, 3});
  CHECK(g.weights().size() == 2);
}

TEST_CASE("forward computes the graph and backward matches finite differences", "[graph]") {
  Graph g(parse_graph_text(kGraph, "g.yaml"), test::registry_with_test_nodes(), {{{"n", 3}}});
  std::map<std::string, Tensor> in{{"rest", random_tensor(2, 3, 3)}, {"target", random_tensor(2, 3, 3, 0.5f)}};
  g.forward(in);
  // garment = 2 * (1.5 x + 0.25) + x
  const Tensor& out = g.output("garment");
  CHECK(out(1, 2, 1) == Approx(4.0 * in["rest"](1, 2, 1) + 0.5));
  const double loss = g.loss();
  g.zero_grad();
  g.backward();
  for (auto& [name, w] : g.weights()) {
    for (int c = 0; c < 3; ++c) {
      const float saved = w->value(0, 0, c);
      const float h = 1e-3f;
      w->value(0, 0, c) = saved + h;
      g.forward(in);
      const double plus = g.loss();
      w->value(0, 0, c) = saved - h;
      g.forward(in);
      const double minus = g.loss();
      w->value(0, 0, c) = saved;
      CHECK(w->grad(0, 0, c) == Approx((plus - minus) / (2 * h)).epsilon(1e-2).margin(1e-4));
    }
  }
  g.forward(in);
  CHECK(g.loss() == Approx(loss));
}

TEST_CASE("inference skips the losses and needs no target", "[graph]") {
  Graph g(parse_graph_text(kGraph, "g.yaml"), test::registry_with_test_nodes(), {{{"n", 3}}});
  g.forward({{"rest", random_tensor(1, 3, 3)}}, false);
  CHECK(g.output("garment").batch() == 1);
  CHECK_THROWS_WITH(g.forward({{"rest", random_tensor(1, 3, 3)}}, true), Catch::Contains("'target'"));
}

TEST_CASE("a wrong-size input says what was expected", "[graph]") {
  Graph g(parse_graph_text(kGraph, "g.yaml"), test::registry_with_test_nodes(), {{{"n", 3}}});
  CHECK_THROWS_WITH(g.forward({{"rest", random_tensor(1, 7, 3)}}, false),
                    Catch::Contains("'rest' has 7 x 3") && Catch::Contains("expects 3 x 3"));
}

TEST_CASE("graph errors name the file, the line and the node", "[graph]") {
  // Unknown type with close matches, on the node's line.
  std::string e = error_of("inputs: { rest: [n, 3] }\nnodes:\n  a: { type: scael, in: rest }\noutputs: [a]\n");
  CHECK_THAT(e, Catch::Contains("g.yaml:3") && Catch::Contains("scael") && Catch::Contains("did you mean 'scale'"));
  // Missing input.
  e = error_of("inputs: { rest: [n, 3] }\nnodes:\n  a: { type: add, in: [rest] }\noutputs: [a]\n");
  CHECK_THAT(e, Catch::Contains("g.yaml:3") && Catch::Contains("input 'b' is not connected"));
  // Extra input.
  e = error_of("inputs: { rest: [n, 3] }\nnodes:\n  a: { type: scale, in: [rest, rest] }\noutputs: [a]\n");
  CHECK_THAT(e, Catch::Contains("too many inputs"));
  // Unknown reference.
  e = error_of("inputs: { rest: [n, 3] }\nnodes:\n  a: { type: scale, in: reest }\noutputs: [a]\n");
  CHECK_THAT(e, Catch::Contains("unknown input 'reest'") && Catch::Contains("did you mean 'rest'"));
  // Unknown output port.
  e = error_of("inputs: { rest: [n, 3] }\nnodes:\n  a: { type: scale, in: rest }\n  b: { type: scale, in: a.outt }\noutputs: [b]\n");
  CHECK_THAT(e, Catch::Contains("g.yaml:4") && Catch::Contains("no output 'outt'"));
  // Cycle.
  e = error_of("inputs: { rest: [n, 3] }\nnodes:\n  a: { type: add, in: [rest, b] }\n  b: { type: scale, in: a }\noutputs: [b]\n");
  CHECK_THAT(e, Catch::Contains("cycle") && Catch::Contains("a -> b -> a"));
  // Shape mismatch.
  e = error_of("inputs: { rest: [n, 3], other: [n, 2] }\nnodes:\n  a: { type: add, in: [rest, other] }\noutputs: [a]\n");
  CHECK_THAT(e, Catch::Contains("g.yaml:3") && Catch::Contains("node 'a' (add)") && Catch::Contains("cannot add"));
  // A number too large for a size (it was "unknown size").
  e = error_of("inputs: { rest: [99999999999, 3] }\nnodes:\n  a: { type: scale, in: rest }\noutputs: [a]\n");
  CHECK_THAT(e, Catch::Contains("size 99999999999 is too large") && !Catch::Contains("unknown size"));
  // Unknown symbolic size.
  e = error_of("inputs: { rest: [m, 3] }\nnodes:\n  a: { type: scale, in: rest }\noutputs: [a]\n");
  CHECK_THAT(e, Catch::Contains("unknown size 'm'"));
  // Unknown top-level key and node key.
  CHECK_THAT(error_of("inptus: {}\n"), Catch::Contains("g.yaml:1") && Catch::Contains("did you mean 'inputs'"));
  CHECK_THAT(error_of("nodes:\n  a: { type: scale, parms: {} }\n"), Catch::Contains("g.yaml:2") && Catch::Contains("'parms'"));
  // Bad parameter value, on its own line.
  e = error_of("inputs: { rest: [n, 3] }\nnodes:\n  a:\n    type: scale\n    in: rest\n    params:\n      factor: big\noutputs: [a]\n");
  CHECK_THAT(e, Catch::Contains("g.yaml:7") && Catch::Contains("factor"));
  // A loss whose type is not a loss.
  CHECK_THAT(error_of(std::string(kGraph) + "  scale: 1.0\n"), Catch::Contains("not a loss"));
  // A loss weight that is not a finite number >= 0 (a negative one would train the loss up).
  for (const char* weight : {".nan", "-1", ".inf"})
    CHECK_THAT(error_of(std::string(kGraph).substr(0, std::string(kGraph).rfind("l2:")) + "l2: " + weight + "\n"),
               Catch::Contains("g.yaml:") && Catch::Contains("finite number >= 0"));
  // A bare word as the last line (a file cut in the middle of a key): yaml-cpp reads it as a key with no value.
  CHECK_THAT(error_of(std::string(kGraph) + "  mse\n"), Catch::Contains("'mse' has no value"));
  // A node named as a graph input: every node reading the input read the
  // node instead (a loss's bound `body` was fed a garment), or a cycle was
  // reported.
  e = error_of("inputs: { rest: [n, 3], body: [n, 3] }\nnodes:\n  body: { type: scale, in: rest }\noutputs: [body]\n");
  CHECK_THAT(e, Catch::Contains("g.yaml:3") && Catch::Contains("node 'body' has the name of a graph input (g.yaml:1)"));
  e = error_of("inputs: { rest: [n, 3] }\nnodes:\n  rest: { type: scale, in: rest }\noutputs: [rest]\n");
  CHECK_THAT(e, Catch::Contains("g.yaml:3") && Catch::Contains("has the name of a graph input") && !Catch::Contains("cycle"));
  // A '.' in a node's name: no reference can name it (node.port).
  e = error_of("inputs: { rest: [n, 3] }\nnodes:\n  a.b: { type: scale, in: rest }\noutputs: [a.b]\n");
  CHECK_THAT(e, Catch::Contains("g.yaml:3") && Catch::Contains("node 'a.b': a name cannot hold '.'"));
}

TEST_CASE("malformed YAML names the file and line", "[graph]") {
  test::TempDir dir;
  write(dir / "bad.yaml", "nodes:\n  a: { type: scale, in: [rest }\n");
  try {
    parse_graph_file(dir / "bad.yaml");
    FAIL("no error");
  } catch (const ConfigError& e) {
    CHECK_THAT(e.what(), Catch::Contains("bad.yaml:2") && Catch::Contains("malformed YAML"));
  }
  // A binary file: yaml-cpp's message carried one of its control bytes raw to the terminal.
  write(dir / "binary.yaml", std::string("\x7f" "ELF\x02\x01\n\x01\0\0\0\x1b[31m", 16));
  CHECK_THROWS_WITH(parse_graph_file(dir / "binary.yaml"), Catch::Contains("binary.yaml:2") && Catch::Contains("not a text file"));
}

TEST_CASE("an ablation overrides a few nodes and loss weights of its base", "[graph]") {
  test::TempDir dir;
  write(dir / "base.yaml", kGraph);
  std::filesystem::create_directories(dir / "ablations");
  write(dir / "ablations" / "more.yaml",
        "base: ../base.yaml\nnodes:\n  twice: { params: { factor: 3.0 } }\nlosses:\n  l2: 0.5\n");
  const GraphSpec spec = parse_graph_file(dir / "ablations" / "more.yaml");
  Graph g(spec, test::registry_with_test_nodes(), {{{"n", 2}}});
  std::map<std::string, Tensor> in{{"rest", random_tensor(1, 2, 3)}, {"target", random_tensor(1, 2, 3)}};
  g.forward(in);
  CHECK(g.output("garment")(0, 1, 2) == Approx(3.0 * (1.5 * in["rest"](0, 1, 2) + 0.25) + in["rest"](0, 1, 2)));
  CHECK(g.loss() == Approx(0.5 * g.loss_terms().at("l2")));
  // The resolved text holds no base and rebuilds the same graph.
  CHECK(spec.text.find("base") == std::string::npos);
  Graph again(parse_graph_text(spec.text, "resolved"), test::registry_with_test_nodes(), {{{"n", 2}}});
  again.forward(in);
  CHECK(again.output("garment")(0, 1, 2) == Approx(g.output("garment")(0, 1, 2)));

  // Type change drops the old params; a null removes; weight 0 disables.
  write(dir / "ablations" / "swap.yaml", "base: ../base.yaml\nnodes:\n  twice: { type: test_affine }\nlosses:\n  l2: 0\n");
  Graph swapped(parse_graph_file(dir / "ablations" / "swap.yaml"), test::registry_with_test_nodes(), {{{"n", 2}}});
  CHECK(swapped.weights().size() == 4);
  swapped.forward(in);
  CHECK(swapped.loss_terms().empty());
  // Errors in an ablation point at the ablation file.
  write(dir / "ablations" / "typo.yaml", "base: ../base.yaml\nnodes:\n  twice: { type: scalee }\n");
  CHECK_THROWS_WITH(Graph(parse_graph_file(dir / "ablations" / "typo.yaml"), test::registry_with_test_nodes(), {{{"n", 2}}}),
                    Catch::Contains("typo.yaml:3") && Catch::Contains("did you mean 'scale'"));
  // An override of a node the base lacks (a misspelt name): named as one, with the close match.
  write(dir / "ablations" / "missing.yaml", "base: ../base.yaml\nnodes:\n  twcie: { params: { factor: 3.0 } }\n");
  CHECK_THROWS_WITH(parse_graph_file(dir / "ablations" / "missing.yaml"),
                    Catch::Contains("missing.yaml:3") && Catch::Contains("overrides no node of the base graph") &&
                        Catch::Contains("did you mean 'twice'"));
  // An output naming no node is blamed on the `outputs:` entry, not on the loss that reads it.
  write(dir / "ablations" / "output.yaml", "base: ../base.yaml\noutputs: { garment: summ }\n");
  CHECK_THROWS_WITH(Graph(parse_graph_file(dir / "ablations" / "output.yaml"), test::registry_with_test_nodes(), {{{"n", 2}}}),
                    Catch::Contains("output.yaml:2") && Catch::Contains("output 'garment': unknown input 'summ'") &&
                        Catch::Contains("did you mean 'sum'"));
  write(dir / "loop.yaml", "base: loop.yaml\n");
  CHECK_THROWS_WITH(parse_graph_file(dir / "loop.yaml"), Catch::Contains("loops back"));
}

TEST_CASE("the gradient checker catches a wrong gradient", "[gradcheck]") {
  // A node whose backward is off by a factor must fail the check.
  class Wrong final : public Node {
   public:
    ShapeMap setup(const ShapeMap& in, const NodeContext&) override { return {{"y", in.at("x")}}; }
    void forward(const TensorIn& in, const TensorOut& out) override { out.at("y")->vec() = in.at("x")->vec() * 2.0f; }
    void backward(const TensorIn&, const TensorIn&, const TensorIn& g, const TensorOut& gin) override {
      gin.at("x")->vec() = g.at("y")->vec() * 2.2f;
    }
  } wrong;
  CHECK_FALSE(check_node_gradients(wrong, {{"x", random_tensor(2, 4, 3)}}).ok(1e-2));
  test::Affine right;
  const auto report = check_node_gradients(right, {{"x", random_tensor(2, 4, 3)}});
  INFO(report.str());
  CHECK(report.ok(1e-2));
  CHECK(report.entries.size() == 3);  // input x, weights b and w
}

TEST_CASE("backward asks a node only for the input gradients that reach a weight (propagate_down)", "[graph]") {
  // A node that records which input gradients backward asked it for.
  static std::vector<std::vector<std::string>> asked;
  class Recorder final : public Node {
   public:
    ShapeMap setup(const ShapeMap& in, const NodeContext&) override { return {{"y", in.at("a")}}; }
    void forward(const TensorIn& in, const TensorOut& out) override {
      out.at("y")->vec() = in.at("a")->vec() + in.at("b")->vec();
    }
    void backward(const TensorIn&, const TensorIn&, const TensorIn& g, const TensorOut& gin) override {
      std::vector<std::string> ports;
      for (const auto& [port, t] : gin) {
        ports.push_back(port);
        t->vec() = g.at("y")->vec();
      }
      asked.push_back(ports);
    }
  };
  Registry reg;
  reg.load_path({test::plugin_dir().string()});
  reg.add(test::affine_descriptor());
  PluginDescriptor d;
  d.kind = "op";
  d.name = "test_recorder";
  d.doc = "test node";
  d.inputs = {{"a", "input"}, {"b", "input"}};
  d.outputs = {{"y", "a + b"}};
  d.create_node = [](const Params&) { return std::make_unique<Recorder>(); };
  reg.add(d);
  const char* yaml = R"(
inputs:
  rest: [n, 3]
  target: [n, 3]
nodes:
  first:  { type: test_recorder, in: { a: rest, b: target } }
  lift:   { type: test_affine, in: first }
  second: { type: test_recorder, in: { a: lift.y, b: rest } }
outputs: { garment: second }
losses:
  l2: 1.0
)";
  Graph g(parse_graph_text(yaml, "g.yaml"), reg, {{{"n", 3}}});
  CHECK(g.gradient_ports("first").empty());  // graph inputs only: its backward never runs
  CHECK(g.gradient_ports("lift").empty());   // fed by a node without weights upstream
  CHECK(g.gradient_ports("second") == std::vector<std::string>{"a"});
  CHECK(g.gradient_ports("l2") == std::vector<std::string>{"pred"});  // not the target
  CHECK_THROWS_WITH(g.gradient_ports("nope"), Catch::Contains("no node named 'nope'"));
  g.forward({{"rest", random_tensor(2, 3, 3)}, {"target", random_tensor(2, 3, 3, 0.5f)}});
  g.zero_grad();
  asked.clear();
  g.backward();
  REQUIRE(asked.size() == 1);  // `first` has no weights upstream: never asked
  CHECK(asked[0] == std::vector<std::string>{"a"});
  for (auto& [name, w] : g.weights()) CHECK(w->grad.vec().norm() > 0);  // the weights still learn
  // Per-node times of the last step: every node ran forward, backward only where gradients flow.
  const auto times = g.last_step_times();
  REQUIRE(times.size() == 4);
  CHECK(times[0].backward_ms == 0.0);
  CHECK(times[3].is_loss);
  CHECK(times[3].backward_ms > 0.0);
}

TEST_CASE("forward in two parts: what feeds a node changed between them", "[graph]") {
  Graph g(parse_graph_text(kGraph, "g.yaml"), test::registry_with_test_nodes(), {{{"n", 3}}});
  const std::map<std::string, Tensor> in{{"rest", random_tensor(2, 3, 3)}};
  g.forward_until(in, "twice");
  // lift ran (1.5 x + 0.25); twice and sum, fed by it, did not.
  Tensor& lifted = g.fed_into("twice", "x");
  CHECK(lifted(1, 2, 1) == Approx(1.5 * in.at("rest")(1, 2, 1) + 0.25));
  const auto ran = g.last_forward_times();
  REQUIRE(ran.size() == 1);
  CHECK(ran[0].name == "lift");
  for (std::size_t i = 0; i < lifted.size(); ++i) lifted.data()[i] = 1.0f;
  g.forward_from("twice");
  // garment = 2 * 1 + x
  CHECK(g.output("garment")(1, 2, 1) == Approx(2.0 + in.at("rest")(1, 2, 1)));
  CHECK(g.output("garment")(0, 0, 0) == Approx(2.0 + in.at("rest")(0, 0, 0)));
  // A plain forward afterwards is the graph again.
  g.forward(in, false);
  CHECK(g.output("garment")(1, 2, 1) == Approx(4.0 * in.at("rest")(1, 2, 1) + 0.5));

  CHECK_THROWS_WITH(g.forward_until(in, "twise"), Catch::Contains("no node named 'twise'"));
  CHECK_THROWS_WITH(g.fed_into("lift", "x"), Catch::Contains("graph input 'rest'"));
  CHECK_THROWS_WITH(g.fed_into("twice", "y"), Catch::Contains("no connected port 'y'"));
}

TEST_CASE("forward_until keeps the outputs of nodes whose inputs did not change, when asked", "[graph]") {
  const char* yaml = R"(
inputs:
  rest: [n, 3]
  shift: [n, 3]
nodes:
  lift:  { type: test_affine, in: rest }
  moved: { type: add, in: [lift.y, shift] }
  twice: { type: scale, in: moved, params: { factor: 2.0 } }
outputs: { garment: twice }
)";
  Graph g(parse_graph_text(yaml, "g.yaml"), test::registry_with_test_nodes(), {{{"n", 3}}});
  std::map<std::string, Tensor> in{{"rest", random_tensor(1, 3, 3)}, {"shift", random_tensor(1, 3, 3, 0.1f)}};
  g.forward_until(in, "twice");
  const float lifted = std::as_const(g).fed_into("moved", "a")(0, 1, 2);
  // A weight changed between the passes shows which nodes ran again.
  for (auto& [name, w] : g.weights()) w->value.vec().array() += 1.0f;
  in["shift"] = random_tensor(1, 3, 3, 0.3f);
  g.forward_until(in, "twice", true);
  CHECK(std::as_const(g).fed_into("moved", "a")(0, 1, 2) == lifted);  // lift kept: its input is the same
  CHECK(std::as_const(g).fed_into("twice", "x")(0, 1, 2) == Approx(lifted + in["shift"](0, 1, 2)));  // moved ran: shift changed
  // Without the reuse, or with its input changed, lift runs again.
  g.forward_until(in, "twice");
  CHECK(std::as_const(g).fed_into("moved", "a")(0, 1, 2) != lifted);
  const float relifted = std::as_const(g).fed_into("moved", "a")(0, 1, 2);
  in["rest"] = random_tensor(1, 3, 3, 2.0f);
  g.forward_until(in, "twice", true);
  CHECK(std::as_const(g).fed_into("moved", "a")(0, 1, 2) != relifted);
  // An output handed out by fed_into (and maybe changed) is made again.
  const float made = std::as_const(g).fed_into("moved", "a")(0, 1, 2);
  g.fed_into("moved", "a")(0, 1, 2) = made + 5.0f;
  g.forward_until(in, "twice", true);
  CHECK(std::as_const(g).fed_into("moved", "a")(0, 1, 2) == made);
  // Another batch size: everything runs.
  g.forward_until({{"rest", random_tensor(2, 3, 3, 2.0f)}, {"shift", random_tensor(2, 3, 3, 0.3f)}}, "twice", true);
  CHECK(std::as_const(g).fed_into("moved", "a").batch() == 2);
}

TEST_CASE("a loss named as a node of the same file and a misspelt removal are said as they are", "[graph]") {
  // An outside check: the clash was blamed on a "base graph" the file did not
  // have, and `decodr: null` offered no 'decoder'.
  const std::string clash = "inputs:\n  target: [n, 3]\nnodes:\n  l2: {type: scale, in: target}\n"
                            "outputs: {garment: l2}\nlosses: {l2: 1.0}\n";
  CHECK_THAT(test::message_of([&] { parse_graph_text(clash, "g.yaml"); }),
             Catch::Contains("g.yaml:6") && Catch::Contains("'l2' is a node at line 4 of this file; a loss needs a name of its own"));
  test::TempDir dir;
  std::ofstream(dir / "base.yaml") << "inputs:\n  target: [n, 3]\nnodes:\n  decoder: {type: scale, in: target}\n"
                                      "outputs: {garment: decoder}\n";
  std::ofstream(dir / "child.yaml") << "base: base.yaml\nnodes:\n  decodr: null\n";
  CHECK_THAT(test::message_of([&] { parse_graph_file(dir / "child.yaml"); }),
             Catch::Contains("child.yaml:3") && Catch::Contains("cannot remove 'decodr'") && Catch::Contains("did you mean 'decoder'"));
}
