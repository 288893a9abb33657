// The v2v, direction and penetration losses with their closest points from
// geometry::BodyPoints: the target's cached after the first step, the
// prediction's searched from the target's faces. Checked against a plain
// BodySurface::locate computation of L_V2V, run twice (the second run from the
// cache), and with only pred's gradient asked for (as a graph does in training)
// against all three.
#include <drape/geometry/closest_point.hpp>
#include <drape/geometry/surface_cache.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "losses_test_util.hpp"

using namespace drape;
using namespace drape::test;

namespace {

struct Samples {
  Tensor pred, target, body;
};

// Three samples on three bodies (a sphere scaled differently), points in a shell around it.
Samples shell_samples(const Mesh& sphere, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> r(0.3, 0.8);
  std::vector<Eigen::MatrixX3d> x, y, bodies;
  for (int b = 0; b < 3; ++b) {
    Eigen::MatrixX3d xb(60, 3), yb(60, 3);
    for (int i = 0; i < 60; ++i) {
      const Eigen::Vector3d dir = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
      yb.row(i) = r(rng) * dir;
      xb.row(i) = yb.row(i) + 0.05 * Eigen::RowVector3d(g(rng), g(rng), g(rng));
    }
    x.push_back(xb);
    y.push_back(yb);
    bodies.push_back(sphere.vertices * (1.0 + 0.15 * b));
  }
  return {tensor_of(x), tensor_of(y), tensor_of(bodies)};
}

// L_V2V (mean) of one sample from BodySurface::locate, independently of the plugin.
double v2v_reference(const Mesh& sphere, const Samples& s, int b) {
  geometry::BodySurface surface(s.body.mat(b).cast<double>(), sphere.faces);
  const Eigen::MatrixX3d x = s.pred.mat(b).cast<double>(), y = s.target.mat(b).cast<double>();
  double sum = 0;
  for (int i = 0; i < x.rows(); ++i) {
    const Eigen::Vector3d cx = surface.locate(x.row(i).transpose()).point, cy = surface.locate(y.row(i).transpose()).point;
    sum += (cx - cy).lpNorm<1>() + ((x.row(i).transpose() - cx) - (y.row(i).transpose() - cy)).lpNorm<1>();
  }
  return sum / double(x.rows());
}

// L_pen (margin eps) of one sample from BodySurface::locate's signed distances.
double penetration_reference(const Mesh& sphere, const Samples& s, int b, double eps) {
  geometry::BodySurface surface(s.body.mat(b).cast<double>(), sphere.faces);
  const Eigen::MatrixX3d x = s.pred.mat(b).cast<double>();
  double sum = 0;
  for (int i = 0; i < x.rows(); ++i) {
    const double depth = std::max(0.0, eps - surface.locate(x.row(i).transpose()).signed_distance);
    sum += depth * depth / (eps * eps);
  }
  return sum / double(x.rows());
}

// Forward then backward with unit loss gradients; `ports` the gradients asked for.
std::map<std::string, Tensor> gradients(Node& node, const Samples& s, const std::vector<std::string>& ports) {
  const TensorIn in{{"pred", &s.pred}, {"target", &s.target}, {"body", &s.body}};
  Tensor loss(s.pred.batch(), 1, 1), gloss(s.pred.batch(), 1, 1, 1.0f);
  node.forward(in, {{"loss", &loss}});
  std::map<std::string, Tensor> g;
  TensorOut gin;
  for (const auto& p : ports) {
    g[p] = Tensor(in.at(p)->batch(), in.at(p)->rows(), in.at(p)->cols());
    gin[p] = &g[p];
  }
  node.backward(in, {{"loss", &loss}}, {{"loss", &gloss}}, gin);
  g["loss"] = loss;
  return g;
}

}  // namespace

