#include "smooth_distance.hpp"

#include <cmath>

namespace drape::collision {

VertexGrid::VertexGrid(const Eigen::MatrixX3d& vertices, double cell) : cell_(cell) {
  cells_.reserve(static_cast<std::size_t>(vertices.rows()));
  for (Eigen::Index j = 0; j < vertices.rows(); ++j)
    cells_[key(cell_of(vertices.row(j).transpose()))].push_back(static_cast<int>(j));
}

Eigen::Vector3i VertexGrid::cell_of(const Eigen::Vector3d& p) const {
  return (p / cell_).array().floor().cast<int>();
}

long long VertexGrid::key(const Eigen::Vector3i& c) {
  // 21 bits per axis: +-1M cells of a few centimetres is far beyond any body.
  const auto part = [](int v) { return static_cast<long long>(v + (1 << 20)) & ((1LL << 21) - 1); };
  return (part(c.x()) << 42) | (part(c.y()) << 21) | part(c.z());
}

std::vector<Contact> smooth_contacts(const Eigen::MatrixX3d& body_vertices, const Eigen::MatrixX3d& body_normals,
                                     const Eigen::MatrixX3d& x, double radius, bool with_hessian,
                                     std::vector<char>& covered) {
  const VertexGrid grid(body_vertices, radius);
  std::vector<Contact> out(static_cast<std::size_t>(x.rows()));
  covered.assign(static_cast<std::size_t>(x.rows()), 0);
  const double r2 = radius * radius;
#pragma omp parallel for schedule(static, 64) if (x.rows() > 512)
  for (Eigen::Index v = 0; v < x.rows(); ++v) {
    const Eigen::Vector3d p = x.row(v).transpose();
    // Sums for d = N / D and their derivatives (w' = dw/dx, w'' = d2w/dx2).
    double n_sum = 0, d_sum = 0;
    Eigen::Vector3d grad_n = Eigen::Vector3d::Zero(), grad_d = Eigen::Vector3d::Zero();
    Eigen::Matrix3d hess_n = Eigen::Matrix3d::Zero(), hess_d = Eigen::Matrix3d::Zero();
    grid.for_each_near(p, [&](int j) {
      const Eigen::Vector3d r = p - body_vertices.row(j).transpose();
      const double q = r.squaredNorm() / r2;
      if (q >= 1) return;
      const double s = 1 - q;
      const double w = s * s * s;
      const Eigen::Vector3d n = body_normals.row(j).transpose();
      const double plane = n.dot(r);
      const Eigen::Vector3d dw = (-6.0 * s * s / r2) * r;  // d/dx (1 - |r|^2/R^2)^3
      n_sum += w * plane;
      d_sum += w;
      grad_n += dw * plane + w * n;
      grad_d += dw;
      if (with_hessian) {
        const Eigen::Matrix3d ddw = (-6.0 * s * s / r2) * Eigen::Matrix3d::Identity() + (24.0 * s / (r2 * r2)) * r * r.transpose();
        hess_n += ddw * plane + dw * n.transpose() + n * dw.transpose();
        hess_d += ddw;
      }
    });
    if (!(d_sum > 0)) continue;  // no vertex within R: the exact contact is the caller's
    covered[static_cast<std::size_t>(v)] = 1;
    Contact& c = out[static_cast<std::size_t>(v)];
    c.distance = n_sum / d_sum;
    c.normal = (grad_n - c.distance * grad_d) / d_sum;
    if (with_hessian)
      c.distance_hessian = (hess_n - c.normal * grad_d.transpose() - grad_d * c.normal.transpose() - c.distance * hess_d) / d_sum;
  }
  return out;
}

}  // namespace drape::collision
