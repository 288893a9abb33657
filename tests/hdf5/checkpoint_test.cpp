// Checkpoints: exact round trip of weights, graph text, metadata and Adam
// moments; atomic saves; clear errors for missing, mismatched or corrupt files.
#include <catch2/catch.hpp>

#include "test_support.hpp"

#include <drape/io/atomic_file.hpp>
#include <drape/io/checkpoint.hpp>
#include <drape/graph.hpp>
#include <drape/io/h5.hpp>
#include <drape/training/init.hpp>
#include <drape/plugin.hpp>

#include <fstream>
#include <set>

using namespace drape;
using drape::test::TempDir;
using drape::test::message_of;
namespace fs = std::filesystem;

namespace {

// y = x W + b with W [in, width], b [1, width], initialised from the node's seed.
class Dense final : public Node {
 public:
  explicit Dense(int width) : width_(width) {}
  ShapeMap setup(const ShapeMap& in, const NodeContext& ctx) override {
    const Shape s = in.at("x");
    Rng rng(ctx.seed);
    xavier_uniform(add_weight("w", s.cols, width_).value, s.cols, width_, rng);
    uniform_fill(add_weight("b", 1, width_).value, 0.1, rng);
    return {{"y", {s.rows, width_}}};
  }
  void forward(const TensorIn& in, const TensorOut& out) override {
    const Tensor& x = *in.at("x");
    for (int i = 0; i < x.batch(); ++i)
      out.at("y")->mat(i) = (x.mat(i) * weights().at("w").value.mat(0)).rowwise() + weights().at("b").value.mat(0).row(0);
  }
  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    const Tensor& x = *in.at("x");
    for (int i = 0; i < x.batch(); ++i) {
      const auto gy = gout.at("y")->mat(i);
      if (auto gx = gin.find("x"); gx != gin.end()) gx->second->mat(i) = gy * weights().at("w").value.mat(0).transpose();
      weights().at("w").grad.mat(0) += x.mat(i).transpose() * gy;
      weights().at("b").grad.mat(0) += gy.colwise().sum();
    }
  }

 private:
  int width_;
};

const Registry& registry() {
  static Registry* r = [] {
    auto* reg = new Registry;
    PluginDescriptor d;
    d.kind = "op";
    d.name = "ckpt_dense";
    d.doc = "test node";
    d.inputs = {{"x", "input"}};
    d.outputs = {{"y", "output"}};
    d.params = {{"width", ParamType::Int, "4", "output channels", 1.0, {}}};
    d.create_node = [](const Params& p) { return std::make_unique<Dense>(static_cast<int>(p.get_int("width"))); };
    reg->add(d);
    return reg;
  }();
  return *r;
}

const char* kGraph = R"(
inputs: { x: [5, 3] }
nodes:
  encoder: { type: ckpt_dense, in: x, params: { width: 6 } }
  decoder: { type: ckpt_dense, in: encoder, params: { width: 2 } }
outputs: { y: decoder }
)";

Graph make_graph(std::uint64_t seed, const char* yaml = kGraph) {
  return Graph(parse_graph_text(yaml, "g.yaml"), registry(), {.dims = {}, .assets = nullptr, .seed = seed});
}

std::vector<float> values(Graph& g) {
  std::vector<float> out;
  for (const auto& [name, w] : g.weights()) out.insert(out.end(), w->value.data(), w->value.data() + w->value.size());
  return out;
}

}  // namespace

TEST_CASE("checkpoint: weights, graph, metadata and Adam state round-trip exactly", "[hdf5][checkpoint]") {
  TempDir dir;
  const fs::path path = dir / "model.h5";
  Graph trained = make_graph(1);
  // Some Adam steps so that weights and moments are non-trivial.
  Adam adam(trained.weights());
  for (int s = 0; s < 3; ++s) {
    trained.zero_grad();
    Tensor grad(2, 5, 2, 0.5f);
    trained.forward({{"x", Tensor(2, 5, 3, 1.0f)}}, false);
    trained.backward_from_output("y", grad);
    adam.step(1e-2);
  }
  const std::map<std::string, std::string> meta = {{"epoch", "3"}, {"seed", "1"}, {"best_val_loss", "0.125"}};
  save_checkpoint(path, trained, meta, &adam);

  Graph fresh = make_graph(2);
  REQUIRE(values(fresh) != values(trained));
  load_weights(path, fresh);
  CHECK(values(fresh) == values(trained));

  const Checkpoint c = read_checkpoint(path);
  CHECK(c.graph == trained.spec().text);
  CHECK(c.meta == meta);
  REQUIRE(c.optimizer);
  Adam resumed(fresh.weights());
  resumed.set_state(*c.optimizer);
  CHECK(resumed.steps() == 3);
  const OptimizerState a = adam.state(), b = resumed.state();
  CHECK(a.scalars == b.scalars);
  REQUIRE(a.tensors.size() == b.tensors.size());
  CHECK(a.tensors.count("m/encoder/w"));
  for (const auto& [name, t] : a.tensors) CHECK(t.vec() == b.tensors.at(name).vec());
  // The next step of the resumed optimiser equals the original's.
  for (auto* g : {&trained, &fresh}) {
    g->zero_grad();
    g->forward({{"x", Tensor(1, 5, 3, -1.0f)}}, false);
    g->backward_from_output("y", Tensor(1, 5, 2, 1.0f));
  }
  adam.step(1e-2);
  resumed.step(1e-2);
  CHECK(values(fresh) == values(trained));
  // The stored graph text builds the same graph.
  CHECK_NOTHROW(Graph(parse_graph_text(c.graph, "from checkpoint"), registry()));
}

