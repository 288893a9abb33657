#include "shape_fit.hpp"

namespace drape::parametric {

Eigen::MatrixX3d fit_template(const BodyTemplate& tpl, const ImplicitBody& body) {
  const Eigen::Index nv = tpl.vertices.rows();
  Eigen::MatrixX3d out(nv, 3);
  for (Eigen::Index v = 0; v < nv; ++v) {
    const Eigen::Vector3d p = tpl.vertices.row(v);
    Eigen::Vector3d q = Eigen::Vector3d::Zero();
    for (int k = 0; k < BodyTemplate::kBind; ++k) {
      const int part = tpl.bind_part[static_cast<std::size_t>(v)][static_cast<std::size_t>(k)];
      const double w = tpl.bind_weight[static_cast<std::size_t>(v)][static_cast<std::size_t>(k)];
      q += w * tpl.mean.parts[static_cast<std::size_t>(part)].carry(p, body.parts[static_cast<std::size_t>(part)]);
    }
    out.row(v) = body.project(q, 8).transpose();
  }
  relax_on_surface(body, tpl.neighbours, out, 4, 0.5);
  return out;
}

void normalise_height(Eigen::MatrixX3d& vertices, double height) {
  const double lo = vertices.col(1).minCoeff(), hi = vertices.col(1).maxCoeff();
  vertices.col(1) = (vertices.col(1).array() - lo) * (height / (hi - lo));
}

}  // namespace drape::parametric
