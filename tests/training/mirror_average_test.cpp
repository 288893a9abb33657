// The mirror average's gradient (Model::backward with the twin's inputs, what
// optimize_drape follows): against central differences of the averaged
// garment in the weights, on the shipped posed model with its push-out off
// (the push-out's own backward passes the gradient straight through, so
// the averaged network is the function checked). The plain backward gives
// another gradient, so the check can tell the two apart.
#include <drape/bodies/posed_body.hpp>
#include <drape/training/model.hpp>

#include <catch2/catch.hpp>

#include "../train/train_test_util.hpp"

#include <cmath>
#include <map>
#include <string>
#include <vector>

using namespace drape;
using namespace drape::test;

namespace {

// L = sum(g .* garment) for a fixed g: its weight gradient is the backward of g.
double weighted_sum(const Tensor& garment, const Tensor& g) {
  double s = 0;
  for (std::size_t i = 0; i < g.size(); ++i) s += static_cast<double>(g.data()[i]) * garment.data()[i];
  return s;
}

// A body of BMI `bmi` at rest posed by `angles`, as the model is fed it
// (at the design grade).
SampleBatch posed_batch(const Model& model, double bmi, const std::map<std::string, double>& angles) {
  BodyRequest request;
  request.bmi = bmi;
  const SampleBatch rest = model.body_for(request);
  Pose pose;
  pose.angles = angles;
  SampleBatch batch = posed_body_batch(model.body_model(), rest.body.mat(0).cast<double>(), pose);
  batch.body_params = rest.body_params;
  batch.garment_grade = Tensor(1, 1, 1, 1.0f);
  return batch;
}

}  // namespace

TEST_CASE("the mirror average's backward matches central differences of the averaged garment", "[model][mirror]") {
  const auto file = source_dir() / "models/tshirt-coarse-posed-human.h5";
  if (!std::filesystem::exists(file)) {
    WARN("skipped: " << file.string() << " is not in this tree");
    return;
  }
  Model model = Model::load(plugins(), file, {{"post", {{"enabled", "false"}, {"mirror_average", "true"}}}},
                            assets_cache());
  REQUIRE(model.mirror_average_node() == "post");
  const SampleBatch batch = posed_batch(model, 28, {{"left_shoulder_abduction", 75}, {"right_shoulder_abduction", 40},
                                                    {"spine_twist", 15}, {"left_elbow_flexion", 30}});
  Graph& graph = model.graph();
  const auto inputs = graph_inputs(graph, batch, false);
  const auto twin = graph_inputs(graph, model.mirrored_batch(batch), false);

  const Tensor garment = model.forward(inputs, &twin);
  Tensor g(1, garment.rows(), 3);
  for (std::size_t i = 0; i < g.size(); ++i) g.data()[i] = static_cast<float>(std::sin(0.37 * static_cast<double>(i) + 1.0));
  graph.zero_grad();
  model.backward(g, &twin);
  // The last layers of the decoder and the spectral branch: the garment is
  // affine in their weights (the skinning is linear in the canonical garment),
  // so central differences are exact but for float rounding. (Deeper
  // weights meet leaky ReLU kinks within any step float allows: their plain
  // backward is 3-25 % off central differences at h = 1e-2 to 1e-3.) Each
  // at its entry of largest gradient.
  int checked = 0;
  for (const auto& [name, w] : graph.weights()) {
    if (name != "decoder/out_w0" && name != "decoder/out_b0" && name != "spectral/mlp_w1" && name != "spectral/mlp_b1")
      continue;
    std::size_t best = 0;
    for (std::size_t i = 1; i < w->grad.size(); ++i)
      if (std::abs(w->grad.data()[i]) > std::abs(w->grad.data()[best])) best = i;
    const double analytic = w->grad.data()[best];
    if (!(std::abs(analytic) > 1e-3)) continue;
    const float saved = w->value.data()[best];
    const float h = 1e-2f;
    w->value.data()[best] = saved + h;
    const double plus = weighted_sum(model.forward(inputs, &twin), g);
    w->value.data()[best] = saved - h;
    const double minus = weighted_sum(model.forward(inputs, &twin), g);
    w->value.data()[best] = saved;
    const double numeric = (plus - minus) / (2.0 * static_cast<double>(h));
    INFO(name << "[" << best << "]: backward " << analytic << ", central differences " << numeric);
    CHECK(analytic == Approx(numeric).epsilon(0.02));
    ++checked;
  }
  CHECK(checked == 4);
  // The plain backward (the batch's pass alone) is another gradient.
  const auto all_gradients = [&] {
    std::vector<float> out;
    for (const auto& [name, w] : graph.weights()) out.insert(out.end(), w->grad.data(), w->grad.data() + w->grad.size());
    return Eigen::Map<const Eigen::VectorXf>(out.data(), static_cast<Eigen::Index>(out.size())).eval();
  };
  model.forward(inputs, &twin);
  graph.zero_grad();
  model.backward(g, &twin);
  const Eigen::VectorXf averaged = all_gradients();
  graph.forward(inputs, false);  // the batch's own pass, its activations
  graph.zero_grad();
  graph.backward_from_output(model.output(), g);
  const Eigen::VectorXf plain = all_gradients();
  INFO("|averaged| " << averaged.norm() << ", |plain - averaged| " << (plain - averaged).norm());
  CHECK((plain - averaged).norm() > 0.1 * averaged.norm());
}


TEST_CASE("backward_network from what the push-out is fed gives backward's gradient, the push-out not run",
          "[model][mirror]") {
  // The push-out passes the gradient straight through, so the weights'
  // gradient of a drape is the same whether reverse mode starts at the
  // model's output after forward (Model::backward) or at the push-out's
  // input after forward_network (Graph::backward_from_fed), which leaves the
  // push-out out of both passes: what the physics optimisation needs.
  const auto file = source_dir() / "models/tshirt-coarse-posed-human.h5";
  if (!std::filesystem::exists(file)) {
    WARN("skipped: " << file.string() << " is not in this tree");
    return;
  }
  Model model = Model::load(plugins(), file, assets_cache());
  REQUIRE(model.push_out_node() == "post");
  const SampleBatch batch = posed_batch(model, 33, {{"left_shoulder_abduction", 60}, {"right_elbow_flexion", 40}, {"spine_twist", -10}});
  Graph& graph = model.graph();
  const auto inputs = graph_inputs(graph, batch, false);
  const auto twin = graph_inputs(graph, model.mirrored_batch(batch), false);

  const Tensor pushed = model.forward(inputs, &twin);
  Tensor g(1, pushed.rows(), 3);
  for (std::size_t i = 0; i < g.size(); ++i) g.data()[i] = static_cast<float>(std::cos(0.23 * static_cast<double>(i)));
  graph.zero_grad();
  model.backward(g, &twin);
  std::vector<Eigen::VectorXf> through_output;
  for (const auto& [name, w] : graph.weights()) through_output.push_back(w->grad.vec());

  // The network's own drape: not the push-out's (it moves vertices of this tight shirt).
  const Tensor own = model.forward_network(inputs, &twin);
  CHECK((own.vec() - pushed.vec()).cwiseAbs().maxCoeff() > 1e-4f);
  graph.zero_grad();
  model.backward_network(g, &twin);
  std::size_t k = 0;
  for (const auto& [name, w] : graph.weights()) {
    INFO(name);
    CHECK((w->grad.vec() - through_output[k]).cwiseAbs().maxCoeff() <= 1e-6f * (1.0f + through_output[k].cwiseAbs().maxCoeff()));
    ++k;
  }
}
