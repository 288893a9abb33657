#pragma once
// The common part of the losses that compare pred and target through their
// closest points on this sample's body (v2v, direction): inputs pred, target
// [N, 3] and body [Nb, 3] -> loss [1, 1], the sum (or mean) over the garment
// vertices of a per-vertex term of x_i, y_i and their closest points c_x, c_y.
// This base finds the closest points (geometry::BodyPoints, the target's
// cached and shared between the losses), sums the terms, and carries a term's
// gradient through the closest points to pred, target and body, to those of
// the three the graph wants. A loss only says what its per-vertex term is.
#include <drape/geometry/body_points.hpp>
#include <drape/node.hpp>

#include <memory>
#include <string>
#include <vector>

namespace drape::nn {

class ClosestPointLoss : public Node {
 public:
  ShapeMap setup(const ShapeMap& in, const NodeContext& context) final;
  void forward(const TensorIn& in, const TensorOut& out) final;
  void backward(const TensorIn& in, const TensorIn& out, const TensorIn& grad_out, const TensorOut& grad_in) final;

 protected:
  // who: the loss's name for error messages; mean: the mean over the vertices, else their plain sum.
  ClosestPointLoss(std::string who, bool mean) : who_(std::move(who)), mean_(mean) {}

  // dTerm/d(x, y, c_x, c_y) of one vertex.
  struct VertexGradient {
    Eigen::Vector3d x = Eigen::Vector3d::Zero(), y = Eigen::Vector3d::Zero();
    Eigen::Vector3d cx = Eigen::Vector3d::Zero(), cy = Eigen::Vector3d::Zero();
  };
  // One vertex's term: x, y its predicted and true positions, hx, hy their closest body points.
  virtual double vertex_loss(const Eigen::Vector3d& x, const Eigen::Vector3d& y, const geometry::SurfacePoint& hx,
                             const geometry::SurfacePoint& hy) const = 0;
  virtual VertexGradient vertex_gradient(const Eigen::Vector3d& x, const Eigen::Vector3d& y,
                                         const geometry::SurfacePoint& hx, const geometry::SurfacePoint& hy) const = 0;

  int rows() const { return rows_; }  // N, known after setup

 private:
  std::string who_;
  bool mean_;
  int rows_ = 0;
  Eigen::MatrixX3i faces_;
  std::unique_ptr<geometry::BodyPoints> points_;
  std::vector<std::shared_ptr<const geometry::BodyPoints::Hits>> hits_x_, hits_y_;  // of the last forward, per sample
};

}  // namespace drape::nn