TEST_CASE("checkpoint: a save that throws leaves the previous file intact", "[hdf5][checkpoint]") {
  TempDir dir;
  const fs::path path = dir / "model.h5";
  Graph g = make_graph(3);
  save_checkpoint(path, g, {{"epoch", "1"}});
  const auto before = values(g);
  // A weight with batch 2 cannot be stored: the save throws halfway through writing.
  Weight bad;
  bad.value = Tensor(2, 2, 2);
  NamedWeights weights = g.weights();
  weights.emplace_back("zzz/bad", &bad);
  Checkpoint c;
  c.graph = "changed";
  c.meta = {{"epoch", "2"}};
  CHECK_THROWS_AS(save_checkpoint(path, weights, c), Error);
  CHECK(read_checkpoint(path).meta.at("epoch") == "1");
  CHECK(read_checkpoint(path).graph == g.spec().text);
  Graph other = make_graph(4);
  load_weights(path, other);
  CHECK(values(other) == before);
  // No temporary files are left behind.
  std::size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir.path())) files += entry.is_regular_file();
  CHECK(files == 1);
}

TEST_CASE("checkpoint: missing, mismatched, extra weights and corrupt files are ConfigErrors", "[hdf5][checkpoint]") {
  TempDir dir;
  const fs::path path = dir / "model.h5";
  Graph g = make_graph(5);
  save_checkpoint(path, g, {});

  SECTION("a weight of the graph is missing from the file") {
    const char* bigger = R"(
inputs: { x: [5, 3] }
nodes:
  encoder: { type: ckpt_dense, in: x, params: { width: 6 } }
  decoder: { type: ckpt_dense, in: encoder, params: { width: 2 } }
  extra:   { type: ckpt_dense, in: decoder, params: { width: 2 } }
outputs: { y: extra }
)";
    Graph h = make_graph(5, bigger);
    const auto before = values(h);
    CHECK(message_of([&] { load_weights(path, h); }) == path.string() + ": missing dataset /weights/extra/b");
    CHECK_THROWS_AS(load_weights(path, h), ConfigError);
    CHECK(values(h) == before);  // all or nothing
    CHECK_NOTHROW(load_weights(path, g));
  }
  SECTION("a weight has another shape") {
    const char* wider = R"(
inputs: { x: [5, 3] }
nodes:
  encoder: { type: ckpt_dense, in: x, params: { width: 7 } }
  decoder: { type: ckpt_dense, in: encoder, params: { width: 2 } }
outputs: { y: decoder }
)";
    Graph h = make_graph(5, wider);
    CHECK(message_of([&] { load_weights(path, h); }) ==
          path.string() + ": weight encoder/b is [1, 6] in the file, the graph has [1, 7]");
  }
  SECTION("the file has weights the graph does not") {
    const char* smaller = R"(
inputs: { x: [5, 3] }
nodes:
  encoder: { type: ckpt_dense, in: x, params: { width: 6 } }
outputs: { y: encoder }
)";
    Graph h = make_graph(5, smaller);
    CHECK_THROWS_WITH(load_weights(path, h), Catch::Contains("weight decoder/b in the file is not in the graph"));
    CHECK_NOTHROW(load_weights(path, h, /*allow_extra=*/true));
  }
  SECTION("corrupt, truncated or foreign files") {
    std::ofstream(dir / "text.h5") << "not hdf5";
    CHECK(message_of([&] { load_weights(dir / "text.h5", g); }) == (dir / "text.h5").string() + ": not an HDF5 file");
    fs::copy_file(path, dir / "cut.h5");
    fs::resize_file(dir / "cut.h5", fs::file_size(path) / 2);
    CHECK_THROWS_AS(load_weights(dir / "cut.h5", g), ConfigError);
    CHECK_THROWS_AS(read_checkpoint(dir / "cut.h5"), ConfigError);
    h5::File::create(dir / "other.h5").write("/x", std::vector<float>{1});
    CHECK_THROWS_WITH(load_weights(dir / "other.h5", g), Catch::Contains("not a drape checkpoint"));
    CHECK_THROWS_AS(read_checkpoint(dir / "absent.h5"), ConfigError);
  }
  SECTION("optimizer state of another optimiser or shape") {
    SGD sgd(g.weights(), {.momentum = 0.9});
    Adam adam(g.weights());
    CHECK_THROWS_WITH(adam.set_state(sgd.state()), Catch::Contains("optimizer state is for 'sgd', not 'adam'"));
    OptimizerState s = adam.state();
    s.tensors.erase("v/decoder/b");
    CHECK_THROWS_WITH(adam.set_state(s), Catch::Contains("missing 'v/decoder/b'"));
  }
}

