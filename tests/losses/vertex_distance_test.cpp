// vertex_distance (the ME metric as a loss): values and gradients by hand,
// shape errors, unknown parameters, determinism.
#include <catch2/catch.hpp>

#include "losses_test_util.hpp"

using namespace drape;
using namespace drape::test;

TEST_CASE("vertex_distance is the mean Euclidean distance per vertex", "[losses][vertex_distance]") {
  CHECK(plugins().get("vertex_distance").kind == "loss");
  auto node = make_node("vertex_distance");
  // Vertex 0: (3, 4, 0) apart, distance 5 (its L1 would be 7); vertex 1 on its
  // target; vertex 2: (1, 2, 2) apart, distance 3. Mean (5 + 0 + 3) / 3.
  const Tensor pred = tensor_of(rows3({{0, 0, 0}, {1, 2, 2}, {1, 1, 1}}));
  const Tensor target = tensor_of(rows3({{3, 4, 0}, {1, 2, 2}, {0, -1, -1}}));
  const auto out = run_forward(*node, {{"pred", pred}, {"target", target}});
  CHECK(out.at("loss")(0, 0, 0) == Approx(8.0 / 3.0).epsilon(1e-6));

  // d/dpred = (pred - target) / |pred - target| / N; 0 where they coincide.
  Tensor gout(1, 1, 1, 1.0f), gpred(1, 3, 3), gtarget(1, 3, 3);
  TensorIn in{{"pred", &pred}, {"target", &target}}, grads{{"loss", &gout}};
  node->backward(in, {}, grads, {{"pred", &gpred}, {"target", &gtarget}});
  const float third = 1.0f / 3.0f;
  CHECK(gpred(0, 0, 0) == Approx(-0.6f * third));
  CHECK(gpred(0, 0, 1) == Approx(-0.8f * third));
  CHECK(gpred(0, 0, 2) == Approx(0.0f).margin(1e-7));
  for (int c = 0; c < 3; ++c) CHECK(gpred(0, 1, c) == 0.0f);
  CHECK(gpred(0, 2, 0) == Approx(third / 3.0f));
  CHECK(gpred(0, 2, 1) == Approx(2.0f * third / 3.0f));
  CHECK(gpred(0, 2, 2) == Approx(2.0f * third / 3.0f));
  for (int v = 0; v < 3; ++v)
    for (int c = 0; c < 3; ++c) CHECK(gtarget(0, v, c) == -gpred(0, v, c));
}

TEST_CASE("vertex_distance checks its shapes and gives the same bits twice", "[losses][vertex_distance]") {
  // (Its gradient against differences: tests/plugins/node_conformance_test.cpp, with every plain node.)
  auto node = make_node("vertex_distance");
  const Tensor a = random_tensor(2, 7, 3, 31), b = random_tensor(2, 7, 3, 32);
  const auto first = run_forward(*node, {{"pred", a}, {"target", b}});
  const auto second = run_forward(*node, {{"pred", a}, {"target", b}});
  CHECK(first.at("loss").vec() == second.at("loss").vec());
  CHECK_THROWS_WITH(node->setup({{"pred", {4, 3}}, {"target", {5, 3}}}, {}), Catch::Contains("differ in shape"));
  CHECK_THROWS_WITH(node->setup({{"pred", {4, 2}}, {"target", {4, 2}}}, {}), Catch::Contains("[N, 3]"));
  CHECK_THROWS_WITH(make_node("vertex_distance", "{reduction: sum}"), Catch::Contains("reduction"));
}
