#include <drape/assets/assets.hpp>
#include <drape/energy_node.hpp>
#include <drape/errors.hpp>

namespace drape {

ShapeMap EnergyNode::setup(const ShapeMap& inputs, const NodeContext& context) {
  const Shape x = inputs.at("x");
  if (x.cols != 3) throw ConfigError("input 'x' must be [vertices, 3], got " + x.str());
  if (!context.assets || !context.assets->garment)
    throw ConfigError("an energy needs a garment template; none is bound to this graph");
  const Garment& g = *context.assets->garment;
  if (g.mesh.num_vertices() != x.rows)
    throw ConfigError("input 'x' has " + std::to_string(x.rows) + " vertices but the garment template has " +
                      std::to_string(g.mesh.num_vertices()));
  vertices_ = x.rows;
  EnergyContext ec;
  ec.garment = &g;
  energy_->bind(ec);
  return {{"energy", {1, 1}}};
}

void EnergyNode::forward(const TensorIn& in, const TensorOut& out) {
  const Tensor& x = *in.at("x");
  Tensor& e = *out.at("energy");
  for (int b = 0; b < x.batch(); ++b) e(b, 0, 0) = static_cast<float>(energy_->value(x.mat(b).cast<double>()));
}

void EnergyNode::backward(const TensorIn& in, const TensorIn&, const TensorIn& grad_out, const TensorOut& grad_in) {
  const Tensor& x = *in.at("x");
  const Tensor& ge = *grad_out.at("energy");
  const auto wanted = grad_in.find("x");
  if (wanted == grad_in.end()) return;  // nothing upstream learns
  Tensor& gx = *wanted->second;
  Eigen::MatrixX3d g(vertices_, 3);
  for (int b = 0; b < x.batch(); ++b) {
    g.setZero();
    energy_->add_gradient(x.mat(b).cast<double>(), g);
    gx.mat(b) = (g * static_cast<double>(ge(b, 0, 0))).cast<float>();
  }
}

}  // namespace drape
