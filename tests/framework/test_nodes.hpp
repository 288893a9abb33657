#pragma once
// In-process nodes for framework tests: a learnable per-column affine map
// y = x * w + b (w, b of shape [1, cols]) and a registry holding it plus the
// build tree's plugins.
#include <drape/plugin.hpp>

#include "test_support.hpp"

namespace drape::test {

class Affine final : public Node {
 public:
  ShapeMap setup(const ShapeMap& in, const NodeContext&) override {
    const Shape s = in.at("x");
    add_weight("w", 1, s.cols).value.vec().setConstant(1.5f);
    add_weight("b", 1, s.cols).value.vec().setConstant(0.25f);
    return {{"y", s}};
  }
  void forward(const TensorIn& in, const TensorOut& out) override {
    const auto w = weights().at("w").value.mat(0).row(0).array();
    const auto b = weights().at("b").value.mat(0).row(0).array();
    const Tensor& x = *in.at("x");
    Tensor& y = *out.at("y");
    for (int i = 0; i < x.batch(); ++i)
      for (int r = 0; r < x.rows(); ++r) y.mat(i).row(r) = x.mat(i).row(r).array() * w + b;
  }
  void backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) override {
    auto& w = weights().at("w");
    auto& b = weights().at("b");
    const Tensor& x = *in.at("x");
    const Tensor& gy = *gout.at("y");
    const auto gx = gin.find("x");  // absent when x is a graph input (propagate_down)
    for (int i = 0; i < x.batch(); ++i)
      for (int r = 0; r < x.rows(); ++r) {
        if (gx != gin.end()) gx->second->mat(i).row(r) = gy.mat(i).row(r).array() * w.value.mat(0).row(0).array();
        w.grad.mat(0).row(0).array() += gy.mat(i).row(r).array() * x.mat(i).row(r).array();
        b.grad.mat(0).row(0) += gy.mat(i).row(r);
      }
  }
};

inline PluginDescriptor affine_descriptor() {
  PluginDescriptor d;
  d.kind = "op";
  d.name = "test_affine";
  d.doc = "test node";
  d.inputs = {{"x", "input"}};
  d.outputs = {{"y", "output"}};
  d.create_node = [](const Params&) { return std::make_unique<Affine>(); };
  return d;
}

// Build-tree plugins plus test_affine.
inline const Registry& registry_with_test_nodes() {
  static Registry* r = [] {
    auto* reg = new Registry;
    reg->load_path({test::plugin_dir().string()});
    reg->add(affine_descriptor());
    return reg;
  }();
  return *r;
}

}  // namespace drape::test