TEST_CASE("v2v and direction: cached ground-truth points give the plain search's losses, twice", "[losses][v2v][cache]") {
  const Mesh sphere = geometry::icosphere(2, 0.5);
  const auto assets = body_assets(sphere);
  const Samples s = shell_samples(sphere, 11);
  for (const std::string type : {"v2v", "direction"}) {
    INFO(type);
    auto node = make_node(type);
    const std::size_t before = geometry::SurfaceCache::shared().entries();
    const auto first =
        run_forward(*node, {{"pred", s.pred}, {"target", s.target}, {"body", s.body}}, {"l", 0, assets.get()});
    // The first loss that sees a sample caches its ground truth (v2v); direction finds v2v's.
    CHECK(geometry::SurfaceCache::shared().entries() == (type == "v2v" ? before + 3 : before));
    Tensor again(3, 1, 1);
    const TensorIn in{{"pred", &s.pred}, {"target", &s.target}, {"body", &s.body}};
    node->forward(in, {{"loss", &again}});
    for (int b = 0; b < 3; ++b) {
      CHECK(again(b, 0, 0) == first.at("loss")(b, 0, 0));  // bit for bit from the cache
      if (type == "v2v") CHECK(first.at("loss")(b, 0, 0) == Approx(v2v_reference(sphere, s, b)).epsilon(1e-6));
    }
    // The next step's prediction (moved up to 2 cm) is searched from this one's
    // faces and still finds the exact closest points.
    Samples moved = s;
    for (std::size_t i = 0; i < moved.pred.size(); ++i) moved.pred.data()[i] += 0.02f * std::sin(float(i));
    const TensorIn in_moved{{"pred", &moved.pred}, {"target", &moved.target}, {"body", &moved.body}};
    node->forward(in_moved, {{"loss", &again}});
    if (type == "v2v")
      for (int b = 0; b < 3; ++b) CHECK(again(b, 0, 0) == Approx(v2v_reference(sphere, moved, b)).epsilon(1e-6));
  }
}

TEST_CASE("v2v and direction: pred's gradient alone equals pred's part of the full backward", "[losses][v2v][cache]") {
  const Mesh sphere = geometry::icosphere(2, 0.5);
  const auto assets = body_assets(sphere);
  const Samples s = shell_samples(sphere, 12);
  for (const std::string type : {"v2v", "direction"}) {
    INFO(type);
    auto node = make_node(type);
    run_forward(*node, {{"pred", s.pred}, {"target", s.target}, {"body", s.body}}, {"l", 0, assets.get()});
    const auto all = gradients(*node, s, {"pred", "target", "body"});
    const auto pred_only = gradients(*node, s, {"pred"});
    CHECK(pred_only.count("target") == 0);
    CHECK(pred_only.at("pred").vec() == all.at("pred").vec());
    CHECK(all.at("pred").vec().norm() > 0);
    CHECK(all.at("target").vec().norm() > 0);  // the full backward does reach the data
    CHECK(pred_only.at("loss").vec() == all.at("loss").vec());
  }
}

// penetration signs BodyPoints' cached and warm-started prediction points with
// PseudoNormals: the loss must be the plain signed search's, on three bodies,
// again bit for bit, and after the prediction moves by up to 2 cm.
TEST_CASE("penetration: cached, warm-started and lazily signed points give the plain search's loss",
          "[losses][penetration][cache]") {
  const Mesh sphere = geometry::icosphere(2, 0.5);
  const auto assets = body_assets(sphere);
  const Samples s = shell_samples(sphere, 13);
  const double eps = 0.05;
  auto node = make_node("penetration", "{margin: 0.05}");
  const auto first = run_forward(*node, {{"pred", s.pred}, {"target", s.target}, {"body", s.body}}, {"l", 0, assets.get()});
  Tensor again(3, 1, 1);
  node->forward({{"pred", &s.pred}, {"target", &s.target}, {"body", &s.body}}, {{"loss", &again}});
  for (int b = 0; b < 3; ++b) {
    INFO("sample " << b);
    CHECK(first.at("loss")(b, 0, 0) == Approx(penetration_reference(sphere, s, b, eps)).epsilon(1e-5));
    CHECK(first.at("loss")(b, 0, 0) > 0.0f);
    CHECK(again(b, 0, 0) == first.at("loss")(b, 0, 0));
  }
  Samples moved = s;
  for (std::size_t i = 0; i < moved.pred.size(); ++i) moved.pred.data()[i] += 0.02f * std::sin(float(i));
  node->forward({{"pred", &moved.pred}, {"target", &moved.target}, {"body", &moved.body}}, {{"loss", &again}});
  for (int b = 0; b < 3; ++b) CHECK(again(b, 0, 0) == Approx(penetration_reference(sphere, moved, b, eps)).epsilon(1e-5));
}
