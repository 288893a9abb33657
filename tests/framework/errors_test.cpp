#include <drape/errors.hpp>
#include <drape/tensor.hpp>

#include <catch2/catch.hpp>

using namespace drape;

TEST_CASE("closest matches find typos, not unrelated names", "[errors]") {
  const std::vector<std::string> names = {"cnn1d", "pointnet", "gcn", "gcn_learned", "multiscale_gcn", "mlp"};
  const auto m = closest_matches("cnn1", names);
  REQUIRE_FALSE(m.empty());
  CHECK(m.front() == "cnn1d");
  CHECK(closest_matches("pointent", names).front() == "pointnet");
  CHECK(closest_matches("zzzzzzzz", names).empty());
  CHECK(did_you_mean("mpl", names) == "; did you mean 'mlp'?");
  // Among the whole registry 'mpl' is also inside 'add_template', 'resample_body'
  // and 'smpl': those three were offered and 'mlp' was not (an outside check).
  const std::vector<std::string> registry = {"add_template", "mlp", "resample_body", "smpl", "spectral"};
  CHECK(closest_matches("mpl", registry).front() == "mlp");
  // A swap of two neighbours is one edit: within the limit of a short name.
  CHECK(closest_matches("gnc", {"gcn", "sum"}) == std::vector<std::string>{"gcn"});
}

TEST_CASE("tensor views are row-major per sample", "[tensor]") {
  Tensor t(2, 3, 2);
  for (std::size_t i = 0; i < t.size(); ++i) t.data()[i] = static_cast<float>(i);
  CHECK(t.mat(1)(0, 1) == 7.0f);
  CHECK(t(1, 2, 1) == 11.0f);
  CHECK(t.flat().rows() == 6);
  CHECK(t.flat()(4, 0) == 8.0f);
  t.mat(0).setZero();
  CHECK(t.vec().head(6).isZero());
  CHECK(t.vec()(6) == 6.0f);
  CHECK(t.shape_str() == "[2, 3, 2]");
}