TEST_CASE("checkpoint: a graph that appends inputs starts as the saved model (load_weights_widening)",
          "[hdf5][checkpoint]") {
  TempDir dir;
  const fs::path path = dir / "model.h5";
  Graph saved = make_graph(7);
  save_checkpoint(path, saved, {});
  // The same graph with a fourth input channel after the three it had (what a
  // concat of the old features and a new one, such as the garment's grade, gives).
  const char* appended = R"(
inputs: { x: [5, 4] }
nodes:
  encoder: { type: ckpt_dense, in: x, params: { width: 6 } }
  decoder: { type: ckpt_dense, in: encoder, params: { width: 2 } }
outputs: { y: decoder }
)";
  Graph widened = make_graph(8, appended);
  const auto grown = load_weights_widening(path, widened.weights());
  REQUIRE(grown.size() == 1);
  CHECK(grown[0].name == "encoder/w");
  CHECK(grown[0].from.str() == "[3, 6]");
  CHECK(grown[0].to.str() == "[4, 6]");
  // Any value of the new channel: the output of the saved model, exactly.
  Tensor x(2, 5, 3), x4(2, 5, 4);
  for (int b = 0; b < 2; ++b)
    for (int r = 0; r < 5; ++r) {
      for (int c = 0; c < 3; ++c) x4.mat(b)(r, c) = x.mat(b)(r, c) = 0.1f * static_cast<float>(b + 2 * r - c);
      x4.mat(b)(r, 3) = 3.0f + static_cast<float>(r);
    }
  saved.forward({{"x", x}}, false);
  widened.forward({{"x", x4}}, false);
  CHECK(widened.output("y").vec() == saved.output("y").vec());
  // The new channel learns: its gradient is not zero.
  widened.zero_grad();
  widened.backward_from_output("y", Tensor(2, 5, 2, 1.0f));
  for (const auto& [name, w] : widened.weights())
    if (name == "encoder/w") CHECK(w->grad.mat(0).row(3).norm() > 0.0f);

  SECTION("a node the file lacks keeps its own initialisation, and is listed as new") {
    const char* branched = R"(
inputs: { x: [5, 3] }
nodes:
  encoder: { type: ckpt_dense, in: x, params: { width: 6 } }
  decoder: { type: ckpt_dense, in: encoder, params: { width: 2 } }
  branch:  { type: ckpt_dense, in: encoder, params: { width: 2 } }
outputs: { y: decoder, z: branch }
)";
    Graph b = make_graph(10, branched);
    std::map<std::string, std::vector<float>> own;
    for (const auto& [name, w] : b.weights()) own[name] = std::vector<float>(w->value.data(), w->value.data() + w->value.size());
    const auto listed = load_weights_widening(path, b.weights());
    REQUIRE(listed.size() == 2);  // branch/b and branch/w
    for (const auto& l : listed) {
      CHECK(l.name.rfind("branch/", 0) == 0);
      CHECK(l.from.rows == 0);
    }
    for (const auto& [name, w] : b.weights()) {
      const std::vector<float> now(w->value.data(), w->value.data() + w->value.size());
      if (name.rfind("branch/", 0) == 0) CHECK(now == own[name]);
    }
    b.forward({{"x", x}}, false);
    CHECK(b.output("y").vec() == saved.output("y").vec());  // the file's weights, loaded
    // A graph that shares no weight with the file is another graph, not an added branch.
    const char* unrelated = R"(
inputs: { x: [5, 3] }
nodes:
  other: { type: ckpt_dense, in: x, params: { width: 2 } }
