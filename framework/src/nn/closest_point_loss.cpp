#include <drape/nn/closest_point_loss.hpp>

#include <drape/assets/assets.hpp>
#include <drape/errors.hpp>
#include <drape/geometry/closest_point_gradient.hpp>
#include <drape/nn/body_loss_inputs.hpp>

namespace drape::nn {

namespace {

Eigen::MatrixX3d to_double(const Tensor& t, int b) { return t.mat(b).cast<double>(); }

}  // namespace

ShapeMap ClosestPointLoss::setup(const ShapeMap& in, const NodeContext& context) {
  rows_ = check_body_loss_inputs(in, context, who_);
  const Mesh& mean_body = context.assets->body;
  faces_ = mean_body.faces;
  points_ = std::make_unique<geometry::BodyPoints>(mean_body, who_);
  return {{"loss", {1, 1}}};
}

void ClosestPointLoss::forward(const TensorIn& in, const TensorOut& out) {
  const Tensor &x = *in.at("pred"), &y = *in.at("target"), &body = *in.at("body");
  const int batch = x.batch();
  hits_x_.assign(batch, {});
  hits_y_.assign(batch, {});
  for (int b = 0; b < batch; ++b) {
    hits_y_[b] = points_->ground_truth(body, y, b);
    hits_x_[b] = points_->prediction(body, x, y, b, *hits_y_[b]);
    const auto xb = x.mat(b), yb = y.mat(b);
    const auto &hx = *hits_x_[b], &hy = *hits_y_[b];
    double sum = 0.0;
    for (int i = 0; i < rows_; ++i)
      sum += vertex_loss(xb.row(i).transpose().cast<double>(), yb.row(i).transpose().cast<double>(), hx[i], hy[i]);
    (*out.at("loss"))(b, 0, 0) = static_cast<float>(mean_ ? sum / rows_ : sum);
  }
}

void ClosestPointLoss::backward(const TensorIn& in, const TensorIn&, const TensorIn& gout, const TensorOut& gin) {
  const Tensor &x = *in.at("pred"), &y = *in.at("target"), &body = *in.at("body");
  const int batch = x.batch();
  if (static_cast<int>(hits_x_.size()) != batch) throw Error(who_ + ": backward without a matching forward");
  const auto gpred = gin.find("pred"), gtarget = gin.find("target"), gbody_port = gin.find("body");
  const bool want_y = gtarget != gin.end() || gbody_port != gin.end();  // the target's closest points move with both
  if (gpred == gin.end() && !want_y) return;
  for (int b = 0; b < batch; ++b) {
    const double scale = (*gout.at("loss"))(b, 0, 0) / (mean_ ? double(rows_) : 1.0);
    const Eigen::MatrixX3d xb = to_double(x, b), yb = to_double(y, b), vb = to_double(body, b);
    const auto &hx = *hits_x_[b], &hy = *hits_y_[b];
    Eigen::MatrixX3d gx(rows_, 3), gy(rows_, 3), gcx(rows_, 3), gcy(rows_, 3);
    for (int i = 0; i < rows_; ++i) {
      const VertexGradient g = vertex_gradient(xb.row(i).transpose(), yb.row(i).transpose(), hx[i], hy[i]);
      gx.row(i) = scale * g.x;
      gy.row(i) = scale * g.y;
      gcx.row(i) = scale * g.cx;
      gcy.row(i) = scale * g.cy;
    }
    Eigen::MatrixX3d gbody = Eigen::MatrixX3d::Zero(vb.rows(), 3);
    geometry::closest_points_backward(vb, faces_, xb, hx, gcx, gx, gbody);
    if (want_y) geometry::closest_points_backward(vb, faces_, yb, hy, gcy, gy, gbody);
    if (gpred != gin.end()) gpred->second->mat(b) = gx.cast<float>();
    if (gtarget != gin.end()) gtarget->second->mat(b) = gy.cast<float>();
    if (gbody_port != gin.end()) gbody_port->second->mat(b) = gbody.cast<float>();
  }
}

}  // namespace drape::nn
