#include <drape/assets/assets.hpp>
#include <drape/gradcheck.hpp>

#include <catch2/catch.hpp>

#include "plugin_test_util.hpp"

using namespace drape;
using namespace drape::test;

TEST_CASE("gather loads as an op: indices are checked against the input", "[gather]") {
  const PluginDescriptor& d = plugins().get("gather");
  CHECK(d.kind == "op");
  CHECK(d.file.find("libdrape_plugin_gather") != std::string::npos);
  CHECK_THROWS_AS(make_node("gather", "{indices: [0, -1]}"), ConfigError);
  CHECK_THROWS_AS(make_node("gather", "{indices: [0.5]}"), ConfigError);
  auto node = make_node("gather", "{indices: [0, 4, 5]}");
  CHECK_THROWS_WITH(node->setup({{"x", {5, 2}}}, {}), Catch::Contains("entry 2 is 5"));
  CHECK(node->setup({{"x", {6, 2}}}, {}).at("out") == Shape{3, 2});
}

TEST_CASE("gather picks rows and scatter-adds gradients back", "[gather]") {
  auto node = make_node("gather", "{indices: [2, 0, 2]}");
  const Tensor x = random_tensor(2, 3, 4, 1);
  const auto out = run_forward(*node, {{"x", x}});
  const int picked[3] = {2, 0, 2};
  for (int b = 0; b < 2; ++b)
    for (int i = 0; i < 3; ++i)
      for (int c = 0; c < 4; ++c) CHECK(out.at("out")(b, i, c) == x(b, picked[i], c));

  Tensor gy = random_tensor(2, 3, 4, 2), gx(2, 3, 4, 99.0f);  // stale values must be overwritten
  node->backward({{"x", &x}}, {{"out", &out.at("out")}}, {{"out", &gy}}, {{"x", &gx}});
  for (int b = 0; b < 2; ++b)
    for (int c = 0; c < 4; ++c) {
      CHECK(gx(b, 0, c) == Approx(gy(b, 1, c)));
      CHECK(gx(b, 1, c) == 0.0f);
      CHECK(gx(b, 2, c) == Approx(gy(b, 0, c) + gy(b, 2, c)));
    }
}

TEST_CASE("gather backward matches finite differences", "[gather][gradcheck]") {
  auto node = make_node("gather", "{indices: [3, 1, 1, 0, 6]}");
  const GradCheckReport r = check_node_gradients(*node, {{"x", random_tensor(2, 7, 3, 6)}});
  INFO(r.str());
  CHECK(r.entries.size() == 1);
  CHECK(r.ok(1e-2));
}

TEST_CASE("gather without indices picks the assets' body->garment correspondences", "[gather]") {
  // Without assets there is nothing to pick by: a clear error, not an empty output.
  CHECK_THROWS_WITH(make_node("gather")->setup({{"x", {5, 2}}}, {}), Catch::Contains("correspondences"));

  Assets assets;
  NodeContext context;
  context.assets = &assets;
  CHECK_THROWS_WITH(make_node("gather")->setup({{"x", {5, 2}}}, context), Catch::Contains("no body->garment"));

  assets.correspondence = {4, 0, 4, 2};
  CHECK_THROWS_WITH(make_node("gather")->setup({{"x", {4, 2}}}, context), Catch::Contains("entry 0 is 4"));
  auto node = make_node("gather");
  CHECK(node->setup({{"x", {5, 2}}}, context).at("out") == Shape{4, 2});
  const Tensor x = random_tensor(2, 5, 2, 7);
  const auto out = run_forward(*node, {{"x", x}}, context);
  for (int b = 0; b < 2; ++b)
    for (int i = 0; i < 4; ++i)
      for (int c = 0; c < 2; ++c) CHECK(out.at("out")(b, i, c) == x(b, assets.correspondence[i], c));
}