outputs: { y: other }
)";
    Graph u = make_graph(11, unrelated);
    CHECK_THROWS_WITH(load_weights_widening(path, u.weights()), Catch::Contains("none of the graph's weights is in the file"));
  }
  SECTION("outputs (columns) may not change, nor rows shrink, and the file's weights must all be used") {
    const char* wider_out = R"(
inputs: { x: [5, 4] }
nodes:
  encoder: { type: ckpt_dense, in: x, params: { width: 7 } }
  decoder: { type: ckpt_dense, in: encoder, params: { width: 2 } }
outputs: { y: decoder }
)";
    Graph h = make_graph(9, wider_out);
    const auto before = values(h);
    CHECK_THROWS_WITH(load_weights_widening(path, h.weights()), Catch::Contains("only rows, the inputs, may be added"));
    CHECK(values(h) == before);  // all or nothing
    const char* fewer = R"(
inputs: { x: [5, 2] }
nodes:
  encoder: { type: ckpt_dense, in: x, params: { width: 6 } }
  decoder: { type: ckpt_dense, in: encoder, params: { width: 2 } }
outputs: { y: decoder }
)";
    Graph f = make_graph(9, fewer);
    CHECK_THROWS_WITH(load_weights_widening(path, f.weights()), Catch::Contains("weight encoder/w is [3, 6] in the file"));
  }
}

TEST_CASE("checkpoint: load_weights_partial keeps the initialisation of a weight of another shape, loads the rest",
          "[hdf5][checkpoint]") {
  TempDir dir;
  const fs::path path = dir / "model.h5";
  Graph saved = make_graph(7);
  save_checkpoint(path, saved, {});
  // The encoder gives 7 channels instead of 6 (another template's level, say):
  // encoder/w and encoder/b change columns, so they keep their initialisation;
  // decoder/w gains a row, which is widened as --init-widen does; decoder/b loads.
  const char* other = R"(
inputs: { x: [5, 3] }
nodes:
  encoder: { type: ckpt_dense, in: x, params: { width: 7 } }
  decoder: { type: ckpt_dense, in: encoder, params: { width: 2 } }
outputs: { y: decoder }
)";
  Graph g = make_graph(12, other);
  std::map<std::string, std::vector<float>> own;
  for (const auto& [name, w] : g.weights()) own[name] = std::vector<float>(w->value.data(), w->value.data() + w->value.size());
  // All or nothing without it.
  CHECK_THROWS_WITH(load_weights_widening(path, g.weights()), Catch::Contains("only rows, the inputs, may be added"));
  const auto changed = load_weights_partial(path, g.weights());
  std::set<std::string> kept, widened;
  for (const auto& c : changed) (c.kept ? kept : widened).insert(c.name);
  CHECK(kept == std::set<std::string>{"encoder/b", "encoder/w"});
  CHECK(widened == std::set<std::string>{"decoder/w"});
  std::map<std::string, Tensor> file;
  for (const auto& [name, w] : saved.weights()) file.emplace(name, w->value);
  for (const auto& [name, w] : g.weights()) {
    INFO(name);
    const std::vector<float> now(w->value.data(), w->value.data() + w->value.size());
    if (kept.count(name)) {
      CHECK(now == own[name]);
    } else if (name == "decoder/w") {
      CHECK(w->value.mat(0).topRows(6) == file.at(name).mat(0));
      CHECK(w->value.mat(0).row(6).norm() == 0.0f);
    } else {
      CHECK(w->value.vec() == file.at(name).vec());
    }
  }
  // A weight in the file the graph lacks is still an error.
  const char* fewer_nodes = R"(
inputs: { x: [5, 3] }
nodes:
  encoder: { type: ckpt_dense, in: x, params: { width: 7 } }
outputs: { y: encoder }
)";
  Graph f = make_graph(13, fewer_nodes);
  CHECK_THROWS_WITH(load_weights_partial(path, f.weights()), Catch::Contains("is not in the graph"));
}

TEST_CASE("a weight stored as integers is refused by name, not read as floats", "[hdf5][checkpoint]") {
  // An outside check rewrote a model's output layer as int32 (zeros) and
  // resealed it: it loaded without a word and predicted, exit 0.
  TempDir dir;
  write_atomically(dir / "int.h5", [&](const fs::path& tmp) {
    h5::File f = h5::File::create(tmp);
    f.set_attribute("/", "format", std::string("drape checkpoint 1"));
    f.create_group("/weights");
    const std::vector<std::int32_t> zeros(6, 0);
    f.write("/weights/w", h5::Dims{2, 3}, zeros.data());
    f.close();
  });
  Weight w;
  w.value = Tensor(1, 2, 3);
  const NamedWeights weights = {{"w", &w}};
  CHECK_THAT(message_of([&] { load_weights(dir / "int.h5", weights); }),
             Catch::Contains("int.h5: /weights/w holds i32; a weight is a floating-point number"));
}
